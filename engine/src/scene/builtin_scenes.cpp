// Built-in procedural scenes, so the main job and the tests need no asset files.
#include <shadow/scene.h>

#include <glm/gtc/constants.hpp>

#include <functional>
#include <map>

namespace shadow {
namespace {

Material matte(float r, float g, float b) {
    Material m;
    m.albedo = {r, g, b};
    m.specular = glm::vec3(0.04f);
    m.shininess = 24.0f;
    return m;
}

/// A matte material for a closed mesh: its back faces are never seen, so the main pass culls them.
Material solid(float r, float g, float b) {
    Material m = matte(r, g, b);
    m.doubleSided = false;
    return m;
}

Transform at(double x, double y, double z) {
    Transform t;
    t.translation = {x, y, z};
    return t;
}

/// The default scene's static casters of several heights: three pillars and a plate on legs.
void addDefaultStaticCasters(World& w, const std::shared_ptr<const MeshData>& unitBox) {
    struct Pillar {
        const char* name;
        double x, z, height;
    };
    for (const Pillar& p : {Pillar{"pillar short", -3.0, -2.0, 0.6}, Pillar{"pillar mid", 2.5, -3.0, 1.6},
                            Pillar{"pillar tall", -1.0, 3.0, 3.2}}) {
        Transform t = at(p.x, 0.5 * p.height, p.z);
        t.scale = {0.8, p.height, 0.8};
        addMeshInstance(w, p.name, unitBox, t, solid(0.8f, 0.55f, 0.35f));
    }
    // A plate on thin legs: a blocker well above the ground, for soft penumbrae.
    Transform plate = at(3.0, 1.4, 2.0);
    plate.scale = {1.6, 0.08, 1.2};
    addMeshInstance(w, "table top", unitBox, plate, solid(0.35f, 0.55f, 0.8f));
}

/// The default scene's three moving casters (orbiting, bobbing, spinning). Returns the orbit's
/// period, the length of one loop of the animation.
double addDefaultMovingCasters(World& w, const std::shared_ptr<const MeshData>& unitBox) {
    const Entity orbiter =
        addMeshInstance(w, "orbiting box", makeBoxMesh(glm::vec3(0.4f)), at(0, 0.4, 0), solid(0.85f, 0.25f, 0.25f));
    ProceduralMotion orbit;
    orbit.kind = ProceduralMotion::Kind::Orbit;
    orbit.center = {0.0, 0.4, 0.0};
    orbit.radius = 4.0;
    orbit.speed = 0.6;
    w.emplace<ProceduralMotion>(orbiter, orbit);

    const Entity bobber = addMeshInstance(w, "bobbing sphere", makeSphereMesh(0.5f, 32, 16), at(-3.5, 1.5, 1.5),
                                          solid(0.3f, 0.75f, 0.35f));
    ProceduralMotion bob;
    bob.kind = ProceduralMotion::Kind::Bob;
    bob.center = {-3.5, 1.6, 1.5};
    bob.axis = {0.0, 1.0, 0.0};
    bob.amplitude = 0.9;
    bob.speed = 1.3;
    w.emplace<ProceduralMotion>(bobber, bob);

    Transform spinT = at(1.0, 1.0, -0.5);
    spinT.scale = {1.6, 0.3, 0.3};
    const Entity spinner = addMeshInstance(w, "spinning bar", unitBox, spinT, solid(0.9f, 0.8f, 0.3f));
    ProceduralMotion spin;
    spin.kind = ProceduralMotion::Kind::Spin;
    spin.axis = {0.0, 1.0, 0.0};
    spin.speed = 0.8;
    w.emplace<ProceduralMotion>(spinner, spin);
    return 2.0 * glm::pi<double>() / orbit.speed;
}

/// The default scene's lights, one of each type, each with its own technique: a PCSS sun, a
/// PCF spot light and a hard point light.
void addDefaultLights(Scene& scene) {
    Light sun;
    sun.type = LightType::Directional;
    sun.color = {1.0f, 0.96f, 0.9f};
    sun.intensity = 4.0f;
    sun.angularRadius = 0.02f;
    Shadow sunShadow;
    sunShadow.technique = ShadowTechnique::Pcss;
    sunShadow.mapSize = 1024;
    sunShadow.cascades = 3;
    addLight(scene, "sun", sun, sunShadow, {0, 20, 0}, glm::normalize(glm::dvec3(0.55, -1.0, -0.35)));

    Light spot;
    spot.type = LightType::Spot;
    spot.color = {0.6f, 0.75f, 1.0f};
    spot.intensity = 60.0f;
    spot.range = 30.0f;
    spot.outerConeAngle = static_cast<float>(glm::pi<double>() / 5.0);
    spot.innerConeAngle = static_cast<float>(glm::pi<double>() / 7.0);
    spot.radius = 0.15f;
    Shadow spotShadow;
    spotShadow.technique = ShadowTechnique::Pcf;
    spotShadow.mapSize = 1024;
    spotShadow.pcfRadius = 0.06f;
    addLight(scene, "spot", spot, spotShadow, {6, 6, 5}, glm::normalize(glm::dvec3(-6, -6, -5)));

    Light bulb;
    bulb.type = LightType::Point;
    bulb.color = {1.0f, 0.7f, 0.45f};
    bulb.intensity = 12.0f;
    bulb.range = 20.0f;
    bulb.radius = 0.05f;
    Shadow bulbShadow;
    bulbShadow.technique = ShadowTechnique::Hard;
    bulbShadow.mapSize = 512;
    addLight(scene, "bulb", bulb, bulbShadow, {-1.5, 2.6, -1.0}, {0, -1, 0});
}

/// The animated default scene: a ground, casters of several heights, three moving objects,
/// and a PCSS sun, a PCF spot light and a hard point light.
Scene makeDefault() {
    Scene scene;
    scene.name = "default";
    World& w = scene.world;
    addMeshInstance(w, "ground", makePlaneMesh(12.0f, 8), at(0, 0, 0), matte(0.75f, 0.75f, 0.72f));
    const std::shared_ptr<const MeshData> unitBox = makeBoxMesh(glm::vec3(0.5f));
    addDefaultStaticCasters(w, unitBox);
    scene.animationDuration = addDefaultMovingCasters(w, unitBox);
    addDefaultLights(scene);
    Camera camera;
    camera.yfov = 0.75f;
    camera.znear = 0.1f;
    camera.zfar = 100.0f;
    addCamera(scene, "camera", camera, {9.0, 7.5, 11.0}, {0.0, 0.5, 0.0});
    return scene;
}

/// The plates' receiver, disk light and camera, without casters (builtin:plates and plates-boxes).
Scene makePlatesStage(const std::string& name) {
    Scene scene;
    scene.name = name;
    World& w = scene.world;
    const PlatesGeometry g;
    addMeshInstance(w, "receiver", makePlaneMesh(static_cast<float>(g.receiverHalfSize), 4), at(0, 0, 0),
                    matte(0.8f, 0.8f, 0.8f));
    Light spot;
    spot.type = LightType::Spot;
    spot.intensity = 40.0f;
    spot.outerConeAngle = 0.95f;
    spot.innerConeAngle = 0.9f;
    spot.radius = static_cast<float>(g.lightRadius);
    Shadow shadow;
    shadow.technique = ShadowTechnique::Pcss;
    shadow.mapSize = 2048;
    shadow.blockerSamples = 32;
    shadow.pcfSamples = 32;
    // maxFilterTexels automatic: the highest caster's penumbra spans ~140 texels of the ground,
    // which a filter clamped narrower would cut (plates-boxes' PCSS penumbra RMSE 0.13 at 64
    // texels, 0.022 at 256), and a wider clamp lets the moment techniques' estimates run wide.
    addLight(scene, "disk light", spot, shadow, {0.0, g.lightHeight, 0.0}, {0.0, -1.0, 0.0});
    Camera camera;
    camera.yfov = 0.9f;
    camera.znear = 0.1f;
    camera.zfar = 50.0f;
    addCamera(scene, "camera", camera, {0.0, 5.5, 3.0}, {0.0, 0.0, 0.0});
    return scene;
}

}  // namespace

Scene makePlatesScene() {
    Scene scene = makePlatesStage("plates");
    World& w = scene.world;
    const PlatesGeometry g;
    for (std::size_t k = 0; k < g.plates.size(); ++k) {
        const PlatesGeometry::Plate& p = g.plates[k];
        const Entity e = addMeshInstance(w, "plate" + std::to_string(k), makePlaneMesh(static_cast<float>(p.halfSize)),
                                         at(p.center.x, p.center.y, p.center.z), matte(0.5f, 0.6f, 0.8f));
        w.get<Mesh>(e).receiveShadows = false;
    }
    return scene;
}

namespace {

/// builtin:plates-boxes, the plates' check on casters they do not have: closed boxes 1, 3 and
/// 10 cm thick at 0.6, 1.5 and 2.6 m under the plates' disk light (so their penumbrae span from
/// narrow to wider than the boxes), one of them turned, none receiving shadows (the figures are
/// the receiver's). Truth comes from shadow_reference: the closed form holds only open squares.
Scene makePlateBoxesScene() {
    Scene scene = makePlatesStage("plates-boxes");
    World& w = scene.world;
    struct Box {
        glm::dvec3 center;
        glm::vec3 halfExtents;
        double yaw;
    };
    const Box boxes[] = {{{-1.2, 0.6, 0.5}, {0.45f, 0.005f, 0.3f}, 0.0},
                         {{1.0, 1.5, -0.3}, {0.35f, 0.015f, 0.35f}, 0.5},
                         {{0.1, 2.6, 0.9}, {0.3f, 0.05f, 0.2f}, 0.0}};
    int k = 0;
    for (const Box& b : boxes) {
        Transform t = at(b.center.x, b.center.y, b.center.z);
        t.rotation = glm::angleAxis(b.yaw, glm::dvec3(0.0, 1.0, 0.0));
        const Entity e =
            addMeshInstance(w, "box" + std::to_string(k++), makeBoxMesh(b.halfExtents), t, matte(0.5f, 0.6f, 0.8f));
        w.get<Mesh>(e).receiveShadows = false;
    }
    return scene;
}

/// Places `bunny` (the Stanford bunny's mesh) on the ground at the origin, 1.2 m tall.
void addBunny(World& w, std::shared_ptr<const MeshData> bunny) {
    const Aabb b = bunny->bounds;
    const double scale = 1.2 / std::max(1e-6f, b.max.y - b.min.y);
    Transform t = at(-scale * b.center().x, -scale * b.min.y, -scale * b.center().z);
    t.scale = glm::dvec3(scale);
    addMeshInstance(w, "bunny", std::move(bunny), t, solid(0.85f, 0.8f, 0.7f));
}

Result<Scene> makeBunny() {
    auto bunny = loadObjMesh(kBunnyObjPath);
    if (!bunny) return Error{bunny.error().code, "builtin:bunny: " + bunny.error().message + " (install glmark2-data)"};
    Scene scene;
    scene.name = "bunny";
    World& w = scene.world;
    addMeshInstance(w, "ground", makePlaneMesh(4.0f, 4), at(0, 0, 0), matte(0.75f, 0.75f, 0.72f));
    addBunny(w, std::move(bunny).value());

    Light sun;
    sun.type = LightType::Directional;
    sun.intensity = 3.0f;
    sun.angularRadius = 0.03f;
    Shadow sunShadow;
    sunShadow.technique = ShadowTechnique::Pcss;
    addLight(scene, "sun", sun, sunShadow, {0, 10, 0}, glm::normalize(glm::dvec3(0.5, -1.0, -0.4)));
    Light spot;
    spot.type = LightType::Spot;
    spot.intensity = 25.0f;
    spot.outerConeAngle = 0.6f;
    spot.innerConeAngle = 0.45f;
    spot.radius = 0.1f;
    Shadow spotShadow;
    spotShadow.technique = ShadowTechnique::Pcf;
    addLight(scene, "spot", spot, spotShadow, {-2.5, 3.0, 2.0}, glm::normalize(glm::dvec3(2.5, -2.6, -2.0)));
    Light bulb;
    bulb.type = LightType::Point;
    bulb.intensity = 6.0f;
    bulb.radius = 0.05f;
    Shadow bulbShadow;
    bulbShadow.technique = ShadowTechnique::Hard;
    bulbShadow.mapSize = 512;
    addLight(scene, "bulb", bulb, bulbShadow, {1.2, 1.8, 1.0}, {0, -1, 0});
    Camera camera;
    camera.yfov = 0.7f;
    camera.znear = 0.05f;
    camera.zfar = 50.0f;
    addCamera(scene, "camera", camera, {2.6, 2.2, 3.4}, {0.0, 0.5, 0.0});
    return scene;
}

/// The bunny under one spot light, the scenes of the peer comparison (benchmarks/run_peers.sh):
/// the Stanford bunny on an 8 m ground, a spot light with a 0.7 rad cone and a 2048^2 PCSS map.
/// `name` is bunny-spot (an emitter of radius 0.08 m) or bunny-spot-wide (0.15 m: penumbrae
/// about twice as wide, so more of the screen is penumbra).
Result<Scene> makeBunnySpot(const std::string& name, float emitterRadius) {
    auto bunny = loadObjMesh(kBunnyObjPath);
    if (!bunny)
        return Error{bunny.error().code, "builtin:" + name + ": " + bunny.error().message + " (install glmark2-data)"};
    Scene scene;
    scene.name = name;
    World& w = scene.world;
    // The ground only receives: it hides nothing from the light (the peer is set up the same way).
    const Entity ground = addMeshInstance(w, "ground", makePlaneMesh(4.0f, 16), at(0, 0, 0), matte(0.85f, 0.8f, 0.75f));
    w.get<Mesh>(ground).castShadows = false;
    addBunny(w, std::move(bunny).value());

    Light spot;
    spot.type = LightType::Spot;
    spot.color = {1.0f, 0.9f, 0.8f};
    spot.intensity = 60.0f;
    spot.outerConeAngle = 0.7f;
    spot.innerConeAngle = 0.55f;
    spot.radius = emitterRadius;
    Shadow shadow;
    shadow.technique = ShadowTechnique::Pcss;
    shadow.mapSize = 2048;
    addLight(scene, "spot", spot, shadow, {-2.0, 3.5, 1.5}, glm::normalize(glm::dvec3(2.0, -3.3, -1.5)));
    Camera camera;
    camera.yfov = 0.7f;
    camera.znear = 0.05f;
    camera.zfar = 50.0f;
    addCamera(scene, "camera", camera, {2.6, 2.2, 3.4}, {0.0, 0.5, 0.0});
    return scene;
}

/// The many-lights benchmark: a 40 m floor with an 8 x 8 grid of boxes, and `lights` small
/// lights (4 m range) over the boxes, spot and point in turn, each with its own shadow map.
/// `lights` = 64 is builtin:many-lights, 1 is builtin:many-lights-1 (the same scene, one light).
Scene makeManyLights(int lights) {
    Scene scene;
    scene.name = lights == 1 ? "many-lights-1" : "many-lights";
    World& w = scene.world;
    addMeshInstance(w, "floor", makePlaneMesh(20.0f, 16), at(0, 0, 0), matte(0.75f, 0.75f, 0.72f));
    const auto box = makeBoxMesh(glm::vec3(0.4f));
    for (int i = 0; i < 64; ++i) {
        const int column = i % 8, row = i / 8;
        const double x = -17.5 + 5.0 * column, z = -17.5 + 5.0 * row;
        addMeshInstance(w, "box " + std::to_string(i), box, at(x + 0.6, 0.4, z + 0.3), solid(0.8f, 0.55f, 0.35f));
        if (i >= lights) continue;
        Light light;
        light.type = i % 2 == 0 ? LightType::Spot : LightType::Point;
        light.color = i % 3 == 0 ? glm::vec3(1.0f, 0.85f, 0.7f) : glm::vec3(0.75f, 0.85f, 1.0f);
        light.intensity = 8.0f;
        light.range = 4.0f;
        light.outerConeAngle = 0.9f;
        light.innerConeAngle = 0.7f;
        light.radius = 0.05f;
        Shadow shadow;
        shadow.technique = light.type == LightType::Spot ? ShadowTechnique::Pcf : ShadowTechnique::Hard;
        shadow.mapSize = 256;
        addLight(scene, "light " + std::to_string(i), light, shadow, {x, 2.5, z}, {0, -1, 0});
    }
    Camera camera;
    camera.yfov = 0.9f;
    camera.znear = 0.5f;
    camera.zfar = 200.0f;
    addCamera(scene, "camera", camera, {0.0, 34.0, 30.0}, {0.0, 0.0, -2.0});
    return scene;
}

const std::map<std::string, std::function<Result<Scene>()>>& registry() {
    static const std::map<std::string, std::function<Result<Scene>()>> scenes = {
        {"default", [] { return Result<Scene>(makeDefault()); }},
        {"plates", [] { return Result<Scene>(makePlatesScene()); }},
        {"plates-boxes", [] { return Result<Scene>(makePlateBoxesScene()); }},
        {"bunny", makeBunny},
        {"bunny-spot", [] { return makeBunnySpot("bunny-spot", 0.08f); }},
        {"bunny-spot-wide", [] { return makeBunnySpot("bunny-spot-wide", 0.15f); }},
        {"many-lights", [] { return Result<Scene>(makeManyLights(64)); }},
        {"many-lights-1", [] { return Result<Scene>(makeManyLights(1)); }},
    };
    return scenes;
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
    std::vector<std::string> names;
    for (const auto& [name, make] : registry()) names.push_back(name);
    return names;
}

Result<Scene> makeBuiltinScene(const std::string& name) {
    const auto it = registry().find(name);
    if (it == registry().end()) {
        std::string known;
        for (const std::string& n : builtinSceneNames()) known += (known.empty() ? "" : ", ") + n;
        return Error{ErrorCode::InvalidArgument, "builtin:" + name + ": no such built-in scene (known: " + known + ")"};
    }
    return it->second();
}

Result<Scene> loadScene(const std::string& spec, const GltfLoadOptions& options) {
    const std::string prefix = "builtin:";
    if (spec.rfind(prefix, 0) != 0) return loadGltf(spec, options);
    auto scene = makeBuiltinScene(spec.substr(prefix.size()));
    if (!scene) return scene;
    // A built-in scene has no clips: a clip named or numbered is an error, as for a file.
    if (Status s = playAnimation(*scene, options.animation); !s) return s.error().within(spec + ": ");
    return scene;
}

}  // namespace shadow
