// osg_bunny: the scene of `builtin:bunny-spot` drawn by OpenSceneGraph, timed, for the peer
// comparison of benchmarks/run_peers.sh. Not part of the library or its tests; built on its own
// (benchmarks/peers/CMakeLists.txt).
//
//   osg_bunny none|sm|vdsm|soft [--warmup W] [--frames N] [--png PATH] [--size WxH] [--grid N]
//                               [--obj PATH] [--softness W]
//
// none: no shadow; sm: osgShadow::ShadowMap; vdsm: osgShadow::ViewDependentShadowMap;
// soft: osgShadow::SoftShadowMap; every map 2048^2 and re-rendered every frame (OSG redraws its
// shadow cameras in every cull, there is no cache to turn off). Prints one JSON object: the
// median/min/max frame time over the N timed frames, GL_RENDERER, the geometry drawn.
//
// The scene's figures are copied from makeBunnySpot (engine/src/scene/builtin_scenes.cpp); keep
// the two in step.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <osg/ComputeBoundsVisitor>
#include <osg/GL>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Image>
#include <osg/LightModel>
#include <osg/LightSource>
#include <osg/Material>
#include <osg/MatrixTransform>
#include <osg/Version>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>
#include <osgShadow/ShadowMap>
#include <osgShadow/ShadowedScene>
#include <osgShadow/SoftShadowMap>
#include <osgShadow/ViewDependentShadowMap>
#include <osgUtil/SmoothingVisitor>
#include <osgViewer/Viewer>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

// --- The scene, as in makeBunnySpot -------------------------------------------------------------
constexpr double kPi = 3.14159265358979323846;
const char* const kDefaultObj = "/usr/share/glmark2/models/bunny.obj";
constexpr double kBunnyHeight = 1.2;     // m, standing on y = 0
constexpr float kGroundHalfSize = 4.0f;  // m: an 8 m square
const osg::Vec3 kGroundAlbedo(0.85f, 0.8f, 0.75f);
const osg::Vec3 kBunnyAlbedo(0.85f, 0.8f, 0.7f);
const osg::Vec3d kSpotPosition(-2.0, 3.5, 1.5);
const osg::Vec3d kSpotAim(2.0, -3.3, -1.5);  // normalised below
constexpr double kSpotOuter = 0.7;           // rad
constexpr double kSpotInner = 0.55;          // rad
const osg::Vec3 kSpotColor(1.0f, 0.9f, 0.8f);
constexpr double kSpotIntensity = 60.0;  // cd
const osg::Vec3d kEye(2.6, 2.2, 3.4);
const osg::Vec3d kTarget(0.0, 0.5, 0.0);
constexpr double kYfov = 0.7;  // rad
constexpr double kNear = 0.05;
constexpr double kFar = 50.0;
constexpr float kAmbient = 0.03f;  // our renderer's default ambient radiance
constexpr int kShadowMapSize = 2048;

// Traversal masks: what receives and what casts.
constexpr unsigned kReceives = 0x1;
constexpr unsigned kCasts = 0x2;

double degrees(double rad) { return rad * 180.0 / kPi; }

struct Options {
    std::string mode;
    int warmup = 5;
    int frames = 60;
    std::string png;
    int width = 1280;
    int height = 720;
    int grid = 256;
    std::string obj = kDefaultObj;
    /// `soft`'s penumbra width in shadow-map texture units (OSG's SoftShadowMap::setSoftnessWidth).
    float softness = 0.005f;
};

[[noreturn]] void usage(const std::string& problem) {
    std::cerr << "osg_bunny: " << problem << "\n"
              << "usage: osg_bunny none|sm|vdsm|soft [--warmup W] [--frames N] [--png PATH] [--size WxH]"
                 " [--grid N] [--obj PATH] [--softness W]\n";
    std::exit(2);
}

int parseInt(const std::string& flag, const std::string& text, int lo, int hi) {
    char* end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || v < lo || v > hi) {
        usage(flag + ": expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got '" + text +
              "'");
    }
    return static_cast<int>(v);
}

Options parseArgs(int argc, char** argv) {
    if (argc < 2) usage("missing mode");
    Options o;
    o.mode = argv[1];
    if (o.mode != "none" && o.mode != "sm" && o.mode != "vdsm" && o.mode != "soft")
        usage("unknown mode '" + o.mode + "'");
    for (int i = 2; i < argc; ++i) {
        const std::string flag = argv[i];
        if (i + 1 >= argc) usage(flag + ": missing value");
        const std::string value = argv[++i];
        if (flag == "--warmup") {
            o.warmup = parseInt(flag, value, 0, 100000);
        } else if (flag == "--frames") {
            o.frames = parseInt(flag, value, 1, 100000);
        } else if (flag == "--png") {
            o.png = value;
        } else if (flag == "--grid") {
            o.grid = parseInt(flag, value, 1, 2048);
        } else if (flag == "--obj") {
            o.obj = value;
        } else if (flag == "--softness") {
            char* end = nullptr;
            const double w = std::strtod(value.c_str(), &end);
            if (value.empty() || *end != '\0' || !(w > 0.0 && w <= 1.0))
                usage("--softness: expected a width in (0, 1], got '" + value + "'");
            o.softness = static_cast<float>(w);
        } else if (flag == "--size") {
            const auto x = value.find('x');
            if (x == std::string::npos) usage("--size: expected WxH, got '" + value + "'");
            o.width = parseInt(flag, value.substr(0, x), 1, 16384);
            o.height = parseInt(flag, value.substr(x + 1), 1, 16384);
        } else {
            usage("unknown option '" + flag + "'");
        }
    }
    return o;
}

/// Matte material matching ours (engine/src/scene/builtin_scenes.cpp, `matte`): our shading is
/// albedo/pi * E plus a normalised Blinn-Phong lobe 0.04 * (n+8)/8 /pi; the 1/pi is folded into
/// the light's attenuation below, so the fixed-function factors are albedo and 0.04 * (n+8)/8.
osg::ref_ptr<osg::Material> matte(const osg::Vec3& albedo) {
    constexpr float shininess = 24.0f;
    const float spec = 0.04f * (shininess + 8.0f) / 8.0f;
    osg::ref_ptr<osg::Material> m = new osg::Material;
    m->setColorMode(osg::Material::OFF);
    // Ambient = albedo, so the light model's ambient gives our `ambient * albedo`.
    m->setAmbient(osg::Material::FRONT_AND_BACK, osg::Vec4(albedo, 1.0f));
    m->setDiffuse(osg::Material::FRONT_AND_BACK, osg::Vec4(albedo, 1.0f));
    m->setSpecular(osg::Material::FRONT_AND_BACK, osg::Vec4(spec, spec, spec, 1.0f));
    m->setEmission(osg::Material::FRONT_AND_BACK, osg::Vec4(0, 0, 0, 1));
    m->setShininess(osg::Material::FRONT_AND_BACK, shininess);
    return m;
}

/// The ground as an n x n grid of quads: fixed-function lighting is evaluated per vertex, so a
/// 4-vertex plane would interpolate the spot's cone away (our ground is lit per pixel).
osg::ref_ptr<osg::Geometry> makeGround(int n) {
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> positions = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec3Array> normals = new osg::Vec3Array;
    positions->reserve(static_cast<std::size_t>(n + 1) * (n + 1));
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            const float x = -kGroundHalfSize + 2.0f * kGroundHalfSize * static_cast<float>(i) / static_cast<float>(n);
            const float z = -kGroundHalfSize + 2.0f * kGroundHalfSize * static_cast<float>(j) / static_cast<float>(n);
            positions->push_back(osg::Vec3(x, 0.0f, z));
            normals->push_back(osg::Vec3(0.0f, 1.0f, 0.0f));
        }
    }
    osg::ref_ptr<osg::DrawElementsUInt> tris = new osg::DrawElementsUInt(GL_TRIANGLES);
    tris->reserve(static_cast<std::size_t>(n) * n * 6);
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const unsigned a = static_cast<unsigned>(j * (n + 1) + i);
            const unsigned b = a + 1;
            const unsigned c = a + static_cast<unsigned>(n + 1);
            const unsigned d = c + 1;
            // Counter-clockwise seen from +y: the front face looks up, at the light.
            for (unsigned v : {a, c, b, b, c, d}) tris->push_back(v);
        }
    }
    g->setVertexArray(positions.get());
    g->setNormalArray(normals.get(), osg::Array::BIND_PER_VERTEX);
    g->addPrimitiveSet(tris.get());
    return g;
}

/// Geometry statistics, and buffer objects instead of display lists (OSG 3.6's default for
/// compatibility contexts): our renderer draws from buffer objects too.
class PrepareGeometry : public osg::NodeVisitor {
public:
    PrepareGeometry() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
    std::size_t vertices = 0;
    std::size_t triangles = 0;
    bool missingNormals = false;

    void apply(osg::Geometry& g) override {
        g.setUseDisplayList(false);
        g.setUseVertexBufferObjects(true);
        if (g.getVertexArray() != nullptr) vertices += g.getVertexArray()->getNumElements();
        if (g.getNormalArray() == nullptr) missingNormals = true;
        for (unsigned p = 0; p < g.getNumPrimitiveSets(); ++p) {
            const osg::PrimitiveSet* ps = g.getPrimitiveSet(p);
            if (ps->getMode() == GL_TRIANGLES)
                triangles += ps->getNumIndices() / 3;
            else if (ps->getMode() == GL_TRIANGLE_STRIP || ps->getMode() == GL_TRIANGLE_FAN)
                triangles += ps->getNumIndices() >= 2 ? ps->getNumIndices() - 2 : 0;
        }
    }
};

/// A light whose brightness follows ours as far as fixed function can: our spot gives
/// intensity * colour / d^2 * smoothstep(cos outer, cos inner, cos angle), times albedo/pi.
osg::ref_ptr<osg::LightSource> makeSpot() {
    osg::ref_ptr<osg::Light> light = new osg::Light(0);
    osg::Vec3d aim = kSpotAim;
    aim.normalize();
    light->setPosition(osg::Vec4(kSpotPosition, 1.0));
    light->setDirection(aim);
    light->setAmbient(osg::Vec4(0, 0, 0, 1));
    light->setDiffuse(osg::Vec4(kSpotColor, 1.0f));
    light->setSpecular(osg::Vec4(kSpotColor, 1.0f));
    // Inverse square with our candela and the BRDF's 1/pi: 1 / (k d^2) = (I/pi) / d^2.
    light->setConstantAttenuation(0.0f);
    light->setLinearAttenuation(0.0f);
    light->setQuadraticAttenuation(static_cast<float>(kPi / kSpotIntensity));
    // Fixed function falls off as cos^e inside the cutoff and drops to 0 there; our smoothstep
    // is 1 inside the inner cone and reaches 0 at the outer. The exponent makes cos^e 0.5 halfway
    // between inner and outer, where our smoothstep is 0.5 too; OSG's centre is still dimmer and
    // its edge a step (from about 0.4 to 0).
    light->setSpotCutoff(static_cast<float>(degrees(kSpotOuter)));
    const double mid = 0.5 * (kSpotInner + kSpotOuter);
    light->setSpotExponent(static_cast<float>(std::log(0.5) / std::log(std::cos(mid))));
    osg::ref_ptr<osg::LightSource> source = new osg::LightSource;
    source->setLight(light.get());
    source->setReferenceFrame(osg::LightSource::RELATIVE_RF);  // world coordinates under the view matrix
    return source;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Runs after the main camera has drawn everything (shadow cameras are nested in its render
/// stage), before the buffer swap: waits for the rasteriser, notes the time, and copies the
/// frame out when asked. On llvmpipe the draw calls only queue work; glFinish is what makes
/// the wall clock cover the rasterisation.
struct FinishAndCapture : public osg::Camera::DrawCallback {
    mutable Clock::time_point drawDone;
    mutable std::string renderer;
    mutable std::string version;
    osg::ref_ptr<osg::Image> capture;  // set to capture the next frame
    int width = 0, height = 0;

    void operator()(osg::RenderInfo&) const override {
        glFinish();
        drawDone = Clock::now();
        if (renderer.empty()) {
            const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
            const auto* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
            renderer = r != nullptr ? r : "?";
            version = v != nullptr ? v : "?";
        }
        if (capture.valid()) capture->readPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE);
    }
};

std::string jsonEscape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = parseArgs(argc, argv);

    // --- Bunny: raw OBJ axes (the reader would turn Y-up data to Z-up without noRotation) -----
    osg::ref_ptr<osgDB::Options> objOptions = new osgDB::Options("noRotation");
    osg::ref_ptr<osg::Node> bunny = osgDB::readRefNodeFile(o.obj, objOptions.get());
    if (!bunny) {
        std::cerr << "osg_bunny: cannot read " << o.obj << " (install glmark2-data and the OSG obj plugin)\n";
        return 1;
    }
    PrepareGeometry bunnyCheck;
    bunny->accept(bunnyCheck);
    if (bunnyCheck.missingNormals) {
        // Smooth normals when the file has none, as our reader does.
        osgUtil::SmoothingVisitor smooth;
        bunny->accept(smooth);
    }
    PrepareGeometry bunnyStats;
    bunny->accept(bunnyStats);
    osg::ComputeBoundsVisitor boundsVisitor;
    bunny->accept(boundsVisitor);
    const osg::BoundingBox b = boundsVisitor.getBoundingBox();
    const double scale = kBunnyHeight / std::max(1e-6, static_cast<double>(b.yMax() - b.yMin()));
    // Scale first, then stand the bunny on the ground centred on the origin (as ours).
    osg::ref_ptr<osg::MatrixTransform> bunnyXform = new osg::MatrixTransform(
        osg::Matrix::scale(scale, scale, scale) *
        osg::Matrix::translate(-scale * b.center().x(), -scale * b.yMin(), -scale * b.center().z()));
    bunnyXform->addChild(bunny.get());
    bunnyXform->setNodeMask(kReceives | kCasts);
    bunnyXform->getOrCreateStateSet()->setAttributeAndModes(matte(kBunnyAlbedo).get());
    // The uniform scale shortens the normals; fixed function must rescale them.
    bunnyXform->getOrCreateStateSet()->setMode(GL_RESCALE_NORMAL, osg::StateAttribute::ON);

    osg::ref_ptr<osg::Geode> ground = new osg::Geode;
    ground->addDrawable(makeGround(o.grid).get());
    // Receive only: nothing lies under the ground, so as a caster it would change no pixel, and
    // OSG's depth passes cull front faces anyway; it would only make OSG transform the dense
    // grid a second time per frame (ours draws its 512-triangle ground into the map).
    ground->setNodeMask(kReceives);
    ground->getOrCreateStateSet()->setAttributeAndModes(matte(kGroundAlbedo).get());
    PrepareGeometry groundStats;
    ground->accept(groundStats);

    // --- Shadowed scene, or a plain group without shadows -------------------------------------
    osg::ref_ptr<osg::Group> scene;
    osg::ref_ptr<osg::LightSource> spot = makeSpot();
    if (o.mode == "none") {
        scene = new osg::Group;
    } else {
        osg::ref_ptr<osgShadow::ShadowedScene> shadowed = new osgShadow::ShadowedScene;
        osgShadow::ShadowSettings* settings = shadowed->getShadowSettings();
        settings->setReceivesShadowTraversalMask(kReceives);
        settings->setCastsShadowTraversalMask(kCasts);
        settings->setTextureSize(osg::Vec2s(kShadowMapSize, kShadowMapSize));
        settings->setLightNum(0);
        if (o.mode == "vdsm") {
            // One map for the one light (no parallel splits), sized like ours.
            settings->setNumShadowMapsPerLight(1);
            shadowed->setShadowTechnique(new osgShadow::ViewDependentShadowMap);
        } else {
            osg::ref_ptr<osgShadow::ShadowMap> sm;
            if (o.mode == "soft") {
                osg::ref_ptr<osgShadow::SoftShadowMap> soft = new osgShadow::SoftShadowMap;
                // Penumbra width in shadow-map texture units: our 0.08 m emitter makes a penumbra
                // of about 4 cm at the bunny's feet, ~0.005 of the 7-8 m the map spans there
                // (the default; a wider emitter scales it, benchmarks/run_peers.sh).
                soft->setSoftnessWidth(o.softness);
                sm = soft;
            } else {
                sm = new osgShadow::ShadowMap;
            }
            sm->setTextureSize(osg::Vec2s(kShadowMapSize, kShadowMapSize));
            sm->setLight(spot.get());
            // Its shader multiplies the whole vertex colour by (x + y * visibility); the OSG
            // default (0.5, 0.5) leaves shadows half lit. (0, 1) makes visibility scale the light
            // as ours does (the 3 % ambient goes dark too, a few 1/255 in the image).
            sm->setAmbientBias(osg::Vec2(0.0f, 1.0f));
            shadowed->setShadowTechnique(sm.get());
        }
        scene = shadowed;
    }
    // The light first, so its position is known when the shadow technique culls the rest.
    scene->addChild(spot.get());
    scene->addChild(ground.get());
    scene->addChild(bunnyXform.get());

    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(scene.get());
    osg::StateSet* rootState = root->getOrCreateStateSet();
    spot->setStateSetModes(*rootState, osg::StateAttribute::ON);
    rootState->setMode(GL_LIGHTING, osg::StateAttribute::ON);
    rootState->setMode(GL_CULL_FACE, osg::StateAttribute::OFF);  // ours draws two-sided too
    osg::ref_ptr<osg::LightModel> lightModel = new osg::LightModel;
    lightModel->setAmbientIntensity(osg::Vec4(kAmbient, kAmbient, kAmbient, 1.0f));
    lightModel->setLocalViewer(true);  // specular half-vector towards the eye, as ours
    lightModel->setTwoSided(false);
    rootState->setAttributeAndModes(lightModel.get());

    // --- Window, camera, viewer ------------------------------------------------------------------
    osg::ref_ptr<osg::GraphicsContext::Traits> traits = new osg::GraphicsContext::Traits;
    traits->readDISPLAY();  // the X server xvfb-run started, not :0
    traits->setUndefinedScreenDetailsToDefaultScreen();
    traits->x = 0;
    traits->y = 0;
    traits->width = o.width;
    traits->height = o.height;
    traits->windowDecoration = false;
    traits->doubleBuffer = true;
    traits->vsync = false;  // time the work, not the display
    osg::ref_ptr<osg::GraphicsContext> gc = osg::GraphicsContext::createGraphicsContext(traits.get());
    if (!gc) {
        std::cerr << "osg_bunny: cannot create a " << o.width << "x" << o.height
                  << " window (is DISPLAY set? run under xvfb-run)\n";
        return 1;
    }

    osgViewer::Viewer viewer;
    viewer.setThreadingModel(osgViewer::Viewer::SingleThreaded);  // one frame = one wall-clock span
    viewer.setReleaseContextAtEndOfFrameHint(false);              // keep it current for glFinish
    viewer.setLightingMode(osg::View::NO_LIGHT);                  // no headlight: only our spot
    viewer.setSceneData(root.get());
    osg::Camera* camera = viewer.getCamera();
    camera->setGraphicsContext(gc.get());
    camera->setViewport(0, 0, o.width, o.height);
    camera->setDrawBuffer(GL_BACK);
    camera->setReadBuffer(GL_BACK);
    camera->setClearColor(osg::Vec4(0, 0, 0, 1));
    camera->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    camera->setProjectionMatrixAsPerspective(degrees(kYfov), static_cast<double>(o.width) / o.height, kNear, kFar);
    camera->setViewMatrixAsLookAt(kEye, kTarget, osg::Vec3d(0, 1, 0));
    camera->setSmallFeatureCullingPixelSize(0.0f);
    osg::ref_ptr<FinishAndCapture> finish = new FinishAndCapture;
    finish->width = o.width;
    finish->height = o.height;
    camera->setFinalDrawCallback(finish.get());
    viewer.realize();
    if (!viewer.isRealized()) {
        std::cerr << "osg_bunny: the viewer did not realise its window\n";
        return 1;
    }

    // --- Frames: W warm-up (shader compilation, first uploads), then N timed ---------------------
    std::vector<double> frameMs, drawMs;
    const int total = o.warmup + o.frames;
    for (int f = 0; f < total; ++f) {
        const bool last = f + 1 == total;
        if (last && !o.png.empty()) finish->capture = new osg::Image;
        const Clock::time_point t0 = Clock::now();
        viewer.frame();  // event, update, cull (shadow cameras included), draw, swap
        glFinish();      // the swap's copy to the window is part of the frame
        const Clock::time_point t1 = Clock::now();
        if (f >= o.warmup) {
            frameMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
            drawMs.push_back(std::chrono::duration<double, std::milli>(finish->drawDone - t0).count());
        }
    }
    if (finish->capture.valid()) {
        if (!osgDB::writeImageFile(*finish->capture, o.png)) {
            std::cerr << "osg_bunny: cannot write " << o.png << " (is the OSG png plugin installed?)\n";
            return 1;
        }
    }

    const auto [minIt, maxIt] = std::minmax_element(frameMs.begin(), frameMs.end());
    std::printf(
        "{\"engine\": \"OpenSceneGraph %s\", \"mode\": \"%s\", \"renderer\": \"%s\", "
        "\"glVersion\": \"%s\",\n"
        " \"size\": [%d, %d], \"shadowMapSize\": %d, \"warmupFrames\": %d, \"frames\": %d,\n"
        " \"frameMs\": {\"median\": %.3f, \"min\": %.3f, \"max\": %.3f},\n"
        " \"drawMs\": {\"median\": %.3f},\n"
        " \"bunny\": {\"vertices\": %zu, \"triangles\": %zu, \"scale\": %.6f},\n"
        " \"ground\": {\"vertices\": %zu, \"triangles\": %zu}}\n",
        osgGetVersion(), o.mode.c_str(), jsonEscape(finish->renderer).c_str(), jsonEscape(finish->version).c_str(),
        o.width, o.height, o.mode == "none" ? 0 : kShadowMapSize, o.warmup, o.frames, median(frameMs), *minIt, *maxIt,
        median(drawMs), bunnyStats.vertices, bunnyStats.triangles, scale, groundStats.vertices, groundStats.triangles);
    return 0;
}
