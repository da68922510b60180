#include "shadow/filter_chain.h"

#include <shadow/shared_constants.h>

#include "gl/program.h"

#include <algorithm>
#include <array>
#include <string_view>

namespace shadow {

namespace {

/// The chain's texel format (its size in bytes: chainTexelBytes).
bool fourChannels(FilterChainKind kind) {
    return kind == FilterChainKind::FourMoments || kind == FilterChainKind::SummedMoments;
}
GLenum formatOf(FilterChainKind kind) { return fourChannels(kind) ? GL_RGBA32F : GL_RG32F; }

/// Summed-area table passes: one invocation per row (or column) of the layer.
constexpr int kSatGroupSize = 64;

}  // namespace

FilterChain FilterChain::allocate(const std::string& label, FilterChainKind kind, int mapSize, int layers, int levels) {
    FilterChain c;
    const int base = baseSize(kind, mapSize);
    c.kind = kind;
    c.levels = levels;
    // Moments are filtered (trilinear: a region's mean); min/max texels and the table's limbs are
    // read one by one.
    const bool filtered = kind == FilterChainKind::Moments || kind == FilterChainKind::FourMoments;
    static constexpr std::array<const char*, 4> kSuffix{"/minmax", "/moments", "/moments", "/summed-moments"};
    c.texture = gpu::makeTexture(label + kSuffix.at(static_cast<std::size_t>(kind)), GL_TEXTURE_2D_ARRAY);
    gl.TextureStorage3D(c.texture.get(), c.levels, formatOf(kind), base, base, layers);
    gl.TextureParameteri(c.texture.get(), GL_TEXTURE_MIN_FILTER,
                         filtered ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_NEAREST);
    gl.TextureParameteri(c.texture.get(), GL_TEXTURE_MAG_FILTER, filtered ? GL_LINEAR : GL_NEAREST);
    gl.TextureParameteri(c.texture.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TextureParameteri(c.texture.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gpu::checkGlError("allocating " + label + " filter chain");
    return c;
}

void FilterChain::clearLayer(int mapSize, int layer) const {
    const float far[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    int size = baseSize(kind, mapSize);
    for (int level = 0; level < levels; ++level, size = std::max(1, size / 2)) {
        gl.ClearTexSubImage(texture.get(), level, 0, 0, layer, size, size, 1, fourChannels(kind) ? GL_RGBA : GL_RG,
                            GL_FLOAT, far);
    }
}

namespace {

FilterChainBuilder::Pass makePass(const std::string& label, const std::string& file,
                                  const std::vector<std::string>& defines) {
    FilterChainBuilder::Pass p;
    p.program = gpu::buildComputeProgram(label, file, defines);
    p.layer = gl.GetUniformLocation(p.program.get(), "uLayer");
    p.level = gl.GetUniformLocation(p.program.get(), "uLevel");
    p.momentScale = gl.GetUniformLocation(p.program.get(), "uMomentScale");
    return p;
}

}  // namespace

void FilterChainBuilder::build(GLuint depthArray, const FilterChain& chain, int mapSize, int layer, float momentScale) {
    const auto kind = static_cast<std::size_t>(chain.kind);
    std::optional<Programs>& programs = programs_.at(kind);
    if (!programs) {
        static constexpr std::array<const char*, 4> kFiles{"shadow_minmax.comp.glsl", "shadow_moments.comp.glsl",
                                                           "shadow_moments.comp.glsl", "shadow_summed_area.comp.glsl"};
        static constexpr std::array<const char*, 4> kLabels{"Shadow/MinMax/", "Shadow/Moments/", "Shadow/FourMoments/",
                                                            "Shadow/SummedMoments/"};
        std::vector<std::string> defines;
        if (chain.kind == FilterChainKind::FourMoments) defines.emplace_back("SG_FOUR_MOMENTS");
        std::vector<std::string> fromDepth = defines;
        fromDepth.emplace_back("SG_CHAIN_FROM_DEPTH");
        const std::string label = kLabels.at(kind);
        programs = Programs{makePass(label + "fromDepth", kFiles.at(kind), fromDepth),
                            makePass(label + "fromBelow", kFiles.at(kind), defines)};
    }
    gl.BindSampler(SG_UNIT_MINMAX_SOURCE, 0);  // the textures' own nearest filtering, no comparison
    if (chain.kind == FilterChainKind::SummedMoments) {
        buildSummedArea(depthArray, chain, mapSize, layer, momentScale);
        return;
    }
    int size = FilterChain::baseSize(chain.kind, mapSize);
    for (int level = 0; level < chain.levels; ++level, size = std::max(1, size / 2)) {
        const Pass& pass = level == 0 ? programs->fromDepth : programs->fromBelow;
        const GLuint program = pass.program.get();
        gl.UseProgram(program);
        gl.ProgramUniform1i(program, pass.layer, layer);
        gl.ProgramUniform1i(program, pass.level, level);
        // Reads level - 1 of the pyramid (texelFetch, never the level written) or the depth map.
        gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, level == 0 ? depthArray : chain.texture.get());
        gl.BindImageTexture(SG_IMAGE_MINMAX, chain.texture.get(), level, GL_FALSE, layer, GL_WRITE_ONLY,
                            formatOf(chain.kind));
        const auto groups = static_cast<GLuint>((size + 7) / 8);
        gl.DispatchCompute(groups, groups, 1);
        // The next level reads this one; the lit pass samples them all.
        gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, 0);
}

void FilterChainBuilder::buildSummedArea(GLuint depthArray, const FilterChain& chain, int mapSize, int layer,
                                         float momentScale) {
    const Programs& programs = *programs_.at(static_cast<std::size_t>(FilterChainKind::SummedMoments));
    const auto groups = static_cast<GLuint>((mapSize + kSatGroupSize - 1) / kSatGroupSize);
    // Rows: prefix sums of the quantised moments along x, from the depth map.
    gl.UseProgram(programs.fromDepth.program.get());
    gl.ProgramUniform1i(programs.fromDepth.program.get(), programs.fromDepth.layer, layer);
    gl.ProgramUniform1f(programs.fromDepth.program.get(), programs.fromDepth.momentScale, momentScale);
    gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, depthArray);
    gl.BindImageTexture(SG_IMAGE_MINMAX, chain.texture.get(), 0, GL_FALSE, layer, GL_READ_WRITE, formatOf(chain.kind));
    gl.DispatchCompute(groups, 1, 1);
    gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    // Columns: prefix sums of the row sums along y, in place.
    gl.UseProgram(programs.fromBelow.program.get());
    gl.DispatchCompute(groups, 1, 1);
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // the lit pass fetches the table
    gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, 0);
}

}  // namespace shadow
