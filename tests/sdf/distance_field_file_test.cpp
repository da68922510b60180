// Tests of saveDistanceField and loadDistanceField (engine/src/sdf/distance_field_file.cpp): a
// round trip keeps every bit, and each broken or hostile header field is one error with its code
// and element, found before any data is allocated.
#include <gtest/gtest.h>
#include <shadow/distance_field.h>
#include <shadow/scene.h>

#include "test_support.h"

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

namespace shadow {
namespace {

constexpr std::size_t kHeaderBytes = 60;
// Header offsets (distance_field.h): magic 0, version 8, size 12, box min 24, box max 36,
// voxelSize 48, data bytes 52.
constexpr std::size_t kVersionAt = 8;
constexpr std::size_t kSizeAt = 12;
constexpr std::size_t kBoxMinAt = 24;
constexpr std::size_t kVoxelSizeAt = 48;
constexpr std::size_t kDataBytesAt = 52;

const DistanceField& boxField() {
    static const DistanceField field = [] {
        DistanceFieldSettings settings;
        settings.voxelBudget = kMinDistanceFieldVoxels;
        return bakeDistanceField(*makeBoxMesh(glm::vec3(0.5f, 0.3f, 0.2f)), settings).value();
    }();
    return field;
}

using test::readBytes;

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void putU32(std::string& bytes, std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<char>((v >> (8 * i)) & 0xffu);
}
void putU64(std::string& bytes, std::size_t at, std::uint64_t v) {
    for (int i = 0; i < 8; ++i) bytes[at + i] = static_cast<char>((v >> (8 * i)) & 0xffu);
}
void putF32(std::string& bytes, std::size_t at, float v) { putU32(bytes, at, std::bit_cast<std::uint32_t>(v)); }

TEST(DistanceFieldFile, RoundTripKeepsEveryBit) {
    const test::TempDir dir("distance_field_file_test");
    const std::string path = dir / "box.sdf";
    const DistanceField& field = boxField();
    ASSERT_TRUE(saveDistanceField(path, field).ok());
    EXPECT_EQ(std::filesystem::file_size(path), kHeaderBytes + field.byteSize());
    const Result<DistanceField> loaded = loadDistanceField(path);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_EQ(loaded->size, field.size);
    EXPECT_EQ(loaded->box.min, field.box.min);
    EXPECT_EQ(loaded->box.max, field.box.max);
    EXPECT_EQ(loaded->voxelSize, field.voxelSize);
    EXPECT_EQ(loaded->distances, field.distances);
}

struct BrokenFile {
    const char* what;
    std::function<void(std::string&)> damage;
    ErrorCode code;
    const char* element;
};

// One damaged copy of a valid file per case; each must fail with its own code and element.
TEST(DistanceFieldFile, EachBrokenFieldIsOneNamedError) {
    const test::TempDir dir("distance_field_file_test");
    const std::string good = dir / "good.sdf";
    ASSERT_TRUE(saveDistanceField(good, boxField()).ok());
    const std::string bytes = readBytes(good);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<BrokenFile> cases = {
        {"truncated header", [](std::string& b) { b.resize(30); }, ErrorCode::MalformedFile, "header"},
        {"empty file", [](std::string& b) { b.clear(); }, ErrorCode::MalformedFile, "header"},
        {"wrong magic", [](std::string& b) { b[0] = 'X'; }, ErrorCode::MalformedFile, "magic"},
        {"other version", [](std::string& b) { putU32(b, kVersionAt, 2); }, ErrorCode::Unsupported, "version"},
        {"zero size", [](std::string& b) { putU32(b, kSizeAt, 0); }, ErrorCode::InvalidValue, "size"},
        {"negative size", [](std::string& b) { putU32(b, kSizeAt + 4, 0xffffffffu); }, ErrorCode::InvalidValue, "size"},
        // 2^20 per axis: 2^60 voxels, a header asking for exabytes.
        {"huge size",
         [](std::string& b) {
             for (int a = 0; a < 3; ++a) putU32(b, kSizeAt + 4 * a, 1u << 20);
         },
         ErrorCode::LimitExceeded, "size"},
        {"huge total", [](std::string& b) { putU32(b, kSizeAt, 1u << 22); }, ErrorCode::LimitExceeded, "size"},
        {"NaN box", [nan](std::string& b) { putF32(b, kBoxMinAt + 4, nan); }, ErrorCode::InvalidValue, "box"},
        {"zero voxel size", [](std::string& b) { putF32(b, kVoxelSizeAt, 0.0f); }, ErrorCode::InvalidValue,
         "voxelSize"},
        {"NaN voxel size", [nan](std::string& b) { putF32(b, kVoxelSizeAt, nan); }, ErrorCode::InvalidValue,
         "voxelSize"},
        {"voxel size off the box", [](std::string& b) { putF32(b, kVoxelSizeAt, boxField().voxelSize * 1.01f); },
         ErrorCode::InvalidValue, "voxelSize"},
        {"data bytes not size x 4", [](std::string& b) { putU64(b, kDataBytesAt, 4); }, ErrorCode::MalformedFile,
         "dataBytes"},
        {"data bytes huge", [](std::string& b) { putU64(b, kDataBytesAt, ~std::uint64_t{0}); },
         ErrorCode::MalformedFile, "dataBytes"},
        {"truncated data", [](std::string& b) { b.resize(b.size() - 4); }, ErrorCode::MalformedFile, "dataBytes"},
        {"trailing bytes", [](std::string& b) { b += "xxxx"; }, ErrorCode::MalformedFile, "dataBytes"},
        {"NaN distance", [nan](std::string& b) { putF32(b, kHeaderBytes + 4 * 5, nan); }, ErrorCode::InvalidValue,
         "distances[5]"},
    };
    for (const BrokenFile& c : cases) {
        std::string damaged = bytes;
        c.damage(damaged);
        const std::string path = dir / "broken.sdf";
        writeBytes(path, damaged);
        const Result<DistanceField> loaded = loadDistanceField(path);
        ASSERT_FALSE(loaded.ok()) << c.what;
        EXPECT_EQ(errorCodeName(loaded.error().code), std::string(errorCodeName(c.code)))
            << c.what << ": " << loaded.error().message;
        EXPECT_EQ(loaded.error().element, c.element) << c.what << ": " << loaded.error().message;
        EXPECT_NE(loaded.error().message.find(path), std::string::npos) << c.what << ": " << loaded.error().message;
    }
}

TEST(DistanceFieldFile, MissingFileIsUnreadable) {
    const test::TempDir dir("distance_field_file_test");
    const Result<DistanceField> loaded = loadDistanceField(dir / "absent.sdf");
    ASSERT_FALSE(loaded.ok());
    EXPECT_EQ(loaded.error().code, ErrorCode::FileUnreadable);
    const Result<DistanceField> folder = loadDistanceField(dir.path().string());
    ASSERT_FALSE(folder.ok());
    EXPECT_EQ(folder.error().code, ErrorCode::FileUnreadable);
}

TEST(DistanceFieldFile, SaveRefusesAFieldThatWouldNotLoad) {
    const test::TempDir dir("distance_field_file_test");
    DistanceField shortData = boxField();
    shortData.distances.pop_back();
    DistanceField nanDistance = boxField();
    nanDistance.distances[3] = std::numeric_limits<float>::quiet_NaN();
    DistanceField flat = boxField();
    flat.size.y = 1;
    for (const DistanceField& field : {shortData, nanDistance, flat, DistanceField{}}) {
        const Status saved = saveDistanceField(dir / "bad.sdf", field);
        ASSERT_FALSE(saved.ok());
        EXPECT_EQ(saved.error().code, ErrorCode::InvalidArgument) << saved.error().message;
        EXPECT_FALSE(std::filesystem::exists(dir / "bad.sdf"));
    }
}

TEST(DistanceFieldFile, UnwritablePathIsReported) {
    const test::TempDir dir("distance_field_file_test");
    const Status saved = saveDistanceField(dir / "no/such/folder/box.sdf", boxField());
    ASSERT_FALSE(saved.ok());
    EXPECT_EQ(saved.error().code, ErrorCode::FileUnwritable);
}

}  // namespace
}  // namespace shadow
