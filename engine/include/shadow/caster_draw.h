// Shadow casters drawn from the game's own geometry: the component the planner culls by its
// bounds and the shadow maps draw, and what a game's draw callback gets.
#pragma once

#include <shadow/gl_handles.h>
#include <shadow/math.h>

#include <glm/glm.hpp>

#include <cstddef>
#include <functional>

namespace shadow {

/// What a `ShadowCasterDraw::draw` callback gets: the layer being drawn, with the module's depth
/// program current and its framebuffer, viewport and depth state set.
struct CasterDrawContext {
    glm::dmat4 lightFromWorld{1.0};  ///< world -> light view (m; the light looks down -Z)
    glm::dmat4 clipFromLight{1.0};   ///< light view -> clip
    float depthScale = 1.0f;         ///< stored depth = lsDepth / depthScale (shadow_depth.frag.glsl)
    bool orthographic = false;       ///< a directional light's layer
    /// The module's depth program (current): vec3 positions at attribute 0, object transform in
    /// `uLightFromLocal`. A callback may draw with it after `setWorldFromLocal`, or with a program
    /// of its own that writes the same depth (shaders/shadow_depth.frag.glsl) and put this back.
    GlProgram program;
    int lightFromLocalLocation = -1;  ///< the location of `uLightFromLocal` in `program`
    /// Points the depth program at object transform `worldFromLocal` for the next draws
    /// (composed with `lightFromWorld` in double, so float precision holds far from the origin).
    void setWorldFromLocal(const glm::dmat4& worldFromLocal) const;
};

/// A shadow caster drawn from the game's own geometry, with nothing mirrored into the module: an
/// entity with a `Transform` (or `WorldTransform`) and this component. The shadow planner culls
/// it per layer by `localBounds` and, where it falls in a layer, the shadow maps draw
/// `indexCount` indices of the game's vertex array with the module's depth program, or call
/// `draw` instead (for the game's instancing, skinning or streaming). The module's own renderer
/// does not draw it in the main pass: a game with such casters lights its own frame
/// (shadowShaderSource, ShadowMask).
struct ShadowCasterDraw {
    Aabb localBounds;                      ///< object space (m): must hold everything the caster draws
    GlVertexArray vertexArray;             ///< the game's vertex array: vec3 float positions at attribute 0
    IndexType indexType = IndexType::U32;  ///< of the vertex array's element buffer
    std::size_t indexOffset = 0;           ///< bytes into the vertex array's element buffer
    int indexCount = 0;                    ///< indices drawn (triangles)
    int baseVertex = 0;                    ///< added to every index
    /// When set, called instead of the indexed draw, once per layer the caster falls in (twice
    /// for a light whose depth mode is midpoint or second: the context's program differs).
    std::function<void(const CasterDrawContext&)> draw;
    /// Set by the game in a frame where the geometry changed while the transform did not
    /// (skinning, streaming): the layers it falls in are redrawn. The module does not reset it.
    bool changedThisFrame = false;
    /// Whether what it draws is closed (watertight), which the second-depth modes need
    /// (`DepthMode`); a light in those modes warns about a caster not marked closed.
    bool closed = false;
    /// Whether the indexed draw's triangles are solid, as `MeshData::solid` (closed, every edge
    /// once in each direction, each part counter-clockwise seen from outside): a nearest-depth
    /// layer then culls their back faces (the front ones under a mirroring transform), which
    /// stores the same depths from about half the fragments. Not used for a `draw` callback,
    /// which is called with culling off.
    bool solid = false;

    /// Whether it draws anything: a callback, or a vertex array with indices.
    [[nodiscard]] bool drawsSomething() const { return draw != nullptr || (vertexArray && indexCount > 0); }
};

}  // namespace shadow
