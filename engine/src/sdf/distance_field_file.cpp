// The distance-field file: a 60-byte little-endian header, then the distances as f32.
//
//   offset  type     field
//        0  char[8]  magic "SHADOWDF"
//        8  u32      version (kDistanceFieldFileVersion)
//       12  i32[3]   size, voxels per axis
//       24  f32[3]   box min
//       36  f32[3]   box max
//       48  f32      voxelSize
//       52  u64      data bytes = 4·size.x·size.y·size.z
//       60  f32[]    distances, x fastest
//
// Bytes are assembled by shifts, so the file is the same on a host of either byte order.
#include <shadow/distance_field.h>
#include <shadow/image_io.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace shadow {
namespace {

constexpr std::array<char, 8> kMagic = {'S', 'H', 'A', 'D', 'O', 'W', 'D', 'F'};
constexpr std::size_t kHeaderBytes = 60;
/// How far the box may disagree with size·voxelSize (relative): float rounding, not more.
constexpr float kBoxTolerance = 1e-4f;

void putU32(std::string& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}
void putU64(std::string& out, std::uint64_t v) {
    for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}
void putF32(std::string& out, float v) { putU32(out, std::bit_cast<std::uint32_t>(v)); }

std::uint32_t getU32(const unsigned char* p) {
    return std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 | std::uint32_t{p[3]} << 24;
}
std::uint64_t getU64(const unsigned char* p) { return std::uint64_t{getU32(p)} | std::uint64_t{getU32(p + 4)} << 32; }
float getF32(const unsigned char* p) { return std::bit_cast<float>(getU32(p)); }

/// The header's fields, as read or about to be written.
struct Header {
    std::uint32_t version = kDistanceFieldFileVersion;
    glm::ivec3 size{0};
    Aabb box;
    float voxelSize = 0.0f;
    std::uint64_t dataBytes = 0;
};

Header parseHeader(const unsigned char* p) {
    Header h;
    h.version = getU32(p + 8);
    for (int a = 0; a < 3; ++a) {
        const std::ptrdiff_t at = std::ptrdiff_t{4} * a;
        h.size[a] = static_cast<std::int32_t>(getU32(p + 12 + at));
        h.box.min[a] = getF32(p + 24 + at);
        h.box.max[a] = getF32(p + 36 + at);
    }
    h.voxelSize = getF32(p + 48);
    h.dataBytes = getU64(p + 52);
    return h;
}

std::string sizeText(const glm::ivec3& s) {
    return std::to_string(s.x) + " x " + std::to_string(s.y) + " x " + std::to_string(s.z);
}

/// What a field's layout must satisfy to be sampled, whether it comes from a file or goes to
/// one. The code is the loader's; the saver reports its own.
Status checkLayout(const glm::ivec3& size, const Aabb& box, float voxelSize) {
    for (int a = 0; a < 3; ++a) {
        if (size[a] < 2)
            return Error{ErrorCode::InvalidValue, "size " + sizeText(size) + ": an axis under 2 voxels", "size"};
        if (size[a] > kMaxDistanceFieldVoxels) {
            return Error{ErrorCode::LimitExceeded, "size " + sizeText(size) + " exceeds the limit", "size"};
        }
    }
    if (std::int64_t{size.x} * size.y * size.z > kMaxDistanceFieldVoxels) {
        return Error{ErrorCode::LimitExceeded,
                     "size " + sizeText(size) + " exceeds " + std::to_string(kMaxDistanceFieldVoxels) + " voxels",
                     "size"};
    }
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(box.min[a]) || !std::isfinite(box.max[a]) || !(box.min[a] < box.max[a])) {
            return Error{ErrorCode::InvalidValue, "box is not finite or is empty", "box"};
        }
    }
    if (!std::isfinite(voxelSize) || !(voxelSize > 0.0f)) {
        return Error{ErrorCode::InvalidValue, "voxelSize " + std::to_string(voxelSize) + " is not positive",
                     "voxelSize"};
    }
    for (int a = 0; a < 3; ++a) {
        const float width = static_cast<float>(size[a]) * voxelSize;
        if (!(std::abs(box.max[a] - box.min[a] - width) <= kBoxTolerance * width)) {
            return Error{ErrorCode::InvalidValue, "box does not span size x voxelSize", "voxelSize"};
        }
    }
    return Ok{};
}

/// The index of the first non-finite distance, or `distances.size()`.
std::size_t firstNonFinite(const std::vector<float>& distances) {
    for (std::size_t i = 0; i < distances.size(); ++i) {
        if (!std::isfinite(distances[i])) return i;
    }
    return distances.size();
}

Error nonFiniteDistance(std::size_t i, ErrorCode code) {
    const std::string element = "distances[" + std::to_string(i) + "]";
    return Error{code, element + " is not finite", element};
}

std::size_t voxelCount(const glm::ivec3& size) {
    return static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) * static_cast<std::size_t>(size.z);
}

std::string encode(const DistanceField& field) {
    std::string out(kMagic.begin(), kMagic.end());
    out.reserve(kHeaderBytes + field.byteSize());
    putU32(out, kDistanceFieldFileVersion);
    for (int a = 0; a < 3; ++a) putU32(out, static_cast<std::uint32_t>(field.size[a]));
    for (int a = 0; a < 3; ++a) putF32(out, field.box.min[a]);
    for (int a = 0; a < 3; ++a) putF32(out, field.box.max[a]);
    putF32(out, field.voxelSize);
    putU64(out, field.byteSize());
    for (float d : field.distances) putF32(out, d);
    return out;
}

/// Reads `bytes` bytes at `offset` of `in` into `out`.
bool readAt(std::ifstream& in, std::uint64_t offset, unsigned char* out, std::size_t bytes) {
    in.seekg(static_cast<std::streamoff>(offset));
    in.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(bytes));
    return static_cast<std::size_t>(in.gcount()) == bytes;
}

/// The header checked field by field, in the order a reader meets them.
Result<Header> readHeader(std::ifstream& in, std::uint64_t fileBytes) {
    if (fileBytes < kHeaderBytes) {
        return Error{ErrorCode::MalformedFile,
                     "truncated: " + std::to_string(fileBytes) + " bytes, the header alone takes " +
                         std::to_string(kHeaderBytes),
                     "header"};
    }
    std::array<unsigned char, kHeaderBytes> bytes{};
    if (!readAt(in, 0, bytes.data(), bytes.size())) return Error{ErrorCode::FileUnreadable, "cannot read the header"};
    if (std::memcmp(bytes.data(), kMagic.data(), kMagic.size()) != 0) {
        return Error{ErrorCode::MalformedFile, "not a distance field (no SHADOWDF magic)", "magic"};
    }
    const Header header = parseHeader(bytes.data());
    if (header.version != kDistanceFieldFileVersion) {
        return Error{ErrorCode::Unsupported,
                     "version " + std::to_string(header.version) + " (this build reads " +
                         std::to_string(kDistanceFieldFileVersion) + ")",
                     "version"};
    }
    const Status layout = checkLayout(header.size, header.box, header.voxelSize);
    if (!layout.ok()) return layout.error();
    const std::uint64_t expected = voxelCount(header.size) * sizeof(float);
    if (header.dataBytes != expected) {
        return Error{ErrorCode::MalformedFile,
                     "data bytes " + std::to_string(header.dataBytes) + " disagree with size " + sizeText(header.size) +
                         " (" + std::to_string(expected) + ")",
                     "dataBytes"};
    }
    if (fileBytes != kHeaderBytes + expected) {
        return Error{ErrorCode::MalformedFile,
                     "the file holds " + std::to_string(fileBytes - kHeaderBytes) + " bytes of data, the header says " +
                         std::to_string(expected),
                     "dataBytes"};
    }
    return header;
}

Result<DistanceField> readField(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        return Error{ErrorCode::FileUnreadable, "no such file (or not a regular file)"};
    }
    const std::uint64_t fileBytes = std::filesystem::file_size(path, ec);
    if (ec) return Error{ErrorCode::FileUnreadable, "cannot read its size: " + ec.message()};
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{ErrorCode::FileUnreadable, "cannot open"};
    const Result<Header> header = readHeader(in, fileBytes);
    if (!header.ok()) return header.error();

    DistanceField field;
    field.size = header->size;
    field.box = header->box;
    field.voxelSize = header->voxelSize;
    std::vector<unsigned char> data(header->dataBytes);
    if (!readAt(in, kHeaderBytes, data.data(), data.size()))
        return Error{ErrorCode::FileUnreadable, "cannot read the data"};
    field.distances.resize(voxelCount(field.size));
    for (std::size_t i = 0; i < field.distances.size(); ++i) field.distances[i] = getF32(&data[4 * i]);
    const std::size_t bad = firstNonFinite(field.distances);
    if (bad < field.distances.size()) return nonFiniteDistance(bad, ErrorCode::InvalidValue);
    return field;
}

}  // namespace

Status saveDistanceField(const std::string& path, const DistanceField& field) {
    const Status layout = checkLayout(field.size, field.box, field.voxelSize);
    if (!layout.ok())
        return Error{ErrorCode::InvalidArgument, path + ": " + layout.error().message, layout.error().element};
    if (field.distances.size() != voxelCount(field.size)) {
        return Error{
            ErrorCode::InvalidArgument,
            path + ": " + std::to_string(field.distances.size()) + " distances for size " + sizeText(field.size),
            "distances"};
    }
    const std::size_t bad = firstNonFinite(field.distances);
    if (bad < field.distances.size()) return nonFiniteDistance(bad, ErrorCode::InvalidArgument).within(path + ": ");
    return writeTextFileAtomic(path, encode(field));
}

Result<DistanceField> loadDistanceField(const std::string& path) {
    Result<DistanceField> field = readField(path);
    if (!field.ok()) return field.error().within(path + ": ");
    return field;
}

}  // namespace shadow
