#include "shadow/map_memory.h"

#include <shadow/shadow_planner.h>
#include <shadow/shared_constants.h>

#include <algorithm>
#include <iterator>
#include <cstdint>

namespace shadow {

namespace {

/// The technique table's Chain column: None, or a kind of chain.
enum class TableChain : std::uint8_t { None, MinMax, Moments, FourMoments, SummedMoments };

std::optional<FilterChainKind> chainOf(TableChain c) {
    switch (c) {
        case TableChain::None: return std::nullopt;
        case TableChain::MinMax: return FilterChainKind::MinMax;
        case TableChain::Moments: return FilterChainKind::Moments;
        case TableChain::FourMoments: return FilterChainKind::FourMoments;
        case TableChain::SummedMoments: return FilterChainKind::SummedMoments;
    }
    return std::nullopt;
}

/// The table's Chain column, one entry per technique.
constexpr TableChain kChainColumn[] = {
#define SHADOW_TECHNIQUE_CHAIN(Enum, Constant, Name, File, Glsl, Chain, ...) TableChain::Chain,
    SHADOW_TECHNIQUE_TABLE(SHADOW_TECHNIQUE_CHAIN)
#undef SHADOW_TECHNIQUE_CHAIN
};

static_assert(std::size(kChainColumn) == kShadowTechniqueCount);

}  // namespace

std::optional<FilterChainKind> filterChainOf(ShadowTechnique t) {
    const auto i = static_cast<std::size_t>(t);
    return i < std::size(kChainColumn) ? chainOf(kChainColumn[i]) : std::nullopt;
}

int chainBaseSize(FilterChainKind kind, int mapSize) {
    if (kind != FilterChainKind::MinMax) return std::max(1, mapSize);
    // A power of two, so that every level halves exactly: texel j of level k covers map texels
    // [T j, T (j + 1)) with T = SG_MINMAX_TILE * 2^k (the shader's mapping); texels past the
    // map's edge repeat the edge.
    const int tiles = std::max(1, (mapSize + SG_MINMAX_TILE - 1) / SG_MINMAX_TILE);
    int size = 1;
    while (size < tiles) size *= 2;
    return size;
}

int chainLevels(ShadowTechnique t, int mapSize, float maxFilterTexels) {
    if (isAutomatic(maxFilterTexels)) maxFilterTexels = kMostFilterTexels;  // sized for the widest it can take
    const FilterChainKind kind = filterChainOf(t).value_or(FilterChainKind::MinMax);
    if (kind == FilterChainKind::SummedMoments) return 1;
    int all = 0;
    for (int size = chainBaseSize(kind, mapSize); size > 0; size /= 2) ++all;
    int needed = 1;
    if (kind == FilterChainKind::MinMax) {
        // A region test reads the first level whose tiles are as wide as the whole region.
        const double widest = 2.0 * (static_cast<double>(maxFilterTexels) + 1.5);
        for (double tile = SG_MINMAX_TILE; tile < widest; tile *= 2.0) ++needed;
    } else {
        // A trilinear fetch at level log2(radius in texels) reads that level's floor and ceiling;
        // level 1 at least, the first the texture holds (chainStoredFrom), whatever the map's size
        // (a level's edge is at least 1).
        for (double tile = 1.0; tile < static_cast<double>(maxFilterTexels); tile *= 2.0) ++needed;
        return std::max(std::min(needed, all), 2);
    }
    return std::clamp(needed, 1, all);
}

int chainStoredFrom(FilterChainKind kind) {
    return kind == FilterChainKind::Moments || kind == FilterChainKind::FourMoments ? 1 : 0;
}

int chainTexelBytes(FilterChainKind kind) {
    return kind == FilterChainKind::FourMoments || kind == FilterChainKind::SummedMoments ? 16 : 8;
}

std::int64_t chainBytes(FilterChainKind kind, int mapSize, int layers, int levels) {
    std::int64_t total = 0;
    std::int64_t size = std::max(1, chainBaseSize(kind, mapSize) >> chainStoredFrom(kind));
    for (int level = chainStoredFrom(kind); level < levels; ++level, size = std::max<std::int64_t>(1, size / 2)) {
        total += std::int64_t{chainTexelBytes(kind)} * size * size * layers;
    }
    return total;
}

std::int64_t depthArrayBytes(int mapSize, int layers) { return std::int64_t{4} * mapSize * mapSize * layers; }

std::int64_t shadowMapBytes(ShadowTechnique technique, int mapSize, int layers, float maxFilterTexels) {
    if (technique == ShadowTechnique::None || mapSize <= 0 || layers <= 0) return 0;
    std::int64_t bytes = depthArrayBytes(mapSize, layers);
    if (const std::optional<FilterChainKind> kind = filterChainOf(technique)) {
        bytes += chainBytes(*kind, mapSize, layers, chainLevels(technique, mapSize, maxFilterTexels));
    }
    return bytes;
}

}  // namespace shadow
