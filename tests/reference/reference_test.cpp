// The reference tracer against closed forms and geometry: builtin:plates' exact visibility,
// camera rays against analytic ray/plane intersections (its own and the engine's position.exr),
// positions mode against camera mode, and the shadow_reference CLI contract.
#include <gtest/gtest.h>

#include "test_support.h"
#include <shadow/image_io.h>
#include <shadow/scene.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "reference/closed_forms.h"
#include <shadow/reference.h>

namespace shadow::reference {
namespace {

namespace fs = std::filesystem;

using test::kExitBadInput;

// ---- Helpers ----

using test::TempDir;
using CliRun = test::ProcessRun;

std::string quoted(const std::string& s) { return test::shellQuoted(s); }

/// Runs `program` (a binary in SHADOW_BIN_DIR) with `args` (quoted where needed).
CliRun runProgram(const TempDir& tmp, const std::string& program, const std::string& args) {
    return test::runProgram(std::string(SHADOW_BIN_DIR "/") + program, args, tmp / (program + ".log"));
}

/// builtin:plates posed at t = 0 and its first camera's view for a `width` x `height` image.
struct PlatesSetup {
    Scene scene = makePlatesScene();
    CameraView view;
    PlatesSetup(int width, int height) {
        animate(scene.world, 0.0);
        (void)updateTransforms(scene.world);
        view = makeCameraView(scene.world, scene.cameras.at(0), static_cast<float>(width) / static_cast<float>(height));
    }
};

ReferenceResult trace(PlatesSetup& setup, int width, int height, int samples, std::uint32_t seed = 1) {
    ReferenceOptions options;
    options.width = width;
    options.height = height;
    options.samples = samples;
    options.seed = seed;
    Result<ReferenceResult> r = traceVisibility(setup.scene, setup.view, options);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return std::move(r.value());
}

/// What the camera ray through image point (px, py) meets first in builtin:plates, derived
/// independently of the tracer: unproject the NDC point through glm::perspective.
struct AnalyticHit {
    int surface = -1;  ///< -1 nothing, 0 the receiver, k + 1 plate k
    glm::dvec3 wsPosition{0.0};
};

AnalyticHit analyticHit(const CameraView& view, int width, int height, double px, double py) {
    const glm::dmat4 clipFromWorld = glm::perspective(static_cast<double>(view.yfov), static_cast<double>(view.aspect),
                                                      static_cast<double>(view.znear), static_cast<double>(view.zfar)) *
                                     view.viewFromWorld;
    const glm::dmat4 worldFromClip = glm::inverse(clipFromWorld);
    const glm::dvec2 ndc(2.0 * px / width - 1.0, 1.0 - 2.0 * py / height);  // (0,0) top-left
    const glm::dvec4 nearH = worldFromClip * glm::dvec4(ndc, -1.0, 1.0);
    const glm::dvec4 farH = worldFromClip * glm::dvec4(ndc, 1.0, 1.0);
    const glm::dvec3 origin = glm::dvec3(nearH) / nearH.w;
    const glm::dvec3 dir = glm::dvec3(farH) / farH.w - origin;

    const PlatesGeometry g;
    AnalyticHit best;
    double bestT = HUGE_VAL;
    auto tryPlane = [&](int surface, double y, const glm::dvec2& center, double half) {
        const double t = (y - origin.y) / dir.y;
        if (!(t > 0.0 && t < bestT)) return;
        const glm::dvec3 p = origin + t * dir;
        if (std::abs(p.x - center.x) > half || std::abs(p.z - center.y) > half) return;
        bestT = t;
        best = {surface, p};
    };
    tryPlane(0, 0.0, {0.0, 0.0}, g.receiverHalfSize);
    for (std::size_t k = 0; k < g.plates.size(); ++k) {
        const PlatesGeometry::Plate& plate = g.plates[k];
        tryPlane(static_cast<int>(k) + 1, plate.center.y, {plate.center.x, plate.center.z}, plate.halfSize);
    }
    return best;
}

/// True when the pixel's centre and its four corners all see the receiver: no silhouette or
/// receiver border crosses it, so any rasteriser must cover its centre with the receiver.
bool interiorReceiverPixel(const CameraView& view, int width, int height, int x, int y) {
    for (const glm::dvec2& o :
         {glm::dvec2(0.5, 0.5), glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(0, 1), glm::dvec2(1, 1)}) {
        if (analyticHit(view, width, height, x + o.x, y + o.y).surface != 0) return false;
    }
    return true;
}

double positionError(const ImageF& positions, int x, int y, const glm::dvec3& expected) {
    const glm::dvec3 p(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2));
    return glm::length(p - expected);
}

// ---- Closed form ----

TEST(Reference, PlatesMatchClosedFormWithinThreeStandardErrors) {
    constexpr int kWidth = 96;
    constexpr int kHeight = 72;
    constexpr int kSamples = 2048;
    PlatesSetup setup(kWidth, kHeight);
    const ReferenceResult r = trace(setup, kWidth, kHeight, kSamples, 7);
    ASSERT_EQ(r.visibility.size(), 1u);
    EXPECT_EQ(r.lights[0].raysPerPixel, kSamples);

    const PlatesGeometry g;
    int receiver = 0;
    int penumbra = 0;
    int within = 0;
    double sumError = 0.0;
    double sumSe = 0.0;
    double worstSigma = 0.0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            if (r.wsPosition.at(x, y, 3) < 0.5f || std::abs(r.wsPosition.at(x, y, 1)) > 1e-4f) {
                // Background and the plates (they do not receive shadows): V = 1 exactly.
                EXPECT_EQ(r.visibility[0].at(x, y, 0), 1.0f) << "pixel (" << x << ", " << y << ")";
                EXPECT_EQ(r.standardError[0].at(x, y, 0), 0.0f);
                continue;
            }
            const glm::dvec3 p(r.wsPosition.at(x, y, 0), r.wsPosition.at(x, y, 1), r.wsPosition.at(x, y, 2));
            const double exact = platesVisibility(g, p);
            const double v = r.visibility[0].at(x, y, 0);
            const double se = r.standardError[0].at(x, y, 0);
            const double error = std::abs(v - exact);
            ++receiver;
            // σ also at the exact value: the estimate's own SE is 0 when every ray agrees.
            const double sigma = std::max(se, binomialStandardError(exact, kSamples));
            within += error <= 3.0 * sigma + 1e-9 ? 1 : 0;
            if (exact > 0.0 && exact < 1.0) {
                ++penumbra;
                sumError += error;
                sumSe += se;
            }
            if (se > 0.0) worstSigma = std::max(worstSigma, error / se);
        }
    }
    const double fractionWithin = static_cast<double>(within) / receiver;
    const double errorOverSe = sumSe > 0.0 ? sumError / sumSe : 0.0;
    std::printf(
        "[ measured ] plates %dx%d, %d rays: %d receiver pixels, %d in penumbra; %.4f within 3 SE; "
        "mean |err| / mean SE = %.3f (penumbra); worst %.2f SE; trace %.2f s on %d threads\n",
        kWidth, kHeight, kSamples, receiver, penumbra, fractionWithin, errorOverSe, worstSigma, r.traceSeconds,
        r.threads);
    EXPECT_GT(receiver, kWidth * kHeight / 2);
    EXPECT_GT(penumbra, 300);
    EXPECT_GE(fractionWithin, 0.997);
    EXPECT_LT(errorOverSe, 1.0);
}

// ---- Geometry of the camera rays ----

TEST(Reference, EnginePositionsMatchCameraRayPlaneIntersections) {
    constexpr int kWidth = 96;
    constexpr int kHeight = 72;
    constexpr double kEngineTolerance = 2e-3;     // m: rasterised, float, camera-relative
    constexpr double kReferenceTolerance = 1e-4;  // m: a double ray/triangle hit stored as float
    TempDir tmp;
    const std::string size = std::to_string(kWidth) + "x" + std::to_string(kHeight);
    const CliRun engine = runProgram(
        tmp, "shadow_render", "builtin:plates --aov position --size " + size + " --out " + quoted(tmp / "engine"));
    ASSERT_EQ(engine.exitCode, 0) << engine.output;
    Result<ImageF> enginePositions = readExr(tmp / "engine/position.exr", {"R", "G", "B", "A"});
    ASSERT_TRUE(enginePositions.ok()) << enginePositions.error().message;
    ASSERT_EQ(enginePositions->width, kWidth);
    ASSERT_EQ(enginePositions->height, kHeight);

    PlatesSetup setup(kWidth, kHeight);
    const ReferenceResult reference = trace(setup, kWidth, kHeight, 1);
    int compared = 0;
    double engineWorst = 0.0;
    double referenceWorst = 0.0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            if (!interiorReceiverPixel(setup.view, kWidth, kHeight, x, y)) continue;
            const glm::dvec3 expected = analyticHit(setup.view, kWidth, kHeight, x + 0.5, y + 0.5).wsPosition;
            ++compared;
            ASSERT_EQ(enginePositions->at(x, y, 3), 1.0f) << "engine pixel (" << x << ", " << y << ")";
            ASSERT_EQ(reference.wsPosition.at(x, y, 3), 1.0f) << "reference pixel (" << x << ", " << y << ")";
            const double e = positionError(*enginePositions, x, y, expected);
            const double rr = positionError(reference.wsPosition, x, y, expected);
            engineWorst = std::max(engineWorst, e);
            referenceWorst = std::max(referenceWorst, rr);
            EXPECT_LE(e, kEngineTolerance) << "engine pixel (" << x << ", " << y << ")";
            EXPECT_LE(rr, kReferenceTolerance) << "reference pixel (" << x << ", " << y << ")";
        }
    }
    std::printf(
        "[ measured ] %d interior receiver pixels: worst position error engine %.3g m, reference "
        "%.3g m\n",
        compared, engineWorst, referenceWorst);
    EXPECT_GT(compared, kWidth * kHeight / 2);

    // The engine's positions shade in positions mode: each finds its surface on the camera ray.
    const CliRun shaded = runProgram(tmp, "shadow_reference",
                                     "builtin:plates --samples 16 --positions " + quoted(tmp / "engine/position.exr") +
                                         " --out " + quoted(tmp / "from-engine"));
    ASSERT_EQ(shaded.exitCode, 0) << shaded.output;
    std::ifstream in(tmp / "from-engine/reference.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    const int covered = j["pixels"]["covered"].get<int>();
    const int withoutSurface = j["pixels"]["positionsWithoutSurface"].get<int>();
    std::printf("[ measured ] engine positions: %d covered, %d without a surface within 0.1 %%\n", covered,
                withoutSurface);
    EXPECT_LE(withoutSurface, covered / 100);
}

// ---- The shadow-ray epsilon ----

// A small scene beside the centre of one that reaches 5e5 m either way (two distant boxes): a
// unit box 1 m above a ground of 1 m cells, a point light 6 m up and 3 m aside. With one epsilon
// for the whole scene (1e-5 of its 1e6 m diagonal: 10 m) the shadow rays start above the box
// and its shadow is lost; with the epsilon of the local geometry it is kept.
TEST(Reference, SmallCasterInAVastSceneKeepsItsShadow) {
    constexpr int kSize = 64;
    Scene scene;
    addMeshInstance(scene.world, "ground", makePlaneMesh(5.0f, 10), Transform{});
    Transform box;
    box.translation = {0.0, 1.5, 0.0};
    addMeshInstance(scene.world, "box", makeBoxMesh(glm::vec3(0.5f)), box);
    for (const double x : {-5e5, 5e5}) {
        Transform far;
        far.translation = {x, 0.5, 0.0};
        addMeshInstance(scene.world, "far", makeBoxMesh(glm::vec3(0.5f)), far);
    }
    Light bulb;
    bulb.type = LightType::Point;
    addLight(scene, "bulb", bulb, Shadow{}, {3.0, 6.0, 0.0}, {0.0, -1.0, 0.0});
    Camera camera;
    camera.zfar = 1e6f;
    addCamera(scene, "eye", camera, {0.0, 9.0, 0.01}, {0.0, 0.0, 0.0});
    animate(scene.world, 0.0);
    (void)updateTransforms(scene.world);
    const CameraView view = makeCameraView(scene.world, scene.cameras[0], 1.0f);
    ReferenceOptions options;
    options.width = kSize;
    options.height = kSize;
    options.samples = 1;
    Result<ReferenceResult> r = traceVisibility(scene, view, options);
    ASSERT_TRUE(r.ok()) << r.error().message;
    // The shadow on the ground, projected from the bulb: the box's top face (y = 2) covers
    // x in [-2.25, -0.75], |z| <= 0.75; its bottom face x in [-1.2, 0], |z| <= 0.6. Ground pixels
    // well inside the top's shadow must be dark, those well clear of both lit.
    int inside = 0, darkInside = 0, outside = 0, litOutside = 0;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            if (r->wsPosition.at(x, y, 3) != 1.0f || std::abs(r->wsPosition.at(x, y, 1)) > 1e-3f) continue;
            const double gx = r->wsPosition.at(x, y, 0);
            const double gz = std::abs(r->wsPosition.at(x, y, 2));
            const float v = r->visibility[0].at(x, y, 0);
            if (gx > -2.1 && gx < -0.9 && gz < 0.6) {
                ++inside;
                darkInside += v == 0.0f ? 1 : 0;
            } else if ((gx > 0.8 || gx < -2.4 || gz > 0.9) && std::max(std::abs(gx), gz) < 4.5) {
                ++outside;
                litOutside += v == 1.0f ? 1 : 0;
            }
        }
    }
    std::printf("[ measured ] shadow-ray epsilon %.3g..%.3g m; %d of %d ground pixels under the box dark\n",
                r->epsilonMin, r->epsilonMax, darkInside, inside);
    EXPECT_GT(inside, kSize * kSize / 100);
    EXPECT_GT(outside, kSize * kSize / 4);
    EXPECT_EQ(darkInside, inside);
    EXPECT_EQ(litOutside, outside);
    EXPECT_LT(r->epsilonMax, 1e-3) << "the epsilon follows the geometry near the camera, not the scene's extent";
}

// ---- Positions mode ----

TEST(Reference, PositionsModeGivesTheVisibilityOfCameraMode) {
    constexpr int kSamples = 128;
    TempDir tmp;
    const std::string common = "builtin:plates --samples " + std::to_string(kSamples) + " --seed 5 --threads 2";
    const CliRun camera = runProgram(tmp, "shadow_reference", common + " --size 64x48 --out " + quoted(tmp / "camera"));
    ASSERT_EQ(camera.exitCode, 0) << camera.output;
    const CliRun positions = runProgram(
        tmp, "shadow_reference",
        common + " --positions " + quoted(tmp / "camera/position.exr") + " --out " + quoted(tmp / "positions"));
    ASSERT_EQ(positions.exitCode, 0) << positions.output;

    const std::vector<std::string> rgba{"R", "G", "B", "A"};
    Result<ImageF> posA = readExr(tmp / "camera/position.exr", rgba);
    Result<ImageF> posB = readExr(tmp / "positions/position.exr", rgba);
    Result<ImageF> visA = readExr(tmp / "camera/visibility_0.exr", {"Y"});
    Result<ImageF> visB = readExr(tmp / "positions/visibility_0.exr", {"Y"});
    Result<ImageF> seA = readExr(tmp / "camera/stderr_0.exr", {"Y"});
    ASSERT_TRUE(posA && posB && visA && visB && seA);
    // The grey picture of the truth beside its EXR: a PNG of the same size.
    std::ifstream png(tmp / "camera/visibility_0.png", std::ios::binary);
    std::string header(24, '\0');
    ASSERT_TRUE(png.read(header.data(), 24)) << "no visibility_0.png";
    EXPECT_EQ(header.substr(1, 3), "PNG");
    EXPECT_EQ(static_cast<unsigned char>(header[19]), 64u) << "PNG width";
    EXPECT_EQ(static_cast<unsigned char>(header[23]), 48u) << "PNG height";
    ASSERT_EQ(visB->width, 64);
    ASSERT_EQ(visB->height, 48);
    EXPECT_EQ(posA->pixels, posB->pixels);

    int differing = 0;
    double sumDiff = 0.0;
    int penumbra = 0;
    for (std::size_t p = 0; p < visA->pixels.size(); ++p) {
        const double a = visA->pixels[p];
        const double diff = std::abs(a - visB->pixels[p]);
        differing += diff > 0.0 ? 1 : 0;
        sumDiff += diff;
        penumbra += a > 0.0 && a < 1.0 ? 1 : 0;
        EXPECT_NEAR(seA->pixels[p], std::sqrt(a * (1.0 - a) / kSamples), 1e-6);
    }
    const double meanDiff = sumDiff / static_cast<double>(visA->pixels.size());
    std::printf(
        "[ measured ] positions vs camera mode, same seed: %d of %zu pixels differ, mean |diff| "
        "%.2e\n",
        differing, visA->pixels.size(), meanDiff);
    EXPECT_GT(penumbra, 100);
    // Same points to float precision and the same sample patterns: only a ray grazing a plate
    // edge within ~1e-7 m may flip.
    EXPECT_LE(differing, static_cast<int>(visA->pixels.size() / 200));
    EXPECT_LT(meanDiff, 1e-4);

    std::ifstream in(tmp / "positions/reference.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["mode"], "positions");
    EXPECT_EQ(j["samplesPerPixel"], kSamples);
    EXPECT_EQ(j["size"], nlohmann::json::array({64, 48}));
    EXPECT_EQ(j["threads"], 2);
    ASSERT_EQ(j["lights"].size(), 1u);
    EXPECT_EQ(j["lights"][0]["raysPerPixel"], kSamples);
    EXPECT_GT(j["lights"][0]["meanStandardError"].get<double>(), 0.0);
    EXPECT_GE(j["lights"][0]["maxStandardError"].get<double>(), j["lights"][0]["meanStandardError"].get<double>());
    EXPECT_GE(j["timeSeconds"]["trace"].get<double>(), 0.0);
    EXPECT_EQ(j["pixels"]["positionsWithoutSurface"], 0);
}

TEST(Reference, ImagesDoNotDependOnTheThreadCount) {
    PlatesSetup setup(40, 30);
    ReferenceOptions options;
    options.width = 40;
    options.height = 30;
    options.samples = 64;
    options.threads = 1;
    Result<ReferenceResult> one = traceVisibility(setup.scene, setup.view, options);
    options.threads = 3;
    Result<ReferenceResult> three = traceVisibility(setup.scene, setup.view, options);
    ASSERT_TRUE(one && three);
    EXPECT_EQ(one->visibility[0].pixels, three->visibility[0].pixels);
    EXPECT_EQ(three->threads, 3);
}

// ---- The CLI contract ----

TEST(Reference, CliRefusesNonFinitePositionsAndSkipsPositionsBeyondReach) {
    TempDir tmp;
    const std::vector<std::string> rgba = {"R", "G", "B", "A"};
    ImageF positions = makeImage(8, 6, 4);
    for (int y = 0; y < 6; ++y) {
        for (int x = 0; x < 8; ++x) positions.at(x, y, 3) = 1.0f;  // covered, at the origin
    }
    positions.at(3, 2, 0) = 1e20f;
    positions.at(5, 4, 2) = -3e38f;
    ASSERT_TRUE(writeExr(tmp / "far.exr", positions, rgba).ok());
    const CliRun far = runProgram(
        tmp, "shadow_reference",
        "builtin:plates --samples 4 --positions " + quoted(tmp / "far.exr") + " --out " + quoted(tmp / "far"));
    ASSERT_EQ(far.exitCode, 0) << far.output;
    EXPECT_NE(far.output.find("2 positions beyond"), std::string::npos) << far.output;
    std::ifstream in(tmp / "far/reference.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["pixels"]["positionsBeyondReach"], 2);
    EXPECT_EQ(j["pixels"]["covered"], 8 * 6 - 2);
    Result<ImageF> written = readExr(tmp / "far/position.exr", rgba);
    ASSERT_TRUE(written.ok()) << written.error().message;
    EXPECT_EQ(written->at(3, 2, 3), 0.0f) << "beyond reach: background";

    positions.at(6, 1, 1) = std::numeric_limits<float>::quiet_NaN();
    ASSERT_TRUE(writeExr(tmp / "nan.exr", positions, rgba).ok());
    const CliRun nan =
        runProgram(tmp, "shadow_reference",
                   "builtin:plates --positions " + quoted(tmp / "nan.exr") + " --out " + quoted(tmp / "nan"));
    EXPECT_EQ(nan.exitCode, kExitBadInput) << nan.output;
    EXPECT_NE(nan.output.find("pixel (6, 1)"), std::string::npos) << nan.output;
    EXPECT_FALSE(fs::exists(tmp / "nan")) << "bad input writes nothing";
}

TEST(Reference, CliRejectsBadInputWithExitCodeTwoAndWritesNothing) {
    TempDir tmp;
    const std::string regularFile = tmp / "a-file";
    std::ofstream(regularFile) << "not a folder";
    ASSERT_TRUE(writeExr(tmp / "small.exr", makeImage(8, 6, 4), {"R", "G", "B", "A"}).ok());
    ASSERT_TRUE(writeExr(tmp / "grey.exr", makeImage(8, 6, 1), {"Y"}).ok());
    const std::string out = " --out " + quoted(tmp / "out");
    const std::vector<std::string> cases = {
        "",                                  // no scene
        "builtin:nonexistent" + out,         // unknown scene
        quoted(tmp / "missing.gltf") + out,  // missing file
        "builtin:plates --size 0x5" + out,
        "builtin:plates --size wide" + out,
        "builtin:plates --samples 0" + out,
        "builtin:plates --samples -3" + out,
        "builtin:plates --samples many" + out,
        "builtin:plates --threads -1" + out,
        "builtin:plates --camera 5" + out,
        "builtin:plates --camera -1" + out,
        "builtin:plates --time nan" + out,
        "builtin:plates --seed -1" + out,
        "builtin:plates --positions " + quoted(tmp / "missing.exr") + out,
        "builtin:plates --positions " + quoted(tmp / "grey.exr") + out,                   // no R,G,B,A
        "builtin:plates --positions " + quoted(tmp / "small.exr") + " --size 9x6" + out,  // size mismatch
        "builtin:plates --bogus" + out,
        "builtin:plates --size 8x6 --out " + quoted(regularFile),  // output is not a folder
    };
    for (const std::string& args : cases) {
        const CliRun run = runProgram(tmp, "shadow_reference", args);
        EXPECT_EQ(run.exitCode, kExitBadInput) << "args: " << args << "\n" << run.output;
        EXPECT_NE(run.output.find("shadow_reference"), std::string::npos) << "args: " << args;
        EXPECT_FALSE(fs::exists(tmp / "out")) << "args: " << args;
    }
}

}  // namespace
}  // namespace shadow::reference
