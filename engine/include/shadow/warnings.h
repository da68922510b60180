// Warnings: what the engine let pass, and how it carried on (after sokol's named log items).
//
// A warning never stops a load or a frame. Settings out of their documented range are clamped,
// lights over the shadow memory budget get a smaller map or none, an entity whose transform is
// not finite is skipped, and under lenient `GltfLoadOptions` a glTF `extras.shadow` that does
// not parse is ignored. Each such decision is one `Warning`: a code for programs and tests to
// branch on, the element at fault, and the line a person reads (what the CLI prints and
// stats.json lists). Producing warnings never throws.
//
// Where they are collected: `Scene::warnings` (loading, and what the content does once per
// entity while playing: the CLIs print them and list them in stats.json with the frame's),
// `ShadowFrame::warnings` (the shadow planner, every frame), `FrameStats::warnings` (a whole
// frame: the transform system's and the planner's).
#pragma once

#include <string>

namespace shadow {

/// What happened. New codes are appended; stats.json spells a code by `warningCodeName`.
enum class WarningCode {
    /// A `Light` or `Shadow` field was out of its documented range (components.h), or NaN, and
    /// was clamped to it (a spot's cone also to what a map covers, 85 degrees). Element: the
    /// light. One warning per field.
    SettingClamped,
    /// The shadow memory budget (`ShadowLimits::maxShadowBytes`) halved a light's map. Element:
    /// the light.
    MapSizeReduced,
    /// The shadow memory budget left a light without a shadow this frame (visibility 1).
    /// Element: the light.
    ShadowDropped,
    /// An entity's world matrix (or an ancestor's) is not finite or reaches beyond
    /// `kMaxWorldCoordinate`; every pass skips it. Element: the entity's name, or
    /// `entity <index>` when it has none.
    NonFiniteTransform,
    /// A glTF `extras.shadow` object did not parse and lenient loading used the defaults in its
    /// place. Element: the object, e.g. `KHR_lights_punctual.lights[1].extras.shadow` or
    /// `nodes[0].extras.shadow` (the message names the file and the member at fault).
    ShadowSettingsIgnored,
    /// The host's GL context held an error before a call into the engine (any public call that
    /// talks to GL: `ShadowSystem::render`, `shaderInputs`, `Renderer::render`, ...): it was read
    /// and cleared so that it is not blamed on the engine, and reported here (a call without a
    /// `FrameStats` keeps it in its object's `warnings()`). Element: the engine call. The message
    /// lists the codes.
    HostGlError,
    /// A glTF `extras.shadow` object has a key the engine does not know (a misspelling, or a
    /// setting of a newer engine); it was ignored. Element: the key, e.g.
    /// `KHR_lights_punctual.lights[0].extras.shadow.techniqe`; the message suggests the closest
    /// known key when one is near.
    UnknownSetting,
    /// A glTF node `matrix` has fewer than two non-zero columns, so it holds no rotation; the
    /// node's rotation is taken as identity (in its parent's frame: -Z forward, +Y up). Reported
    /// for a light or camera on such a node or below it. Element: the light or camera's node,
    /// e.g. `nodes[1]`; the message names the node with the matrix.
    DegenerateTransform,
    /// A `KHR_lights_punctual` light has a `type` the engine does not know; it was skipped, and
    /// the nodes that reference it carry no light. Element: the light, e.g.
    /// `KHR_lights_punctual.lights[2]`.
    UnsupportedLight,
    /// A light whose depth mode is `midpoint` or `second` has casters in its layers that are not
    /// known to be closed (`MeshData::closed`, `ShadowCasterDraw::closed`): where a ray meets
    /// only one surface of them the map stores the far depth, and in `second` mode a receiver
    /// right behind one may be compared with itself. Element: the light; the message counts
    /// them and names the first.
    OpenCaster,
    /// A light with technique `sdf` has casters no distance field represents (a game's own
    /// `ShadowCasterDraw`, a mesh with a non-uniform scale): they cast through the light's shadow
    /// map instead (a hard shadow, multiplied with the march's visibility). Element: the light;
    /// the message counts their draws and names the first.
    CasterWithoutField,
    /// A glTF scene lists a node that is not a root (or lists one twice). The node is taken
    /// once: below its nearest ancestor the scene lists too, else as a root of its own subtree
    /// with its own transform. Element: the node, e.g. `nodes[1]`; the message says which.
    SceneNodeNotRoot,
    /// A glTF file uses something the module does not draw (an extension, morph targets, an
    /// emissive colour, a texture it does not read, ...): it is left out and the rest drawn.
    /// One warning per kind, element: the first element that uses it, e.g.
    /// `materials[2].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform`; the
    /// message counts the uses and says what the module does instead.
    UnsupportedFeature,
    /// A material's texture reads a `TEXCOORD_n` set its primitive lacks: the primitive is drawn
    /// without that texture. Element: the primitive, e.g. `meshes[0].primitives[1]`; the
    /// message names the material and the texture.
    MissingTexcoord,
    /// The scene had no lights, so the default rig (`addDefaultRig`, shadow/default_rig.h) lit
    /// it: a shadowed sun placed from the model's bounds and a shadow-catcher ground. A notice
    /// rather than a fault, so that a picture of a file's own lighting is not mistaken for the
    /// rig's. Element: the scene's name (the file); the message says what was added and where.
    DefaultRigAdded,
    /// More morph weights of a mesh instance were non-zero at once than a draw blends
    /// (`kMaxMorphInfluences`): the ones of largest magnitude are drawn, alike in every pass and
    /// in the reference tracer, and the rest left out. Reported once per entity, the first frame
    /// it happens (into `Scene::warnings`, by `reportTruncatedMorphs`). Element: the entity's
    /// name (its glTF node's); the message names the mesh and counts the weights.
    MorphTargetsDropped,
};

/// One decision the engine reports.
struct Warning {
    WarningCode code = WarningCode::SettingClamped;
    /// The light, entity or glTF element at fault (see `WarningCode`).
    std::string element;
    /// The whole line for a person, naming the element and what was done, e.g.
    /// `lamp: mapSize 99999 clamped to 16384`.
    std::string message;
};

/// The code's name as written in stats.json ("SettingClamped", ...); "Unknown" for a value
/// outside the enum.
[[nodiscard]] constexpr const char* warningCodeName(WarningCode code) {
    switch (code) {
        case WarningCode::SettingClamped: return "SettingClamped";
        case WarningCode::MapSizeReduced: return "MapSizeReduced";
        case WarningCode::ShadowDropped: return "ShadowDropped";
        case WarningCode::NonFiniteTransform: return "NonFiniteTransform";
        case WarningCode::ShadowSettingsIgnored: return "ShadowSettingsIgnored";
        case WarningCode::HostGlError: return "HostGlError";
        case WarningCode::UnknownSetting: return "UnknownSetting";
        case WarningCode::DegenerateTransform: return "DegenerateTransform";
        case WarningCode::UnsupportedLight: return "UnsupportedLight";
        case WarningCode::OpenCaster: return "OpenCaster";
        case WarningCode::CasterWithoutField: return "CasterWithoutField";
        case WarningCode::SceneNodeNotRoot: return "SceneNodeNotRoot";
        case WarningCode::UnsupportedFeature: return "UnsupportedFeature";
        case WarningCode::MissingTexcoord: return "MissingTexcoord";
        case WarningCode::DefaultRigAdded: return "DefaultRigAdded";
        case WarningCode::MorphTargetsDropped: return "MorphTargetsDropped";
    }
    return "Unknown";
}

}  // namespace shadow
