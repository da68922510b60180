#include "shadow/minmax_pyramid.h"

#include <shadow/shared_constants.h>

#include "gl/program.h"

#include <algorithm>

namespace shadow {

int MinMaxPyramid::baseSize(int mapSize) {
    // A power of two, so that every level halves exactly: texel j of level k covers map texels
    // [T j, T (j + 1)) with T = SG_MINMAX_TILE * 2^k (the shader's mapping); texels past the
    // map's edge repeat the edge.
    const int tiles = std::max(1, (mapSize + SG_MINMAX_TILE - 1) / SG_MINMAX_TILE);
    int size = 1;
    while (size < tiles) size *= 2;
    return size;
}

int MinMaxPyramid::levelsFor(int mapSize, float maxFilterTexels) {
    int all = 0;
    for (int size = baseSize(mapSize); size > 0; size /= 2) ++all;
    const double widest = 2.0 * (static_cast<double>(maxFilterTexels) + 1.5);
    int needed = 1;
    for (double tile = SG_MINMAX_TILE; tile < widest; tile *= 2.0) ++needed;
    return std::clamp(needed, 1, all);
}

MinMaxPyramid MinMaxPyramid::allocate(const std::string& label, int mapSize, int layers, int levels) {
    MinMaxPyramid p;
    const int base = baseSize(mapSize);
    p.levels = levels;
    p.texture = gpu::makeTexture(label + "/minmax", GL_TEXTURE_2D_ARRAY);
    gl.TextureStorage3D(p.texture.get(), p.levels, GL_RG32F, base, base, layers);
    gl.TextureParameteri(p.texture.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    gl.TextureParameteri(p.texture.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gpu::checkGlError("allocating " + label + "/minmax");
    return p;
}

void MinMaxPyramid::clearLayer(int mapSize, int layer) const {
    const float far[2] = {1.0f, 1.0f};
    int size = baseSize(mapSize);
    for (int level = 0; level < levels; ++level, size = std::max(1, size / 2)) {
        gl.ClearTexSubImage(texture.get(), level, 0, 0, layer, size, size, 1, GL_RG, GL_FLOAT, far);
    }
}

namespace {

MinMaxBuilder::Pass makePass(const std::string& label, const std::vector<std::string>& defines) {
    MinMaxBuilder::Pass p;
    p.program = gpu::buildComputeProgram(label, "shadow_minmax.comp.glsl", defines);
    p.layer = gl.GetUniformLocation(p.program.get(), "uLayer");
    p.level = gl.GetUniformLocation(p.program.get(), "uLevel");
    return p;
}

}  // namespace

void MinMaxBuilder::build(GLuint depthArray, const MinMaxPyramid& pyramid, int mapSize, int layer) {
    if (!programs_) {
        programs_ = Programs{makePass("Shadow/MinMax/fromDepth", {"SG_MINMAX_FROM_DEPTH"}),
                             makePass("Shadow/MinMax/fromBelow", {})};
    }
    gl.BindSampler(SG_UNIT_MINMAX_SOURCE, 0);  // the textures' own nearest filtering, no comparison
    int size = MinMaxPyramid::baseSize(mapSize);
    for (int level = 0; level < pyramid.levels; ++level, size = std::max(1, size / 2)) {
        const Pass& pass = level == 0 ? programs_->fromDepth : programs_->fromBelow;
        const GLuint program = pass.program.get();
        gl.UseProgram(program);
        gl.ProgramUniform1i(program, pass.layer, layer);
        gl.ProgramUniform1i(program, pass.level, level);
        // Reads level - 1 of the pyramid (texelFetch, never the level written) or the depth map.
        gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, level == 0 ? depthArray : pyramid.texture.get());
        gl.BindImageTexture(SG_IMAGE_MINMAX, pyramid.texture.get(), level, GL_FALSE, layer, GL_WRITE_ONLY, GL_RG32F);
        const auto groups = static_cast<GLuint>((size + 7) / 8);
        gl.DispatchCompute(groups, groups, 1);
        // The next level reads this one; the lit pass samples them all.
        gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, 0);
}

}  // namespace shadow
