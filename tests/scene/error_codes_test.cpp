// Every kind of bad input gives its `ErrorCode` (and, for a glTF element, the element), so a
// program can react to the cause without reading the message.
#include <gtest/gtest.h>

#include <shadow/image_io.h>
#include <shadow/metrics.h>
#include <shadow/result.h>
#include <shadow/scene.h>

#include <limits>
#include <string>

#include "scene/gltf_import.h"
#include "scene/gltf_test_support.h"

namespace shadow {
namespace {

using namespace gltf_test;  // NOLINT(google-build-using-namespace): the files' vocabulary

Error loadFailure(const fs::path& path) {
    const Result<Scene> result = loadGltf(path.string());
    EXPECT_FALSE(result.ok()) << path;
    return result.ok() ? Error{} : result.error();
}

Error memoryFailure(const std::string& json) {
    const Result<Scene> result = gltf::loadGltfFromMemory(json, "mem.gltf");
    EXPECT_FALSE(result.ok()) << json;
    return result.ok() ? Error{} : result.error();
}

TEST(ErrorCodes, EveryCodeHasItsName) {
    EXPECT_STREQ(errorCodeName(ErrorCode::FileUnreadable), "FileUnreadable");
    EXPECT_STREQ(errorCodeName(ErrorCode::Internal), "Internal");
    EXPECT_STREQ(errorCodeName(static_cast<ErrorCode>(200)), "Unknown");
}

TEST(ErrorCodes, AFileThatCannotBeReadIsFileUnreadable) {
    EXPECT_EQ(loadFailure(testDir() / "absent.gltf").code, ErrorCode::FileUnreadable);
    EXPECT_EQ(loadFailure(testDir()).code, ErrorCode::FileUnreadable) << "a folder is not a scene";
    EXPECT_EQ(readExr((testDir() / "absent.exr").string(), {"Y"}).error().code, ErrorCode::FileUnreadable);
}

TEST(ErrorCodes, BrokenSyntaxAndNestingAreMalformedFile) {
    EXPECT_EQ(memoryFailure(R"({"asset": {"version": "2.0"}, "nodes": [)").code, ErrorCode::MalformedFile);
    // Appended, not `literal + std::string(...)`: GCC 12 reports that form as an out-of-bounds
    // copy (-Warray-bounds, a false positive) where it is inlined into a larger unit.
    std::string deep = R"({"asset": {"version": "2.0"}, "extras": )";
    deep.append(100, '[').append(100, ']').append("}");
    EXPECT_EQ(memoryFailure(deep).code, ErrorCode::MalformedFile);
}

TEST(ErrorCodes, ABadElementIsInvalidValueNamingTheElement) {
    Doc doc;
    doc.node({{"children", {7}}});
    const Error e = loadFailure(doc.write(testDir() / "s.gltf"));
    EXPECT_EQ(e.code, ErrorCode::InvalidValue);
    EXPECT_EQ(e.element, "nodes[0].children");
    EXPECT_NE(e.message.find("s.gltf: nodes[0].children"), std::string::npos) << e.message;
}

TEST(ErrorCodes, AnOrthographicCameraIsUnsupported) {
    Doc doc;
    doc.push("cameras",
             {{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}});
    doc.node({{"camera", 0}});
    const Error e = loadFailure(doc.write(testDir() / "s.gltf"));
    EXPECT_EQ(e.code, ErrorCode::Unsupported);
    EXPECT_EQ(e.element, "cameras[0]");
}

TEST(ErrorCodes, ComparisonsTellMismatchFromBadTruth) {
    ImageF estimate = makeImage(4, 4, 1);
    ImageF truth = makeImage(4, 2, 1);
    EXPECT_EQ(compareVisibility(estimate, truth).error().code, ErrorCode::MismatchedInputs);
    truth = makeImage(4, 4, 1);
    truth.pixels[5] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(compareVisibility(estimate, truth).error().code, ErrorCode::InvalidValue);
}

TEST(ErrorCodes, WithinAddsWhereButKeepsTheCause) {
    const Error inner{ErrorCode::LimitExceeded, "too many", "nodes"};
    const Error outer = inner.within("scene.gltf: ");
    EXPECT_EQ(outer.code, ErrorCode::LimitExceeded);
    EXPECT_EQ(outer.element, "nodes");
    EXPECT_EQ(outer.message, "scene.gltf: too many");
}

}  // namespace
}  // namespace shadow
