// ShadowMaps: the GPU "do" phase. Each shadowed light owns one GL_TEXTURE_2D_ARRAY of
// GL_DEPTH_COMPONENT32F layers holding linear depth (see shaders/shadow_depth.frag.glsl).
#include <shadow/context.h>
#include <shadow/mesh_cache.h>
#include <shadow/shadow_maps.h>
#include <shadow/shared_constants.h>

#include "core/screen_bounds.h"
#include "gl/gl_state.h"
#include "gl/mesh_cache_access.h"
#include "gl/no_throw.h"
#include "gl/objects.h"
#include "gl/pass_timer.h"
#include "gl/program.h"
#include "shadow/distance_field_atlas.h"
#include "shadow/filter_chain.h"
#include "shadow/map_memory.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>

namespace shadow {

namespace {

/// One shadowed light's depth texture array and the framebuffer its layers are drawn through.
struct ShadowMapGpu {
    gpu::Texture array;
    gpu::Framebuffer framebuffer;
    int mapSize = 0;
    int layers = 0;
    /// Per layer: stored depth -> metres, as last drawn (readLayerDepth).
    std::vector<float> depthScales;
    /// For the techniques that read one only (filterChainOf); `chainCurrent[k]` once layer k's
    /// chain matches its map.
    std::optional<FilterChain> chain;
    std::vector<bool> chainCurrent;
    /// Per layer: the lowest and highest levels its chain was last built for
    /// (ShadowLayerPlan::chainFirstLevel, chainLastLevel).
    std::vector<int> chainFirstLevel;
    std::vector<int> chainLastLevel;
    /// Per layer: the texels that may hold a depth other than the far depth (its casters' and
    /// backgrounds' since it was last cleared; the whole layer when allocated). Every texel
    /// outside holds the far depth, so a redraw clears these alone (a spot map's caster covers
    /// a small part of it, and a full clear of a 2048^2 layer cost a quarter of the bunny's
    /// shadow pass on llvmpipe), and a min/max pyramid reads these alone (a layer with a
    /// pyramid has no backgrounds: its casters' texels).
    std::vector<PixelRect> writtenTexels;
    /// Made this frame (a new light, or a new map size or layer count): its texture name changed.
    bool allocatedThisFrame = true;
};

/// A depth-only program of the shadow pass, shared by every light type: the nearest depth, or
/// (`defines` SG_DEPTH_BEHIND_FIRST …) the second pass of a second-depth mode; with
/// SG_ALPHA_TESTED, for cut-out casters; each also built for skinned and morphed casters
/// (gpu::appendDeformDefines), when a layer first draws one.
struct DepthProgram {
    gpu::Program program;
    GLint lightFromLocal = -1;
    GLint clipFromLight = -1;
    GLint depthScale = -1;
    GLint orthographic = -1;
    GLint firstPass = -1;  ///< the second-depth programs only
    gpu::DeformUniforms deform;
    GLint alpha = -1;        ///< the alpha-tested programs only
    GLint alphaCutoff = -1;  ///< likewise
    GLint layerIndex = -1;   ///< the background programs only: the layer of uCasters

    DepthProgram(std::string label, std::vector<std::string> defines) {
        program = gpu::buildProgram(
            {std::move(label), "shadow_depth.vert.glsl", "shadow_depth.frag.glsl", std::move(defines)});
        lightFromLocal = gl.GetUniformLocation(program.get(), "uLightFromLocal");
        clipFromLight = gl.GetUniformLocation(program.get(), "uClipFromLight");
        depthScale = gl.GetUniformLocation(program.get(), "uDepthScale");
        orthographic = gl.GetUniformLocation(program.get(), "uOrthographic");
        firstPass = gl.GetUniformLocation(program.get(), "uFirstPass");
        deform = gpu::DeformUniforms::of(program.get());
        alpha = gl.GetUniformLocation(program.get(), "uAlpha");
        alphaCutoff = gl.GetUniformLocation(program.get(), "uAlphaCutoff");
        layerIndex = gl.GetUniformLocation(program.get(), "uLayer");
    }

    /// Sets the layer's uniforms and makes the program current; `first`: the first of a
    /// second-depth mode's two passes.
    void use(const ShadowLayerPlan& layer, bool first = false) const {
        const GLuint name = program.get();
        gl.UseProgram(name);
        if (firstPass >= 0) gl.ProgramUniform1i(name, firstPass, first ? 1 : 0);
        gl.ProgramUniformMatrix4fv(name, clipFromLight, 1, GL_FALSE, glm::value_ptr(glm::mat4(layer.clipFromLight)));
        gl.ProgramUniform1f(name, depthScale, layer.depthScale);
        gl.ProgramUniform1i(name, orthographic, layer.orthographic ? 1 : 0);
    }
};

/// The nearest depth of the layer being drawn in a second-depth mode, which its second pass
/// reads: one 2D depth texture shared by every light, grown to the largest map that needed it.
struct NearestScratch {
    gpu::Texture texture;
    gpu::Framebuffer framebuffer;
    int size = 0;

    void reserve(int mapSize) {
        if (size >= mapSize) return;
        texture = gpu::makeTexture("Shadow/nearest scratch", GL_TEXTURE_2D);
        gl.TextureStorage2D(texture.get(), 1, GL_DEPTH_COMPONENT32F, mapSize, mapSize);
        gl.TextureParameteri(texture.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl.TextureParameteri(texture.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        framebuffer = gpu::makeFramebuffer("Shadow/nearest scratch framebuffer");
        gl.NamedFramebufferTexture(framebuffer.get(), GL_DEPTH_ATTACHMENT, texture.get(), 0);
        gl.NamedFramebufferDrawBuffer(framebuffer.get(), GL_NONE);
        gl.NamedFramebufferReadBuffer(framebuffer.get(), GL_NONE);
        size = mapSize;
        gpu::checkGlError("allocating the nearest-depth scratch");
    }

    [[nodiscard]] long long bytes() const { return depthArrayBytes(size, size > 0 ? 1 : 0); }
};

/// Builds into `p` the depth program `label` with `defines`, for cut-out casters (`cutout`) and
/// casters deformed as `deform` says (gpu::MeshDeformBits) too.
void makeDepthProgram(std::optional<DepthProgram>& p, std::string label, std::vector<std::string> defines, bool cutout,
                      unsigned deform) {
    if (cutout) {
        defines.emplace_back("SG_ALPHA_TESTED");
        label += "/alpha";
    }
    label += gpu::deformLabel(deform);
    gpu::appendDeformDefines(deform, defines);
    p.emplace(std::move(label), std::move(defines));
}

std::unique_ptr<ShadowMapGpu> allocate(const ShadowLightPlan& plan) {
    auto map = std::make_unique<ShadowMapGpu>();
    const std::string label = "Shadow/" + plan.name;
    map->mapSize = plan.mapSize;
    map->layers = static_cast<int>(plan.layers.size());
    map->depthScales.assign(plan.layers.size(), 1.0f);
    map->writtenTexels.assign(plan.layers.size(), PixelRect{0, 0, map->mapSize, map->mapSize});
    map->array = gpu::makeTexture(label + "/array", GL_TEXTURE_2D_ARRAY);
    gl.TextureStorage3D(map->array.get(), 1, GL_DEPTH_COMPONENT32F, map->mapSize, map->mapSize, map->layers);
    gl.TextureParameteri(map->array.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TextureParameteri(map->array.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TextureParameteri(map->array.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);  // the pyramid's gathers
    gl.TextureParameteri(map->array.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    map->framebuffer = gpu::makeFramebuffer(label + "/framebuffer");
    gl.NamedFramebufferDrawBuffer(map->framebuffer.get(), GL_NONE);
    gl.NamedFramebufferReadBuffer(map->framebuffer.get(), GL_NONE);
    gpu::checkGlError("allocating " + label);
    return map;
}

/// Sets `out` to the name of pass `what`<k> of `plan`'s map, e.g. "Shadow/sun/layer0". Into a
/// string kept from frame to frame: building names anew would allocate every frame.
void formatPassName(std::string& out, const ShadowLightPlan& plan, std::string_view what, std::size_t k) {
    char index[24];
    char* end = std::to_chars(index, index + sizeof(index), k).ptr;
    out.assign("Shadow/").append(plan.name).append("/").append(what).append(index, end);
}

/// Draws a caster of the game's own (`ShadowCasterDraw`) into the layer of `context`.
void drawOwnCaster(const ShadowCasterDraw& own, const WorldTransform& wt, const CasterDrawContext& context) {
    if (own.draw) {
        own.draw(context);
        gl.UseProgram(context.program.name);  // the callback may have used its own,
        gl.Disable(GL_CULL_FACE);             // and culled faces: off, as it was called
        return;
    }
    context.setWorldFromLocal(wt.worldFromLocal);
    gl.BindVertexArray(own.vertexArray.name);
    gl.DrawElementsBaseVertex(
        GL_TRIANGLES, own.indexCount, static_cast<GLenum>(own.indexType),
        reinterpret_cast<const void*>(own.indexOffset),  // NOLINT(performance-no-int-to-ptr): GL's offset
        own.baseVertex);
}

/// Depth-only state of the shadow passes.
void beginDepthOnly() {
    gpu::setPassDefaults();
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.DepthMask(GL_TRUE);
    gl.Disable(GL_CULL_FACE);  // open meshes (planes) cast from both sides
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
}

void endDepthOnly() {
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.BindVertexArray(0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

/// Fills what `ls` says of `plan` before any layer is drawn (its strings keep their storage).
void describe(const ShadowLightPlan& plan, LightShadowStats& ls) {
    ls.sceneIndex = plan.sceneIndex;
    ls.name.assign(plan.name);
    ls.type.assign(lightTypeName(plan.light.type));
    ls.technique.assign(techniqueName(plan.technique()));
    ls.mapSize = plan.mapSize;
    ls.requestedMapSize = plan.settings.technique != ShadowTechnique::None ? plan.settings.mapSize : 0;
    ls.layers = static_cast<int>(plan.layers.size());
    ls.affectsView = plan.affectsView;
    ls.regionTest = plan.regionTest;
    ls.automatic = plan.automatic;
    ls.pcfRadiusMetres = plan.pcfRadiusMetres;
    ls.maxFilterTexels = plan.maxFilterTexels;
    ls.pcfSamples = plan.settings.pcfSamples;
    ls.blockerSamples = plan.settings.blockerSamples;
    ls.autoChoice = plan.autoChoice;
}

}  // namespace

struct ShadowMaps::Impl {
    DepthProgram depth{"Shadow/Depth", {}};
    /// The other depth programs, by depth mode (`DepthMode`), alpha test (0 opaque, 1 cut-out)
    /// and deformation (gpu::MeshDeformBits), built when a layer first needs one (the nearest,
    /// opaque, rigid one is `depth`).
    std::array<std::array<std::array<std::optional<DepthProgram>, gpu::kMeshDeforms>, 2>, 3> others;
    /// The background programs (SG_DEPTH_BACKGROUND), likewise by alpha test and deformation.
    std::array<std::array<std::optional<DepthProgram>, gpu::kMeshDeforms>, 2> backgroundPrograms;
    /// Copies the backgrounds into a layer (shadow_background.frag.glsl), with the vertex array
    /// its one triangle is drawn with; made when a layer first has backgrounds.
    std::optional<gpu::Program> copyBackground;
    gpu::VertexArray emptyVertexArray;
    NearestScratch scratch;
    /// The distance fields of the sdf lights' casters, made when a light first uses sdf.
    std::optional<gpu::DistanceFieldAtlas> fields;
    FilterChainBuilder chains;
    gpu::PassTimer timer;
    std::string passName;  ///< the name of the pass being timed (see `formatPassName`)
    /// Per scene light (index = `ShadowFrame::lights`): its map, or null without one.
    std::vector<std::pair<Entity, std::unique_ptr<ShadowMapGpu>>> maps;
    /// Last frame's `maps` while `syncMaps` moves them to this frame's slots; empty otherwise.
    std::vector<std::pair<Entity, std::unique_ptr<ShadowMapGpu>>> lastMaps;

    std::vector<Warning> pending;  ///< host errors of the calls without a FrameStats

    explicit Impl(bool softwareRenderer) : timer(softwareRenderer) {}

    /// Gives every light of `frame` with a map an array of its size, reusing last frame's.
    void syncMaps(const ShadowFrame& frame);
    /// Draws layer `k` of `plan`'s map: its casters, depth only (twice in a second-depth mode).
    void drawLayer(const World& world, MeshCache& meshes, const ShadowLightPlan& plan, std::size_t k,
                   LightShadowStats& ls);
    /// The program of depth mode `mode` (the second pass's for Midpoint and Second), opaque or
    /// alpha-tested, for casters deformed as `deform` says, built on first use.
    const DepthProgram& program(DepthMode mode, bool cutout, unsigned deform = 0);
    /// The background program for opaque or cut-out meshes deformed as `deform` says.
    const DepthProgram& backgroundProgram(bool cutout, unsigned deform);
    /// Fills the texels of layer `k` of `plan`'s map that hold no caster with the farthest of its
    /// backgrounds (ShadowLayerPlan::backgrounds), within a lookup's reach of `casterTexels`,
    /// those its casters can have drawn; called with the layer drawn and bound. Returns the
    /// texels it may have written.
    PixelRect drawBackgrounds(const World& world, MeshCache& meshes, const ShadowLightPlan& plan, std::size_t k,
                              const PixelRect& casterTexels, LightShadowStats& ls);
    /// Brings the filter chain of every layer of `plan` whose map changed up to date.
    void updateChains(const ShadowLightPlan& plan, LightShadowStats& ls);
};

void ShadowMaps::Impl::syncMaps(const ShadowFrame& frame) {
    // The two lists trade places every frame, so their storage is reused: only maps move.
    std::swap(maps, lastMaps);
    maps.clear();
    maps.resize(frame.lights.size());
    for (std::size_t i = 0; i < frame.lights.size(); ++i) {
        const ShadowLightPlan& plan = frame.lights[i];
        maps[i].first = plan.entity;
        if (!plan.hasMap()) continue;
        auto it = std::find_if(lastMaps.begin(), lastMaps.end(),
                               [&](const auto& m) { return m.second && m.first == plan.entity; });
        std::unique_ptr<ShadowMapGpu> map = it != lastMaps.end() ? std::move(it->second) : nullptr;
        if (!map || map->mapSize != plan.mapSize || map->layers != static_cast<int>(plan.layers.size())) {
            map = allocate(plan);
        } else {
            map->allocatedThisFrame = false;
        }
        const std::optional<FilterChainKind> kind = shadow::filterChainOf(plan.technique());
        if (!kind) {
            map->chain.reset();  // no technique of the light reads one: no memory for it
        } else if (const int levels =
                       FilterChain::levelsFor(plan.technique(), map->mapSize, plan.settings.maxFilterTexels);
                   !map->chain || map->chain->kind != *kind || map->chain->levels != levels) {
            map->chain = FilterChain::allocate("Shadow/" + plan.name, *kind, map->mapSize, map->layers, levels);
            map->chainCurrent.assign(static_cast<std::size_t>(map->layers), false);
            map->chainFirstLevel.assign(static_cast<std::size_t>(map->layers), 0);
            map->chainLastLevel.assign(static_cast<std::size_t>(map->layers), 0);
        }
        maps[i].second = std::move(map);
    }
    lastMaps.clear();  // the maps of lights gone or without a map this frame
}

void ShadowMaps::Impl::updateChains(const ShadowLightPlan& plan, LightShadowStats& ls) {
    ShadowMapGpu& map = *maps[static_cast<std::size_t>(plan.sceneIndex)].second;
    if (!map.chain) return;
    for (std::size_t k = 0; k < plan.layers.size(); ++k) {
        // A layer's moment scale follows its matrices and its casters' bounds, whose changes
        // mark it dirty: a clean layer's table holds the scale of this frame's plan.
        // So do its first and last levels, but with the receivers too: a clean layer whose
        // lookups now reach beyond the levels built has its chain built again.
        const int firstLevel = plan.layers[k].chainFirstLevel;
        const int lastLevel = plan.layers[k].chainLastLevel;
        if (!plan.layers[k].dirty && map.chainCurrent[k] && map.chainFirstLevel[k] <= firstLevel &&
            map.chainLastLevel[k] >= lastLevel)
            continue;
        if (map.chain->kind == FilterChainKind::MinMax && !plan.regionTest) {
            // Not read this frame (ShadowLimits::pyramidTexelsPerPixel): built when it next is.
            map.chainCurrent[k] = false;
            continue;
        }
        // From the first level read, drawn straight from the depth map.
        if (plan.layers[k].casters.empty()) {
            // Nothing in front of the far plane. A summed-area table is left as it is: the
            // layer's moment scale 0 has its lookups read lit (ShadowLayerPlan::momentScale).
            if (map.chain->clearable()) map.chain->clearLayer(map.mapSize, static_cast<int>(k));
        } else {
            formatPassName(passName, plan, map.chain->kind == FilterChainKind::MinMax ? "minmax" : "moments", k);
            const gpu::ScopedPass pass(timer, passName);
            ls.pyramidTexelsRead +=
                chains.build(map.array.get(), *map.chain, map.mapSize, static_cast<int>(k), plan.layers[k].momentScale,
                             firstLevel, lastLevel,
                             map.chain->kind == FilterChainKind::MinMax ? map.writtenTexels[k]
                                                                        : PixelRect{0, 0, map.mapSize, map.mapSize});
        }
        map.chainCurrent[k] = true;
        map.chainFirstLevel[k] = firstLevel;
        map.chainLastLevel[k] = lastLevel;
    }
}

const DepthProgram& ShadowMaps::Impl::program(DepthMode mode, bool cutout, unsigned deform) {
    if (mode == DepthMode::Nearest && !cutout && deform == 0) return depth;
    std::optional<DepthProgram>& p = others[static_cast<std::size_t>(mode)][cutout ? 1 : 0][deform];
    if (!p) {
        std::vector<std::string> defines;
        std::string label = "Shadow/Depth";
        if (mode != DepthMode::Nearest) defines.emplace_back("SG_DEPTH_BEHIND_FIRST");
        if (mode == DepthMode::Midpoint) defines.emplace_back("SG_DEPTH_MIDPOINT");
        if (mode != DepthMode::Nearest) label += mode == DepthMode::Midpoint ? "/midpoint" : "/second";
        makeDepthProgram(p, std::move(label), std::move(defines), cutout, deform);
    }
    return *p;
}

const DepthProgram& ShadowMaps::Impl::backgroundProgram(bool cutout, unsigned deform) {
    std::optional<DepthProgram>& p = backgroundPrograms[cutout ? 1 : 0][deform];
    if (!p) makeDepthProgram(p, "Shadow/Depth/background", {"SG_DEPTH_BACKGROUND"}, cutout, deform);
    return *p;
}

namespace {

/// The faces of a solid caster (`MeshData::solid`, `ShadowCasterDraw::solid`) a nearest-depth
/// layer may cull, for object transform `worldFromLocal` and object bounds `localBounds`:
/// GL_BACK, or GL_FRONT where the transform and the projection together mirror its winding; 0
/// (cull none) where its bounds reach in front of the layer's near plane, whose rays could then
/// start inside it and meet a back face first (a light inside a box, a cascade's near plane
/// through a caster).
GLenum solidCulledFaces(const ShadowLayerPlan& layer, const glm::dmat4& worldFromLocal, const Aabb& localBounds) {
    const glm::dmat4 lightFromLocal = layer.lightFromWorld * worldFromLocal;
    // Clip z + w, affine in light-view coordinates, is positive beyond the near plane: its least
    // value over the caster's light-view box, with a margin for the float clipping of vertices.
    const DAabb box = transformBounds(lightFromLocal, localBounds);
    if (box.empty()) return 0;
    const glm::dmat4& p = layer.clipFromLight;
    double least = p[3][2] + p[3][3];
    double scale = std::abs(least);
    for (int axis = 0; axis < 3; ++axis) {
        const double k = p[axis][2] + p[axis][3];
        least += k * (k > 0.0 ? box.min[axis] : box.max[axis]);
        scale += std::abs(k * box.min[axis]) + std::abs(k * box.max[axis]);
    }
    if (!(least > 1e-5 * scale)) return 0;
    // A face towards the light: counter-clockwise in the window when the projection keeps the
    // orientation of the view's x-y plane (the light looks down -Z) and the transform does not
    // mirror.
    const double mirror = glm::determinant(glm::dmat3(lightFromLocal)) * (p[0][0] * p[1][1] - p[1][0] * p[0][1]);
    if (!(std::abs(mirror) > 0.0)) return 0;
    return mirror > 0.0 ? GL_BACK : GL_FRONT;
}

/// The texels of a `mapSize`^2 layer that a caster within world bounds `box` can draw: its
/// projection (`projectedBounds`) one texel wider on each side; the whole layer without bounds.
PixelRect casterTexels(const ShadowLayerPlan& layer, int mapSize, const DAabb* box) {
    if (box == nullptr) return {0, 0, mapSize, mapSize};
    if (box->empty()) return {};
    return grownWithin(projectedBounds(layer.clipFromLight * layer.lightFromWorld, *box, mapSize, mapSize), 1, mapSize,
                       mapSize);
}

/// The faces culled in a depth pass, set only when they change (0: none, as beginDepthOnly
/// leaves it).
struct FaceCulling {
    GLenum faces = 0;
    /// Culls the faces `to` (0: none) from the next draw on; true when some are culled.
    bool set(GLenum to) {
        if (to != faces) {
            if (to == 0) {
                gl.Disable(GL_CULL_FACE);
            } else {
                if (faces == 0) gl.Enable(GL_CULL_FACE);
                gl.CullFace(to);
            }
            faces = to;
        }
        return faces != 0;
    }
};

/// What a layer's caster draws are told and tell back.
struct CasterPass {
    /// A nearest-depth layer: a rigid, opaque solid mesh (or a game's solid indexed draw) is
    /// drawn with its back faces culled (`solidCulledFaces`), counted in `culled`.
    bool cullSolids = false;
    /// The texels the casters may draw gathered in `texels` (`casterTexels`, within `within`,
    /// the caller enabling the scissor test): the layer holds nothing beyond them
    /// (writtenTexels, the min/max pyramid's region). A game's caster (ShadowCasterDraw), whose
    /// bounds are the game's word, is scissored to its own texels, so that one that draws
    /// beyond them (which the planner culls it by) leaves no depth a redraw would not clear;
    /// a mesh's bounds are the module's own, and its draws are not (a scissor per draw cost
    /// `courtyard`'s 251 caster draws 2-4 ms of a 137 ms shadow pass in 3 paired runs).
    bool gatherTexels = false;
    PixelRect within{0, 0, std::numeric_limits<int>::max(), std::numeric_limits<int>::max()};
    int mapSize = 0;
    int culled = 0;
    PixelRect texels;
    PixelRect scissor;  ///< as last set (none yet: empty)
    FaceCulling cull;

    /// Before a caster's draw (object transform `worldFromLocal`, object bounds `localBounds`,
    /// `gameBounds` when they are a game's): culls its faces when `solid` (`solidCulledFaces`)
    /// and, when gathering, adds the texels it can draw, its world box from `worldBox()` (an
    /// optional: none when unknown), asked for only then.
    template <class WorldBox>
    void prepare(const ShadowLayerPlan& layer, bool solid, const glm::dmat4& worldFromLocal, const Aabb& localBounds,
                 bool gameBounds, WorldBox worldBox) {
        culled += cull.set(solid ? solidCulledFaces(layer, worldFromLocal, localBounds) : 0) ? 1 : 0;
        if (!gatherTexels) return;
        const std::optional<DAabb> box = worldBox();
        const PixelRect own = intersect(casterTexels(layer, mapSize, box ? &*box : nullptr), within);
        texels = unite(texels, own);
        const PixelRect to = gameBounds ? own : within;
        if (to == scissor) return;
        gl.Scissor(to.x0, to.y0, std::max(to.x1 - to.x0, 0), std::max(to.y1 - to.y0, 0));
        scissor = to;
    }
};

/// Draws `casters` (a list of `layer`'s) into the bound framebuffer, with `opaque` (current, its layer
/// uniforms set: the rigid, opaque program) or, for a cut-out or deformed caster,
/// `programFor(cutout, deform)` (made current and set up here); `first`: the first pass of a
/// second-depth mode. A skinned caster
/// is drawn in its pose. `pass` says whether solids are culled and gathers what was drawn.
/// Returns the draw calls made.
template <typename ProgramFor>
int drawCasters(const World& world, MeshCache& meshes, const ShadowLayerPlan& layer, const std::vector<Entity>& casters,
                const DepthProgram& opaque, ProgramFor&& programFor, bool first, CasterPass& pass) {
    const CasterDrawContext context{layer.lightFromWorld,
                                    layer.clipFromLight,
                                    layer.depthScale,
                                    layer.orthographic,
                                    GlProgram{opaque.program.get()},
                                    opaque.lightFromLocal};
    const DepthProgram* current = &opaque;
    const auto choose = [&](const DepthProgram& p) {
        if (&p == current) return;
        p.use(layer, first);
        current = &p;
    };
    int drawn = 0;
    for (Entity caster : casters) {
        const WorldTransform* wt = world.tryGet<WorldTransform>(caster);
        if (wt == nullptr || !wt->finite) continue;
        if (const Mesh* mesh = world.tryGet<Mesh>(caster); mesh != nullptr && mesh->data != nullptr) {
            const Skin* skin = world.tryGet<Skin>(caster);
            if (skin != nullptr && !skin->posed) continue;
            const Morph* morph = world.tryGet<Morph>(caster);
            const unsigned deform = gpu::meshDeform(skin, morph);
            const Material* m = world.tryGet<Material>(caster);
            const bool alphaTested = m != nullptr && m->cutout();
            // A posed skin or a morph may fold a part inside out, and a cut-out's holes show its inside.
            const bool rigidOpaqueSolid = pass.cullSolids && mesh->data->solid && deform == 0 && !alphaTested;
            pass.prepare(layer, rigidOpaqueSolid, wt->worldFromLocal, mesh->data->bounds, false, [&] {
                const WorldBounds* bounds = world.tryGet<WorldBounds>(caster);
                return bounds != nullptr ? std::optional<DAabb>(bounds->box) : std::nullopt;
            });
            choose(alphaTested || deform != 0 ? programFor(alphaTested, deform) : opaque);
            const GLuint name = current->program.get();
            if (alphaTested) {
                gl.ProgramUniform1f(name, current->alpha, m->alpha);
                gl.ProgramUniform1f(name, current->alphaCutoff, m->alphaCutoff);
                gpu::MeshCacheAccess::bindTexture(meshes, m->baseColorTexture, SG_UNIT_BASE_COLOR);
            }
            // Composed in double: light-relative float values stay precise far from the origin.
            const glm::mat4 lightFromLocal(layer.lightFromWorld *
                                           (skin != nullptr ? skin->worldFromFrame : wt->worldFromLocal));
            gl.ProgramUniformMatrix4fv(name, current->lightFromLocal, 1, GL_FALSE, glm::value_ptr(lightFromLocal));
            const int count =
                gpu::MeshCacheAccess::bindDeformed(meshes, mesh->data, name, current->deform, skin, morph);
            gl.DrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
        } else if (const ShadowCasterDraw* own = world.tryGet<ShadowCasterDraw>(caster); own != nullptr) {
            pass.prepare(layer, pass.cullSolids && own->solid && !own->draw, wt->worldFromLocal, own->localBounds, true,
                         [&] { return std::optional<DAabb>(transformBounds(wt->worldFromLocal, own->localBounds)); });
            choose(opaque);
            drawOwnCaster(*own, *wt, context);
        } else {
            continue;
        }
        ++drawn;
    }
    pass.cull.set(0);
    if (current != &opaque) opaque.use(layer, first);  // what the caller left current
    return drawn;
}

/// Attaches layer `k` of `map` to its framebuffer and clears it to the far depth where it may
/// hold anything else (writtenTexels, none after).
void attachAndClear(ShadowMapGpu& map, std::size_t k) {
    const GLuint framebuffer = map.framebuffer.get();
    gl.NamedFramebufferTextureLayer(framebuffer, GL_DEPTH_ATTACHMENT, map.array.get(), 0, static_cast<GLint>(k));
    PixelRect& written = map.writtenTexels[k];
    if (written.empty()) return;
    const float far = 1.0f;
    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(written.x0, written.y0, written.x1 - written.x0, written.y1 - written.y0);
    gl.ClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &far);
    gl.Disable(GL_SCISSOR_TEST);
    written = {};
}

}  // namespace

void ShadowMaps::Impl::drawLayer(const World& world, MeshCache& meshes, const ShadowLightPlan& plan, std::size_t k,
                                 LightShadowStats& ls) {
    const ShadowLayerPlan& layer = plan.layers[k];
    ShadowMapGpu& map = *maps[static_cast<std::size_t>(plan.sceneIndex)].second;
    map.depthScales[k] = layer.depthScale;
    if (layer.casters.empty()) {
        // Nothing casts into this layer: the far depth, nothing drawn.
        attachAndClear(map, k);
        ++ls.layersCleared;
        return;
    }
    gl.Viewport(0, 0, map.mapSize, map.mapSize);
    const DepthMode mode = plan.settings.depthMode;
    const auto programFor = [this, mode](bool alphaTested, unsigned deform) -> const DepthProgram& {
        return program(mode, alphaTested, deform);
    };
    if (mode != DepthMode::Nearest) {
        // First pass: the nearest depth, into the scratch the second pass reads, by the second
        // pass's own program (see uFirstPass in shadow_depth.frag.glsl).
        scratch.reserve(map.mapSize);
        gl.BindFramebuffer(GL_FRAMEBUFFER, scratch.framebuffer.get());
        const float far = 1.0f;
        gl.ClearNamedFramebufferfv(scratch.framebuffer.get(), GL_DEPTH, 0, &far);
        const DepthProgram& program = this->program(mode, false);
        program.use(layer, true);
        CasterPass firstPass;
        firstPass.mapSize = map.mapSize;
        ls.castersDrawn += drawCasters(world, meshes, layer, layer.casters, program, programFor, true, firstPass);
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, map.framebuffer.get());
    attachAndClear(map, k);
    if (mode != DepthMode::Nearest) {
        gl.BindSampler(SG_UNIT_MINMAX_SOURCE, 0);  // the texture's own nearest filtering, no comparison
        gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, scratch.texture.get());
    }
    const DepthProgram& program = this->program(mode, false);
    program.use(layer);
    // The second-depth modes need the far side of every caster: only a nearest layer culls.
    CasterPass pass;
    pass.cullSolids = mode == DepthMode::Nearest;
    pass.gatherTexels = true;  // what the next redraw clears (writtenTexels)
    pass.mapSize = map.mapSize;
    gl.Enable(GL_SCISSOR_TEST);
    ls.castersDrawn += drawCasters(world, meshes, layer, layer.casters, program, programFor, false, pass);
    gl.Disable(GL_SCISSOR_TEST);
    ls.castersCulled += pass.culled;
    PixelRect& written = map.writtenTexels[k];
    written = pass.texels;
    if (mode != DepthMode::Nearest) gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, 0);
    if (!layer.backgrounds.empty()) written = unite(written, drawBackgrounds(world, meshes, plan, k, pass.texels, ls));
    ++ls.layersDrawn;
}

PixelRect ShadowMaps::Impl::drawBackgrounds(const World& world, MeshCache& meshes, const ShadowLightPlan& plan,
                                            std::size_t k, const PixelRect& casterTexels, LightShadowStats& ls) {
    const ShadowLayerPlan& layer = plan.layers[k];
    ShadowMapGpu& map = *maps[static_cast<std::size_t>(plan.sceneIndex)].second;
    // Only a region that holds a caster texel reads anything but lit, and a receiver reads one
    // only within its region's reach of it: for the trilinear fetch of the mip chains, a texel
    // of the level above the radius and its bilinear neighbour, under 4 radii. Beyond twice
    // that, and an edge texel, the layer may keep the far depth.
    const int reach = 8 * static_cast<int>(std::ceil(std::max(plan.maxFilterTexels, 1.0f))) + 2;
    if (casterTexels.empty()) return {};
    const PixelRect near = grownWithin(casterTexels, reach, map.mapSize, map.mapSize);
    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(near.x0, near.y0, near.x1 - near.x0, near.y1 - near.y0);
    // The farthest background into the scratch (cleared to 0, tested GREATER), where the layer
    // holds no caster (the background programs read it).
    scratch.reserve(map.mapSize);
    gl.BindFramebuffer(GL_FRAMEBUFFER, scratch.framebuffer.get());
    const float nothing = 0.0f;
    gl.ClearNamedFramebufferfv(scratch.framebuffer.get(), GL_DEPTH, 0, &nothing);
    gl.DepthFunc(GL_GREATER);
    gl.BindSampler(SG_UNIT_MINMAX_SOURCE, 0);  // the texture's own nearest filtering, no comparison
    gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, map.array.get());
    const auto programFor = [this, k](bool alphaTested, unsigned deform) -> const DepthProgram& {
        const DepthProgram& p = backgroundProgram(alphaTested, deform);
        gl.ProgramUniform1i(p.program.get(), p.layerIndex, static_cast<GLint>(k));
        return p;
    };
    const DepthProgram& opaque = programFor(false, 0);
    opaque.use(layer);
    CasterPass pass;  // no culling: a background may be seen from either side
    pass.gatherTexels = true;
    pass.within = near;
    pass.mapSize = map.mapSize;
    ls.backgroundsDrawn += drawCasters(world, meshes, layer, layer.backgrounds, opaque, programFor, false, pass);
    // Then into the layer, within the texels the backgrounds can have drawn.
    const PixelRect copied = intersect(near, pass.texels);
    if (!copyBackground) {
        copyBackground =
            gpu::buildProgram({"Shadow/Background", "fullscreen.vert.glsl", "shadow_background.frag.glsl", {}});
        emptyVertexArray = gpu::makeVertexArray("Shadow/background vertex array");
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, map.framebuffer.get());
    gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, scratch.texture.get());
    gl.DepthFunc(GL_ALWAYS);
    gl.Scissor(copied.x0, copied.y0, copied.x1 - copied.x0, copied.y1 - copied.y0);
    gl.UseProgram(copyBackground->get());
    gl.BindVertexArray(emptyVertexArray.get());
    if (!copied.empty()) gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.Disable(GL_SCISSOR_TEST);
    gl.DepthFunc(GL_LESS);
    gl.BindTextureUnit(SG_UNIT_MINMAX_SOURCE, 0);
    return copied;
}

void CasterDrawContext::setWorldFromLocal(const glm::dmat4& worldFromLocal) const {
    // Composed in double: light-relative float values stay precise far from the origin.
    const glm::mat4 lightFromLocal(lightFromWorld * worldFromLocal);
    gl.ProgramUniformMatrix4fv(program.name, lightFromLocalLocation, 1, GL_FALSE, glm::value_ptr(lightFromLocal));
}

ShadowMaps::ShadowMaps() {
    gpu::requireLoaded("ShadowMaps");
    std::vector<Warning> pending;
    gpu::reportHostGlErrors("ShadowMaps", pending, gpu::kMaxPendingWarnings);
    impl_ = std::make_unique<Impl>(queryGlInfo().softwareRenderer);
    impl_->timer.setEnabled(false);
    impl_->pending = std::move(pending);
}

ShadowMaps::~ShadowMaps() = default;

Result<std::unique_ptr<ShadowMaps>> ShadowMaps::create() noexcept {
    return gpu::noThrow<std::unique_ptr<ShadowMaps>>("ShadowMaps", [] { return std::make_unique<ShadowMaps>(); });
}

Status ShadowMaps::tryRender(const ShadowFrame& frame, const World& world, MeshCache& meshes,
                             FrameStats& stats) noexcept {
    return gpu::noThrowStatus("ShadowMaps::render", [&] { render(frame, world, meshes, stats); });
}

void ShadowMaps::render(const ShadowFrame& frame, const World& world, MeshCache& meshes, FrameStats& stats) {
    gpu::reportHostGlErrors("ShadowMaps::render", stats);
    // What the calls without a FrameStats found since the last frame, in the order found.
    gpu::movePendingWarnings(impl_->pending, stats.warnings);
    gpu::movePendingWarnings(gpu::MeshCacheAccess::pending(meshes), stats.warnings);
    static constexpr std::array<GLint, 2> kUnits{SG_UNIT_MINMAX_SOURCE, SG_UNIT_BASE_COLOR};
    static constexpr std::array<GLint, 1> kImageUnits{SG_IMAGE_MINMAX};
    const gpu::GlStateGuard hostState(kUnits, {}, kImageUnits);
    Impl& g = *impl_;
    g.syncMaps(frame);
    stats.warnings.insert(stats.warnings.end(), frame.warnings.begin(), frame.warnings.end());
    beginDepthOnly();
    const std::size_t firstLight = stats.lights.size();
    for (const ShadowLightPlan& plan : frame.lights) {
        LightShadowStats& ls = stats.addLight();
        describe(plan, ls);
        const auto& map = g.maps[static_cast<std::size_t>(plan.sceneIndex)].second;
        ls.mapAllocated = map != nullptr && map->allocatedThisFrame;
        ls.mapBytes = map != nullptr ? depthArrayBytes(map->mapSize, map->layers) : 0;
        ls.filterChainBytes = map != nullptr && map->chain ? map->chain->bytes(map->mapSize, map->layers) : 0;
        for (std::size_t k = 0; k < plan.layers.size(); ++k) {
            if (!plan.layers[k].dirty) {
                ++ls.layersReused;
                continue;
            }
            const bool drawn = !plan.layers[k].casters.empty();
            std::optional<gpu::ScopedPass> pass;
            if (drawn) {
                formatPassName(g.passName, plan, "layer", k);
                pass.emplace(g.timer, g.passName);
            }
            g.drawLayer(world, meshes, plan, k, ls);
        }
        stats.shadowLayersDrawn += ls.layersDrawn;
        stats.shadowLayersReused += ls.layersReused;
        stats.shadowLayersCleared += ls.layersCleared;
        stats.shadowDrawCalls += ls.castersDrawn + ls.backgroundsDrawn;
    }
    endDepthOnly();
    for (std::size_t i = 0; i < frame.lights.size(); ++i) {
        if (frame.lights[i].hasMap()) g.updateChains(frame.lights[i], stats.lights[firstLight + i]);
    }
    stats.shadowScratchBytes = g.scratch.bytes();
    if (g.fields && g.fields->voxelBudget() != frame.distanceFieldVoxels) g.fields.reset();  // bake again
    if (!g.fields && (frame.techniquesInUse & techniqueBit(ShadowTechnique::Sdf)) != 0) {
        g.fields.emplace(frame.distanceFieldVoxels);
    }
    if (g.fields) {
        const int baked = g.fields->fieldsBaked();
        const double seconds = g.fields->bakeSeconds();
        g.fields->update(frame, world, stats.warnings);
        stats.distanceFieldsBaked = g.fields->fieldsBaked() - baked;
        stats.distanceFieldBakeMs = 1000.0 * (g.fields->bakeSeconds() - seconds);
        stats.distanceFieldBytes = g.fields->bytes();
    }
    gpu::checkGlError("shadow pass");
    g.timer.collect(stats);
}

void ShadowMaps::setTiming(bool enabled) { impl_->timer.setEnabled(enabled); }

GlTexture ShadowMaps::textureOf(std::size_t i) const {
    const auto& maps = impl_->maps;
    return GlTexture{i < maps.size() && maps[i].second ? maps[i].second->array.get() : 0u};
}

GlTexture ShadowMaps::textureOfLight(Entity light) const {
    for (const auto& [entity, map] : impl_->maps) {
        if (entity == light && map) return GlTexture{map->array.get()};
    }
    return {};
}

GlTexture ShadowMaps::filterChainOf(std::size_t i) const {
    const auto& maps = impl_->maps;
    return GlTexture{i < maps.size() && maps[i].second && maps[i].second->chain ? maps[i].second->chain->texture.get()
                                                                                : 0u};
}

GlTexture ShadowMaps::fieldAtlas() const { return GlTexture{impl_->fields ? impl_->fields->atlas() : 0u}; }

GlTexture ShadowMaps::fieldInstances(const glm::dvec3& wsCamera) const {
    if (!impl_->fields) return GlTexture{0u};
    // An error the host left pending is the host's: reported, not thrown as the upload's.
    gpu::reportHostGlErrors("ShadowMaps::fieldInstances", impl_->pending, gpu::kMaxPendingWarnings);
    return GlTexture{impl_->fields->instances(wsCamera)};
}

GlTexture ShadowMaps::fieldInstances() const {
    return GlTexture{impl_->fields ? impl_->fields->uploadedInstances() : 0u};
}

int ShadowMaps::layersOf(std::size_t i) const {
    const auto& maps = impl_->maps;
    return i < maps.size() && maps[i].second ? maps[i].second->layers : 0;
}

std::vector<float> ShadowMaps::readLayerDepth(std::size_t i, int layer) const {
    const auto& maps = impl_->maps;
    if (i >= maps.size() || !maps[i].second) return {};
    const ShadowMapGpu& map = *maps[i].second;
    if (layer < 0 || layer >= map.layers) return {};
    gpu::reportHostGlErrors("ShadowMaps::readLayerDepth", impl_->pending, gpu::kMaxPendingWarnings);
    std::vector<float> depth(static_cast<std::size_t>(map.mapSize) * map.mapSize);
    const gpu::GlStateGuard hostState({}, {});
    gpu::setReadbackDefaults();
    gl.GetTextureSubImage(map.array.get(), 0, 0, 0, layer, map.mapSize, map.mapSize, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                          static_cast<GLsizei>(depth.size() * sizeof(float)), depth.data());
    const float scale = map.depthScales[static_cast<std::size_t>(layer)];
    for (float& d : depth) d *= scale;
    return depth;
}

const std::vector<Warning>& ShadowMaps::warnings() const { return impl_->pending; }

void ShadowMaps::clearWarnings() { impl_->pending.clear(); }

}  // namespace shadow
