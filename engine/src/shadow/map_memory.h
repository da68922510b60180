// What a light's maps take: the filter chain its technique reads, that chain's levels and sizes,
// and the bytes of depth and chain together. Pure CPU: the planner budgets with it
// (ShadowLimits::maxShadowBytes) and the shadow maps allocate by it (filter_chain.h), so the
// budget counts exactly what is allocated.
#pragma once

#include <shadow/components.h>

#include <cstdint>
#include <optional>

namespace shadow {

/// What a filter chain holds (filter_chain.h).
enum class FilterChainKind : std::uint8_t { MinMax, Moments, FourMoments, SummedMoments };

/// The chain technique `t` reads, or nullopt when it reads none (no memory is spent on one).
[[nodiscard]] std::optional<FilterChainKind> filterChainOf(ShadowTechnique t);

/// Edge of level 0 for a map of `mapSize` texels: for MinMax the power of two of at least
/// mapSize / SG_MINMAX_TILE texels (each level halves exactly), for moments and the summed-area
/// table the map's own.
[[nodiscard]] int chainBaseSize(FilterChainKind kind, int mapSize);

/// Levels technique `t`'s lookups of at most `maxFilterTexels` texels of radius read. MinMax:
/// the first whose tiles are as wide as the widest region (2 * (maxFilterTexels + 1.5) texels),
/// and those below; moments: up to ceil(log2(radius)), at least 2; the summed-area table is one
/// level.
[[nodiscard]] int chainLevels(ShadowTechnique t, int mapSize, float maxFilterTexels);

/// The first level of a chain of `kind` that its texture holds (the texture's level 0): 1 for
/// moments (VSM, MSM-soft, whose lookups take level 0 from a gather of the depth map), else 0.
[[nodiscard]] int chainStoredFrom(FilterChainKind kind);

/// Bytes of one texel of a chain of `kind` (RG32F, or RGBA32F for four moments and the table).
[[nodiscard]] int chainTexelBytes(FilterChainKind kind);

/// Bytes of a chain of `kind` with `levels` levels for `layers` layers of a `mapSize`^2 map: the
/// levels from `chainStoredFrom` up.
[[nodiscard]] std::int64_t chainBytes(FilterChainKind kind, int mapSize, int layers, int levels);

/// Bytes of a depth array of `layers` layers of `mapSize`^2 texels (GL_DEPTH_COMPONENT32F).
[[nodiscard]] std::int64_t depthArrayBytes(int mapSize, int layers);

}  // namespace shadow
