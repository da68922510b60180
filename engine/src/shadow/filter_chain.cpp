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

/// Summed-area table passes: one invocation per pair of rows (or per column) of the layer.
constexpr int kSatGroupSize = 64;

}  // namespace

FilterChain FilterChain::allocate(const std::string& label, FilterChainKind kind, int mapSize, int layers, int levels) {
    FilterChain c;
    c.kind = kind;
    c.levels = levels;
    c.storedFrom = chainStoredFrom(kind);
    const int base = c.storedEdge(mapSize);
    const int stored = c.levels - c.storedFrom;
    // Moments are filtered (trilinear: a region's mean); min/max texels and the table's limbs are
    // read one by one.
    const bool filtered = kind == FilterChainKind::Moments || kind == FilterChainKind::FourMoments;
    static constexpr std::array<const char*, 4> kSuffix{"/minmax", "/moments", "/moments", "/summed-moments"};
    c.texture = gpu::makeTexture(label + kSuffix.at(static_cast<std::size_t>(kind)), GL_TEXTURE_2D_ARRAY);
    gl.TextureStorage3D(c.texture.get(), stored, formatOf(kind), base, base, layers);
    gl.TextureParameteri(c.texture.get(), GL_TEXTURE_MIN_FILTER,
                         filtered ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_NEAREST);
    gl.TextureParameteri(c.texture.get(), GL_TEXTURE_MAG_FILTER, filtered ? GL_LINEAR : GL_NEAREST);
    gl.TextureParameteri(c.texture.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TextureParameteri(c.texture.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (filtered) {
        for (int layer = 0; layer < layers; ++layer) {
            GLuint view = 0;
            gl.GenTextures(1, &view);  // a view takes a name that has no target yet
            gl.TextureView(view, GL_TEXTURE_2D, c.texture.get(), formatOf(kind), 0, static_cast<GLuint>(stored),
                           static_cast<GLuint>(layer), 1);
            // Bilinear within the one level it shows (the mean of 2x2 texels from one fetch).
            gl.TextureParameteri(view, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            gl.TextureParameteri(view, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            gl.TextureParameteri(view, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            gl.TextureParameteri(view, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            c.layerViews.emplace_back(view);
        }
    }
    // A moment chain's levels beyond those a layer's lookups read are not built (ShadowLayerPlan's
    // chainFirstLevel, chainLastLevel), yet a trilinear fetch at the last level built reads the
    // one above with weight 0: every level starts as the far plane's moments, finite.
    if (filtered) {
        for (int layer = 0; layer < layers; ++layer) c.clearLayer(mapSize, layer);
    }
    gpu::checkGlError("allocating " + label + " filter chain");
    return c;
}

void FilterChain::clearLayer(int mapSize, int layer) const {
    const float far[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    int size = storedEdge(mapSize);
    for (int level = 0; level < levels - storedFrom; ++level, size = std::max(1, size / 2)) {
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
    p.origin = gl.GetUniformLocation(p.program.get(), "uOrigin");
    return p;
}

}  // namespace

long long FilterChainBuilder::build(GLuint depthArray, const FilterChain& chain, int mapSize, int layer,
                                    float momentScale, int fromLevel, int toLevel, const PixelRect& drawn) {
    gl.BindSampler(SG_UNIT_MINMAX_SOURCE, 0);  // the textures' own nearest filtering, no comparison
    long long read = 0;
    switch (chain.kind) {
        case FilterChainKind::MinMax: read = buildMinMax(depthArray, chain, mapSize, layer, drawn); break;
        case FilterChainKind::Moments:
        case FilterChainKind::FourMoments:
            buildMoments(depthArray, chain, mapSize, layer, fromLevel, std::min(toLevel, chain.levels - 1));
            break;
        case FilterChainKind::SummedMoments: buildSummedArea(depthArray, chain, mapSize, layer, momentScale); break;
    }
    gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, 0);
    return read;
}

const FilterChainBuilder::Programs& FilterChainBuilder::computePrograms(FilterChainKind kind) {
    const bool summed = kind == FilterChainKind::SummedMoments;
    std::optional<Programs>& programs = computePrograms_.at(summed ? 1 : 0);
    if (!programs) {
        const char* file = summed ? "shadow_summed_area.comp.glsl" : "shadow_minmax.comp.glsl";
        const std::string label = summed ? "Shadow/SummedMoments/" : "Shadow/MinMax/";
        programs = Programs{makePass(label + "fromDepth", file, {"SG_CHAIN_FROM_DEPTH"}),
                            makePass(label + "fromBelow", file, {})};
    }
    return *programs;
}

long long FilterChainBuilder::buildMinMax(GLuint depthArray, const FilterChain& chain, int mapSize, int layer,
                                          const PixelRect& drawn) {
    long long read = 0;
    const Programs& programs = computePrograms(FilterChainKind::MinMax);
    int size = FilterChain::baseSize(chain.kind, mapSize);
    // The tiles of each level that hold a drawn texel; the others hold the far depth's range.
    // Tiles past the map's edge read its edge texels (the gathers clamp): built with them.
    const auto end = [mapSize](int drawnEnd, int tile, int levelSize) {
        return drawnEnd >= mapSize ? levelSize : std::min((drawnEnd + tile - 1) / tile, levelSize);
    };
    int tile = SG_MINMAX_TILE;
    for (int level = 0; level < chain.levels; ++level, size = std::max(1, size / 2), tile *= 2) {
        const int x0 = drawn.x0 / tile, y0 = drawn.y0 / tile;
        const int x1 = end(drawn.x1, tile, size), y1 = end(drawn.y1, tile, size);
        if (drawn.empty() || x0 > 0 || y0 > 0 || x1 < size || y1 < size) {
            const std::array<float, 2> far{1.0f, 1.0f};
            gl.ClearTexSubImage(chain.texture.get(), level, 0, 0, layer, size, size, 1, GL_RG, GL_FLOAT, far.data());
        }
        if (drawn.empty()) continue;
        if (level == 0) read = static_cast<long long>(x1 - x0) * (y1 - y0) * tile * tile;
        const Pass& pass = level == 0 ? programs.fromDepth : programs.fromBelow;
        const GLuint program = pass.program.get();
        gl.UseProgram(program);
        gl.ProgramUniform1i(program, pass.layer, layer);
        gl.ProgramUniform1i(program, pass.level, level);
        gl.ProgramUniform2i(program, pass.origin, x0, y0);
        // Reads level - 1 of the pyramid (texelFetch, never the level written) or the depth map.
        gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, level == 0 ? depthArray : chain.texture.get());
        gl.BindImageTexture(SG_IMAGE_MINMAX, chain.texture.get(), level, GL_FALSE, layer, GL_WRITE_ONLY,
                            formatOf(chain.kind));
        gl.DispatchCompute(static_cast<GLuint>((x1 - x0 + 7) / 8), static_cast<GLuint>((y1 - y0 + 7) / 8), 1);
        // The next level reads this one (and its cleared tiles); the lit pass samples them all.
        gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    }
    return read;
}

void FilterChainBuilder::buildMoments(GLuint depthArray, const FilterChain& chain, int mapSize, int layer,
                                      int fromLevel, int toLevel) {
    const MomentsPrograms& programs = momentsPrograms();
    const GLuint fb = momentsFramebuffer_.get();
    const GLuint view = chain.layerViews.at(static_cast<std::size_t>(layer)).get();
    gl.Disable(GL_DEPTH_TEST);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fb);
    gl.BindVertexArray(emptyVertexArray_.get());
    // Chain levels; the texture's are storedFrom lower, and nothing below its level 0 is drawn.
    const int base = chain.storedFrom;
    fromLevel = std::max(fromLevel, base);
    for (int level = fromLevel; level <= toLevel; ++level) {
        const int size = std::max(1, mapSize >> level);
        const bool fromMap = level == fromLevel;
        const MomentsPrograms::Pass& pass = !fromMap     ? programs.fromBelow
                                            : level == 1 ? programs.fromDepthQuad
                                                         : programs.fromDepthTiles;
        gl.UseProgram(pass.program.get());
        if (fromMap) {
            gl.ProgramUniform1i(pass.program.get(), pass.layer, layer);
            gl.ProgramUniform1i(pass.program.get(), pass.level, level);
            gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, depthArray);
        } else {
            // The view shows the level below alone, so the level drawn is not one it samples.
            gl.TextureParameteri(view, GL_TEXTURE_BASE_LEVEL, level - 1 - base);
            gl.TextureParameteri(view, GL_TEXTURE_MAX_LEVEL, level - 1 - base);
            gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, view);
        }
        gl.NamedFramebufferTextureLayer(fb, GL_COLOR_ATTACHMENT0, chain.texture.get(), level - base, layer);
        gl.Viewport(0, 0, size, size);
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    gl.TextureParameteri(view, GL_TEXTURE_BASE_LEVEL, 0);
    gl.TextureParameteri(view, GL_TEXTURE_MAX_LEVEL, chain.levels - 1 - base);
    gl.BindVertexArray(0);
    gl.NamedFramebufferTextureLayer(fb, GL_COLOR_ATTACHMENT0, 0, 0, 0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

const FilterChainBuilder::MomentsPrograms& FilterChainBuilder::momentsPrograms() {
    std::optional<MomentsPrograms>& p = momentsPrograms_;
    if (!p) {
        const auto make = [&](const char* stage, std::vector<std::string> defines) {
            MomentsPrograms::Pass pass;
            pass.program = gpu::buildProgram({std::string("Shadow/Moments/") + stage, "fullscreen.vert.glsl",
                                              "shadow_moments.frag.glsl", std::move(defines)});
            pass.layer = gl.GetUniformLocation(pass.program.get(), "uLayer");
            pass.level = gl.GetUniformLocation(pass.program.get(), "uLevel");
            return pass;
        };
        p = MomentsPrograms{make("fromDepthQuad", {"SG_CHAIN_FROM_DEPTH", "SG_CHAIN_TILE 2"}),
                            make("fromDepthTiles", {"SG_CHAIN_FROM_DEPTH", "SG_CHAIN_TILE 0"}), make("fromBelow", {})};
    }
    if (!momentsFramebuffer_) {
        momentsFramebuffer_ = gpu::makeFramebuffer("Shadow/moments framebuffer");
        emptyVertexArray_ = gpu::makeVertexArray("Shadow/moments vertex array");
    }
    return *p;
}

void FilterChainBuilder::buildSummedArea(GLuint depthArray, const FilterChain& chain, int mapSize, int layer,
                                         float momentScale) {
    const Programs& programs = computePrograms(FilterChainKind::SummedMoments);
    const auto groups = static_cast<GLuint>((mapSize + kSatGroupSize - 1) / kSatGroupSize);
    const auto rowPairGroups = static_cast<GLuint>(((mapSize + 1) / 2 + kSatGroupSize - 1) / kSatGroupSize);
    // Rows: prefix sums of the quantised moments along x, from the depth map, two rows per
    // invocation.
    gl.UseProgram(programs.fromDepth.program.get());
    gl.ProgramUniform1i(programs.fromDepth.program.get(), programs.fromDepth.layer, layer);
    gl.ProgramUniform1f(programs.fromDepth.program.get(), programs.fromDepth.momentScale, momentScale);
    gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, depthArray);
    gl.BindImageTexture(SG_IMAGE_MINMAX, chain.texture.get(), 0, GL_FALSE, layer, GL_READ_WRITE, formatOf(chain.kind));
    gl.DispatchCompute(rowPairGroups, 1, 1);
    gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    // Columns: prefix sums of the row sums along y, in place.
    gl.UseProgram(programs.fromBelow.program.get());
    gl.DispatchCompute(groups, 1, 1);
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // the lit pass fetches the table
}

}  // namespace shadow
