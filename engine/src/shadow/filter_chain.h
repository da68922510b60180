// A light's per-layer filter chain, built after a layer is drawn and cached with it: a mip
// chain (or a table) per layer of its shadow-map array, of one of four kinds.
//   - MinMax (PCF, PCSS): texel (level k) holds the least and greatest stored depth of a tile of
//     SG_MINMAX_TILE * 2^k map texels; the lookups decide "no blocker" or "only blockers" for a
//     whole filter region from four fetches.
//   - Moments (VSM): texel (level k) holds the mean stored depth and mean squared depth of
//     a tile of 2^k map texels; a trilinear fetch gives a filter region's mean and variance.
//   - FourMoments (MSM-soft): the same with the means of z, z^2, z^3 and z^4, from level 1 up
//     (its texture's level 0 is level 1: the lookups gather level 0 from the depth map).
//   - SummedMoments (VSSM): one level, a summed-area table of z and z^2 in 24-bit fixed point,
//     exact integer sums modulo 2^48 held as two 24-bit limbs per moment in RGBA32F (integers
//     below 2^24 are exact floats); any rectangle's moments come from its four corners, with no
//     float cancellation however large the table.
#pragma once

#include <shadow/components.h>

#include "core/screen_bounds.h"
#include "gl/objects.h"
#include "shadow/map_memory.h"

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace shadow {

/// One light's chain texture (an RG32F array, RGBA32F for four moments and the summed-area
/// table; one mip chain per layer, one level for the table).
struct FilterChain {
    gpu::Texture texture;
    FilterChainKind kind = FilterChainKind::MinMax;
    int levels = 0;
    /// The first level the texture holds, its level 0 (`chainStoredFrom`): level k of the chain
    /// is the texture's level k - storedFrom. 1 for moments, whose level 0 no lookup reads.
    int storedFrom = 0;
    /// Moment chains: a 2D view of each layer, through which a level's draw samples the level
    /// below alone (its base and max level set to it).
    std::vector<gpu::Texture> layerViews;

    /// `chainBaseSize` (map_memory.h): the edge of the chain's level 0.
    [[nodiscard]] static int baseSize(FilterChainKind kind, int mapSize) { return chainBaseSize(kind, mapSize); }
    /// The edge of the texture's level 0, the chain's level `storedFrom`.
    [[nodiscard]] int storedEdge(int mapSize) const { return std::max(1, baseSize(kind, mapSize) >> storedFrom); }
    /// `chainLevels` (map_memory.h).
    [[nodiscard]] static int levelsFor(ShadowTechnique t, int mapSize, float maxFilterTexels) {
        return chainLevels(t, mapSize, maxFilterTexels);
    }
    /// Allocates the chain of a `mapSize`^2 array of `layers` layers with `levels` levels.
    static FilterChain allocate(const std::string& label, FilterChainKind kind, int mapSize, int layers, int levels);
    /// Whether a cleared layer's chain is one value throughout, which clearLayer writes: not the
    /// summed-area table's, whose sums grow across the layer (a layer without casters keeps no
    /// table: its lookups read lit, ShadowLayerPlan::momentScale).
    [[nodiscard]] bool clearable() const { return kind != FilterChainKind::SummedMoments; }
    /// Every level of `layer` as for a cleared layer, nothing in front of the far plane: all 1.
    void clearLayer(int mapSize, int layer) const;
    /// Bytes of GPU memory the chain holds (`chainBytes`, what the memory budget counts).
    [[nodiscard]] long long bytes(int mapSize, int layers) const { return chainBytes(kind, mapSize, layers, levels); }
};

/// The programs that build chains, shared by every light; built on first use.
class FilterChainBuilder {
public:
    /// Builds every level of `layer` of `chain` from `depthArray`, a `mapSize`^2 array; a
    /// summed-area table of the moments of min(z momentScale, 1) (ShadowLayerPlan::momentScale).
    /// Moment chains: levels `fromLevel` (at least the first the texture holds) to `toLevel` (at
    /// most the top level); the first straight from the depth map (each texel the mean
    /// over its 2^fromLevel-texel tile), each above from the one below. The levels outside are not
    /// built (ShadowLayerPlan::chainFirstLevel, chainLastLevel). The min/max pyramid reads the
    /// depth map only within `drawn`, the texels the layer's casters may have drawn (every texel
    /// outside holds the far depth): its tiles outside are cleared to the far depth's range. Returns the depth texels the pyramid's
    /// level 0 read (0 for the other kinds).
    long long build(GLuint depthArray, const FilterChain& chain, int mapSize, int layer, float momentScale,
                    int fromLevel, int toLevel, const PixelRect& drawn);

    /// A compute program and its uniforms.
    struct Pass {
        gpu::Program program;
        GLint layer = -1, level = -1, momentScale = -1, origin = -1;
    };

private:
    long long buildMinMax(GLuint depthArray, const FilterChain& chain, int mapSize, int layer, const PixelRect& drawn);
    void buildMoments(GLuint depthArray, const FilterChain& chain, int mapSize, int layer, int fromLevel, int toLevel);
    void buildSummedArea(GLuint depthArray, const FilterChain& chain, int mapSize, int layer, float momentScale);

    /// Compute builds. The min/max pyramid: level 0 from the depth map, then each level from the
    /// one below. The summed-area table: prefix sums along rows from the depth map, then along
    /// columns in place.
    struct Programs {
        Pass fromDepth, fromBelow;
    };
    /// The compute programs of MinMax or SummedMoments, built on first use.
    const Programs& computePrograms(FilterChainKind kind);
    std::array<std::optional<Programs>, 2> computePrograms_;  ///< [summed-area table]

    /// Moment chains: a full-screen draw per level, the first built from the depth map, the others
    /// from the level below; the same programs for two and four moments (the chain's format keeps
    /// what it holds).
    struct MomentsPrograms {
        struct Pass {
            gpu::Program program;
            GLint layer = -1, level = -1;
        };
        /// From the depth map: level 1 (one gather each), a level above (a loop of gathers over
        /// each tile); a level from the one below.
        Pass fromDepthQuad, fromDepthTiles, fromBelow;
    };
    /// The moment programs (and the framebuffer they draw through), built on first use.
    const MomentsPrograms& momentsPrograms();
    std::optional<MomentsPrograms> momentsPrograms_;
    gpu::Framebuffer momentsFramebuffer_;
    gpu::VertexArray emptyVertexArray_;
};

}  // namespace shadow
