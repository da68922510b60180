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
    for (int level = 0; level < p.levels; ++level) {
        GLuint view = 0;
        gl.GenTextures(1, &view);
        gl.TextureView(view, GL_TEXTURE_2D_ARRAY, p.texture.get(), GL_RG32F, static_cast<GLuint>(level), 1, 0,
                       static_cast<GLuint>(layers));
        p.levelViews.emplace_back(view);
        p.levelViews.back().label(label + "/minmax/level" + std::to_string(level));
    }
    p.framebuffer = gpu::makeFramebuffer(label + "/minmaxFramebuffer");
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

void MinMaxBuilder::build(GLuint depthArray, const MinMaxPyramid& pyramid, int mapSize, int layer) {
    const GLuint framebuffer = pyramid.framebuffer.get();
    if (!programs_) {
        Programs p;
        p.fromDepth = gpu::buildProgram(
            {"Shadow/MinMax/fromDepth", "fullscreen.vert.glsl", "shadow_minmax.frag.glsl", {"SG_MINMAX_FROM_DEPTH"}});
        p.fromBelow =
            gpu::buildProgram({"Shadow/MinMax/fromBelow", "fullscreen.vert.glsl", "shadow_minmax.frag.glsl", {}});
        p.fromDepthLayer = gl.GetUniformLocation(p.fromDepth.get(), "uLayer");
        p.fromBelowLayer = gl.GetUniformLocation(p.fromBelow.get(), "uLayer");
        GLuint vao = 0;
        gl.CreateVertexArrays(1, &vao);
        p.empty = gpu::VertexArray(vao);
        programs_ = std::move(p);
    }
    const Programs& p = *programs_;
    gl.BindVertexArray(p.empty.get());
    gl.BindSampler(SG_UNIT_MINMAX_SOURCE, 0);  // the textures' own nearest filtering, no comparison
    gl.NamedFramebufferDrawBuffer(framebuffer, GL_COLOR_ATTACHMENT0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    int size = MinMaxPyramid::baseSize(mapSize);
    for (int level = 0; level < pyramid.levels; ++level, size = std::max(1, size / 2)) {
        gl.NamedFramebufferTextureLayer(framebuffer, GL_COLOR_ATTACHMENT0, pyramid.texture.get(), level, layer);
        gl.Viewport(0, 0, size, size);
        if (level == 0) {
            gl.UseProgram(p.fromDepth.get());
            gl.ProgramUniform1i(p.fromDepth.get(), p.fromDepthLayer, layer);
            gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, depthArray);
        } else {
            gl.UseProgram(p.fromBelow.get());
            gl.ProgramUniform1i(p.fromBelow.get(), p.fromBelowLayer, layer);
            gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, pyramid.levelViews[static_cast<std::size_t>(level - 1)].get());
        }
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, 0);
}

}  // namespace shadow
