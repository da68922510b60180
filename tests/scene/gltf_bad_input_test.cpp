// Input made to break the loader rather than to describe a scene: JSON nested deep enough to
// exhaust tinygltf's recursive conversion, files that are FIFOs, directories or devices, and
// messages that would quote megabytes of a data: URI. Each fails with one short message naming
// the file, and quickly.
#include <gtest/gtest.h>
#include <shadow/scene.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "scene/gltf_import.h"
#include "scene/glb_bytes.h"
#include "scene/gltf_parse.h"
#include "scene/gltf_test_support.h"

namespace shadow {
namespace {

using namespace gltf_test;  // NOLINT(google-build-using-namespace): the files' vocabulary

/// `levels` nested arrays as the `extras` of the asset: a valid glTF at any depth.
std::string deepGltf(int levels) {
    return R"({"asset": {"version": "2.0", "extras": )" + std::string(static_cast<std::size_t>(levels), '[') +
           std::string(static_cast<std::size_t>(levels), ']') + "}}";
}

TEST(GltfBadInput, DeepJsonIsRefusedNamingTheFileAndDepth) {
    const fs::path dir = testDir();
    writeText(dir / "deep.gltf", deepGltf(20000));
    const std::string message = loadError(dir / "deep.gltf");
    EXPECT_MESSAGE(message, "deep.gltf: ");
    EXPECT_MESSAGE(message, "20002 levels");  // the root object and the asset object above the arrays
    EXPECT_MESSAGE(message, std::to_string(gltf::kMaxJsonDepth));

    writeText(dir / "deep.glb", glbOf(deepGltf(20000)));
    EXPECT_MESSAGE(loadError(dir / "deep.glb"), "deep.glb: JSON nested 20002 levels");

    EXPECT_FALSE(gltf::loadGltfFromMemory(deepGltf(20000), "memory", {}).ok());
}

TEST(GltfBadInput, JsonDepthCountsBracketsOutsideStringsOnly) {
    const fs::path dir = testDir();
    // At the limit: the root object and the asset object, then the arrays.
    writeText(dir / "limit.gltf", deepGltf(static_cast<int>(gltf::kMaxJsonDepth) - 2));
    EXPECT_TRUE(loadGltf((dir / "limit.gltf").string()).ok());
    writeText(dir / "over.gltf", deepGltf(static_cast<int>(gltf::kMaxJsonDepth) - 1));
    EXPECT_MESSAGE(loadError(dir / "over.gltf"), "over.gltf: JSON nested 65 levels");

    // Brackets in strings, escaped quotes included, are text.
    const std::string brackets(5000, '[');
    writeText(dir / "text.gltf", R"({"asset": {"version": "2.0", "extras": {"a": "\"x\\\")" + brackets + R"("}}})");
    const Result<Scene> text = loadGltf((dir / "text.gltf").string());
    EXPECT_TRUE(text.ok()) << text.error().message;
}

/// Runs `load` in a child process and returns its message (empty when it loaded), failing the
/// test instead of hanging when the child does not finish within a few seconds.
template <typename Load>
std::string messageWithinSeconds(const fs::path& dir, Load load) {
    const fs::path messageFile = dir / "message.txt";
    const pid_t child = ::fork();
    if (child == 0) {
        const Result<Scene> scene = load();
        writeText(messageFile, scene.ok() ? std::string() : scene.error().message);
        ::_exit(0);
    }
    EXPECT_GT(child, 0);
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (::waitpid(child, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > deadline) {
            ::kill(child, SIGKILL);
            ::waitpid(child, &status, 0);
            ADD_FAILURE() << "the load did not return within 10 s (blocked on a FIFO?)";
            return {};
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    return fs::exists(messageFile) ? readBytes(messageFile) : std::string();
}

TEST(GltfBadInput, SceneThatIsAFifoOrDirectoryIsRefused) {
    const fs::path dir = testDir();
    ASSERT_EQ(::mkfifo((dir / "pipe.gltf").c_str(), 0600), 0) << std::strerror(errno);
    const std::string fifo = messageWithinSeconds(dir, [&] { return loadGltf((dir / "pipe.gltf").string()); });
    EXPECT_MESSAGE(fifo, "pipe.gltf: not a regular file (a FIFO)");

    fs::create_directories(dir / "folder.gltf");
    EXPECT_MESSAGE(loadError(dir / "folder.gltf"), "folder.gltf: not a regular file (a directory)");
    EXPECT_MESSAGE(loadError("/dev/null"), "/dev/null: not a regular file (a device)");
}

TEST(GltfBadInput, ExternalBufferThatIsAFifoOrDirectoryIsRefused) {
    const fs::path dir = testDir();
    Doc doc;
    doc.node({{"mesh", doc.triangleMesh()}});
    const fs::path path = doc.write(dir / "ext.gltf", "data.bin");
    fs::remove(dir / "data.bin");
    ASSERT_EQ(::mkfifo((dir / "data.bin").c_str(), 0600), 0) << std::strerror(errno);
    const std::string fifo = messageWithinSeconds(dir, [&] { return loadGltf(path.string()); });
    EXPECT_MESSAGE(fifo, "ext.gltf: ");
    EXPECT_MESSAGE(fifo, "data.bin");
    EXPECT_MESSAGE(fifo, "not a regular file (a FIFO)");

    fs::remove(dir / "data.bin");
    fs::create_directories(dir / "data.bin");
    const std::string folder = loadError(path);
    EXPECT_MESSAGE(folder, "data.bin");
    EXPECT_MESSAGE(folder, "not a regular file (a directory)");
}

TEST(GltfBadInput, MessageNeverQuotesADataUriAndIsCapped) {
    const fs::path dir = testDir();
    Doc doc;
    doc.node({{"mesh", doc.triangleMesh()}});
    doc.j["buffers"] = json::array(
        {{{"byteLength", 2 * 1024 * 1024},  // more than the data holds
          {"uri", "data:application/octet-stream;base64," + base64(std::vector<unsigned char>(768 * 1024, 7))}}});
    doc.bin.clear();  // keep the buffer above
    writeText(dir / "big.gltf", doc.j.dump());
    const std::string message = loadError(dir / "big.gltf");
    EXPECT_LT(message.size(), 1024u) << message.substr(0, 2000);
    EXPECT_MESSAGE(message, "big.gltf: ");
    EXPECT_MESSAGE(message, "data:\u2026 (");
    EXPECT_EQ(message.find("base64,"), std::string::npos) << message.substr(0, 2000);
}

}  // namespace
}  // namespace shadow
