// The min/max depth pyramid of a light's shadow-map array: per layer, a mip chain whose texel
// (level k) holds the least and greatest stored depth of a tile of SG_MINMAX_TILE * 2^k map
// texels. Built after a layer is drawn, cached with it. PCF and PCSS read it to decide "no
// blocker" or "only blockers" for a whole filter region from four fetches.
#pragma once

#include "gl/objects.h"

#include <optional>
#include <string>
#include <vector>

namespace shadow {

/// The programs that build pyramids, shared by every light; built on first use.
class MinMaxBuilder {
public:
    /// Builds every level of `layer` of `pyramid` from `depthArray`, a `mapSize`^2 array.
    void build(GLuint depthArray, const struct MinMaxPyramid& pyramid, int mapSize, int layer);

    /// A compute program and its uniforms.
    struct Pass {
        gpu::Program program;
        GLint layer = -1, level = -1;
    };

private:
    struct Programs {
        Pass fromDepth, fromBelow;
    };
    std::optional<Programs> programs_;
};

/// One light's pyramid texture (RG32F array, one mip chain per layer).
struct MinMaxPyramid {
    gpu::Texture texture;
    int levels = 0;

    /// Edge of level 0 for a map of `mapSize` texels: the power of two of at least
    /// mapSize / SG_MINMAX_TILE texels.
    [[nodiscard]] static int baseSize(int mapSize);
    /// Levels a lookup of at most `maxFilterTexels` texels of radius can use: the first whose
    /// tiles are as wide as the widest region (2 * (maxFilterTexels + 1.5) texels), and those below.
    [[nodiscard]] static int levelsFor(int mapSize, float maxFilterTexels);
    /// Allocates the pyramid of a `mapSize`^2 array of `layers` layers with `levels` levels.
    static MinMaxPyramid allocate(const std::string& label, int mapSize, int layers, int levels);
    /// Sets every level of `layer` to (1, 1): a cleared layer, nothing in front of the far plane.
    void clearLayer(int mapSize, int layer) const;
};

}  // namespace shadow
