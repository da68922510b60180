#include "scene/gltf_accessors.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/ext/vector_float1.hpp>
#include <initializer_list>

#include "scene/gltf_values.h"

namespace shadow::gltf {
namespace {

/// The component types and element type a use of an accessor accepts.
struct Format {
    std::initializer_list<int> componentTypes;
    int type;
    const char* description;  ///< for the error message
};

template <typename T>
T load(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));  // glTF data need not be aligned for the host
    return value;
}

/// A range of elements known to lie inside its buffer, or inside `dense` (an accessor without
/// bufferView, or a sparse one: its elements gathered, zero-filled, sparse values applied).
struct CheckedSpan {
    const unsigned char* data = nullptr;
    std::size_t count = 0;
    std::size_t stride = 0;
    int componentType = 0;
    int components = 0;
    bool normalized = false;
    std::string name;  ///< `<where>: accessors[i]`, for messages about elements
    /// Owns the elements `data` points at when they are not the buffer's. A move keeps the
    /// pointer valid (the heap block moves with the vector); the span is never copied.
    std::vector<unsigned char> dense;
};

/// Most bytes the elements of one accessor without bufferView, or of one sparse accessor, may
/// take once made dense: the file does not hold them, so its size does not bound them.
constexpr std::size_t kMaxDenseBytes = std::size_t{256} << 20U;

/// Whether `count` elements of `elementSize` bytes, `stride` apart, starting `offset` bytes in,
/// fit in `length` bytes. Written to be free of overflow for any input.
bool fits(std::size_t offset, std::size_t stride, std::size_t count, std::size_t elementSize, std::size_t length) {
    if (count == 0) return offset <= length;
    if (offset > length || elementSize > length - offset) return false;
    return count - 1 <= (length - offset - elementSize) / stride;
}

Status checkFormat(const tinygltf::Accessor& a, const Format& format, const std::string& name) {
    const bool typeOk = a.type == format.type;
    const bool componentOk = std::find(format.componentTypes.begin(), format.componentTypes.end(), a.componentType) !=
                             format.componentTypes.end();
    if (!typeOk || !componentOk) {
        return elementError(name, std::string("must be ") + format.description);
    }
    return Ok{};
}

/// Where `count` elements of `elementSize` bytes, `stride` apart (0: packed), start at
/// `byteOffset` in bufferView `viewIndex`, checked against the view and its buffer. `user` names
/// the reader in messages (`<where>: accessors[i]`, or its `.sparse.indices`).
Result<const unsigned char*> viewElements(const tinygltf::Model& model, int viewIndex, std::size_t byteOffset,
                                          std::size_t stride, std::size_t count, std::size_t elementSize,
                                          const std::string& where, const std::string& user) {
    if (viewIndex < 0 || static_cast<std::size_t>(viewIndex) >= model.bufferViews.size()) {
        return elementError(user, "bufferView " + std::to_string(viewIndex) + " does not exist");
    }
    const auto view = static_cast<std::size_t>(viewIndex);
    const tinygltf::BufferView& v = model.bufferViews[view];
    const std::string viewName = where + ": " + indexed("bufferViews", view);
    if (v.buffer < 0 || static_cast<std::size_t>(v.buffer) >= model.buffers.size()) {
        return elementError(viewName, "buffer " + std::to_string(v.buffer) + " does not exist");
    }
    const auto bufferIndex = static_cast<std::size_t>(v.buffer);
    const tinygltf::Buffer& buffer = model.buffers[bufferIndex];
    if (buffer.uri.empty() && buffer.data.empty() && v.byteLength > 0) {
        return elementError(viewName, "reads " + indexed("buffers", bufferIndex) +
                                          ", which has no uri (only a .glb's BIN chunk may go without one)");
    }
    if (!fits(v.byteOffset, 1, v.byteLength, 1, buffer.data.size())) {
        return elementError(viewName, "exceeds " + indexed("buffers", bufferIndex));
    }
    if (stride == 0) stride = elementSize;
    if (stride < elementSize) {
        return elementError(user, "byteStride of " + indexed("bufferViews", view) + " is smaller than one element");
    }
    if (!fits(byteOffset, stride, count, elementSize, v.byteLength)) {
        return elementError(user, "exceeds " + indexed("bufferViews", view));
    }
    return buffer.data.data() + v.byteOffset + byteOffset;
}

/// Applies `a.sparse` to the dense elements of `span` (glTF 2.0, 3.6.2.3): `sparse.count`
/// indices, strictly increasing and below `a.count`, each replacing one element by the next of
/// `sparse.values`.
Status applySparse(const tinygltf::Model& model, const tinygltf::Accessor& a, std::size_t elementSize,
                   const std::string& where, CheckedSpan& span) {
    const std::string sparseName = span.name + ".sparse";
    if (a.sparse.count < 1 || static_cast<std::size_t>(a.sparse.count) > a.count) {
        return elementError(sparseName + ".count", "must be in [1, count " + std::to_string(a.count) + "], not " +
                                                       std::to_string(a.sparse.count));
    }
    const auto n = static_cast<std::size_t>(a.sparse.count);
    const int indexType = a.sparse.indices.componentType;
    if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        return elementError(sparseName + ".indices.componentType",
                            "must be UNSIGNED_BYTE, UNSIGNED_SHORT or "
                            "UNSIGNED_INT");
    }
    const auto indexSize =
        static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(indexType)));
    if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0) {
        return elementError(sparseName, "byteOffset must not be negative");
    }
    // Sparse data is tightly packed: the bufferViews' byteStride does not apply.
    auto indices =
        viewElements(model, a.sparse.indices.bufferView, static_cast<std::size_t>(a.sparse.indices.byteOffset),
                     indexSize, n, indexSize, where, sparseName + ".indices");
    if (!indices) return indices.error();
    auto values = viewElements(model, a.sparse.values.bufferView, static_cast<std::size_t>(a.sparse.values.byteOffset),
                               elementSize, n, elementSize, where, sparseName + ".values");
    if (!values) return values.error();
    std::size_t previous = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const unsigned char* p = *indices + k * indexSize;
        const std::size_t index = indexType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? load<std::uint8_t>(p)
                                  : indexType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? load<std::uint16_t>(p)
                                                                                        : load<std::uint32_t>(p);
        if (index >= a.count) {
            return elementError(sparseName + ".indices", "index " + std::to_string(index) + " at position " +
                                                             std::to_string(k) + " out of range (count " +
                                                             std::to_string(a.count) + ")");
        }
        if (k > 0 && index <= previous) {
            return elementError(sparseName + ".indices", "not strictly increasing at position " + std::to_string(k) +
                                                             " (" + std::to_string(previous) + ", then " +
                                                             std::to_string(index) + ")");
        }
        previous = index;
        std::memcpy(span.dense.data() + index * elementSize, *values + k * elementSize, elementSize);
    }
    return Ok{};
}

/// Checks accessor `index` against `format` and its bufferView and buffer; returns where its
/// elements are. An accessor without bufferView is zero-filled (glTF 2.0, 3.6.2.1), and a sparse
/// one's values replace elements on top (3.6.2.3).
Result<CheckedSpan> checkedSpan(const tinygltf::Model& model, int index, const Format& format,
                                const std::string& where) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
        return elementError(where, "accessor " + std::to_string(index) + " does not exist");
    }
    const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
    CheckedSpan span;
    span.name = where + ": " + indexed("accessors", static_cast<std::size_t>(index));
    if (auto st = checkFormat(a, format, span.name); !st) return st.error();
    span.components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    const auto elementSize =
        static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType))) *
        static_cast<std::size_t>(span.components);
    span.count = a.count;
    span.componentType = a.componentType;
    span.normalized = a.normalized;
    span.stride = elementSize;
    if (a.bufferView >= 0) {
        const auto viewIndex = static_cast<std::size_t>(a.bufferView);
        const std::size_t stride =
            viewIndex < model.bufferViews.size() ? model.bufferViews[viewIndex].byteStride : std::size_t{0};
        auto data = viewElements(model, a.bufferView, a.byteOffset, stride, a.count, elementSize, where, span.name);
        if (!data) return data.error();
        span.data = *data;
        if (stride != 0) span.stride = stride;
        if (!a.sparse.isSparse) return span;
    }
    if (a.count > kMaxDenseBytes / elementSize) {
        return elementError(span.name,
                            std::string(a.bufferView >= 0 ? "is sparse" : "has no bufferView") + " and its " +
                                std::to_string(a.count) + " elements exceed the " +
                                std::to_string(kMaxDenseBytes >> 20U) + " MiB the engine makes dense",
                            ErrorCode::LimitExceeded);
    }
    span.dense.assign(a.count * elementSize, 0);
    for (std::size_t i = 0; span.data != nullptr && i < a.count; ++i) {
        std::memcpy(span.dense.data() + i * elementSize, span.data + i * span.stride, elementSize);
    }
    if (a.sparse.isSparse) {
        if (auto st = applySparse(model, a, elementSize, where, span); !st) return st.error();
    }
    span.data = span.dense.data();
    span.stride = elementSize;
    return span;
}

/// One component as a float; integer types are mapped to [-1, 1] or [0, 1] as the glTF spec
/// defines for normalized accessors.
float decodeComponent(const unsigned char* p, int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
        case TINYGLTF_COMPONENT_TYPE_BYTE: return std::max(static_cast<float>(load<std::int8_t>(p)) / 127.0f, -1.0f);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return static_cast<float>(load<std::uint8_t>(p)) / 255.0f;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return std::max(static_cast<float>(load<std::int16_t>(p)) / 32767.0f, -1.0f);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return static_cast<float>(load<std::uint16_t>(p)) / 65535.0f;
        default: return 0.0f;  // excluded by the format check
    }
}

/// Decodes every element of `span` into `N`-component vectors and checks they are finite.
template <typename Vec, int N>
Result<std::vector<Vec>> decodeFinite(const CheckedSpan& span) {
    const std::size_t componentSize =
        static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(span.componentType)));
    std::vector<Vec> out(span.count);
    for (std::size_t i = 0; i < span.count; ++i) {
        const unsigned char* element = span.data + i * span.stride;
        for (int c = 0; c < N; ++c) {
            const float v = decodeComponent(element + static_cast<std::size_t>(c) * componentSize, span.componentType);
            if (!std::isfinite(v)) {
                return elementError(span.name, "element " + std::to_string(i) + " not finite");
            }
            out[i][c] = v;
        }
    }
    return out;
}

}  // namespace

Result<std::vector<glm::vec3>> readVec3(const tinygltf::Model& model, int accessor, const std::string& where) {
    const Format format{{TINYGLTF_COMPONENT_TYPE_FLOAT}, TINYGLTF_TYPE_VEC3, "FLOAT VEC3"};
    auto span = checkedSpan(model, accessor, format, where);
    if (!span) return span.error();
    return decodeFinite<glm::vec3, 3>(*span);
}

Result<std::vector<float>> readScalars(const tinygltf::Model& model, int accessor, const std::string& where) {
    const Format format{{TINYGLTF_COMPONENT_TYPE_FLOAT}, TINYGLTF_TYPE_SCALAR, "FLOAT SCALAR"};
    auto span = checkedSpan(model, accessor, format, where);
    if (!span) return span.error();
    auto vectors = decodeFinite<glm::vec1, 1>(*span);
    if (!vectors) return vectors.error();
    std::vector<float> out(vectors->size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = (*vectors)[i].x;
    return out;
}

Result<std::vector<glm::vec4>> readRotations(const tinygltf::Model& model, int accessor, const std::string& where) {
    const Format format{
        {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
         TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
        TINYGLTF_TYPE_VEC4,
        "FLOAT VEC4 or a normalized 8/16-bit integer VEC4"};
    auto span = checkedSpan(model, accessor, format, where);
    if (!span) return span.error();
    if (span->componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !span->normalized) {
        return elementError(span->name, "integer rotations must be normalized");
    }
    return decodeFinite<glm::vec4, 4>(*span);
}

Result<std::vector<glm::vec4>> readTangents(const tinygltf::Model& model, int accessor, const std::string& where) {
    const Format format{{TINYGLTF_COMPONENT_TYPE_FLOAT}, TINYGLTF_TYPE_VEC4, "FLOAT VEC4"};
    auto span = checkedSpan(model, accessor, format, where);
    if (!span) return span.error();
    return decodeFinite<glm::vec4, 4>(*span);
}

Result<std::vector<std::uint32_t>> readIndices(const tinygltf::Model& model, int accessor, std::size_t vertexCount,
                                               const std::string& where) {
    const Format format{{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                        TINYGLTF_TYPE_SCALAR,
                        "UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT SCALAR"};
    auto span = checkedSpan(model, accessor, format, where);
    if (!span) return span.error();
    std::vector<std::uint32_t> out(span->count);
    for (std::size_t i = 0; i < span->count; ++i) {
        const unsigned char* p = span->data + i * span->stride;
        const std::uint32_t index = span->componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ? load<std::uint8_t>(p)
                                    : span->componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                                        ? load<std::uint16_t>(p)
                                        : load<std::uint32_t>(p);
        if (index >= vertexCount) {
            return elementError(span->name, "index " + std::to_string(index) + " at position " + std::to_string(i) +
                                                " out of range (" + std::to_string(vertexCount) + " vertices)");
        }
        out[i] = index;
    }
    return out;
}

namespace {
/// Float VEC`N`, or a normalized unsigned 8/16-bit integer one (TEXCOORD_n, WEIGHTS_n).
template <typename Vec, int N>
Result<std::vector<Vec>> readUnsignedNormalized(const tinygltf::Model& model, int accessor, const Format& format,
                                                const std::string& where) {
    auto span = checkedSpan(model, accessor, format, where);
    if (!span) return span.error();
    if (span->componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !span->normalized) {
        return elementError(span->name, "integer components must be normalized");
    }
    return decodeFinite<Vec, N>(*span);
}
}  // namespace

Result<std::vector<glm::vec2>> readTexcoords(const tinygltf::Model& model, int accessor, const std::string& where) {
    const Format format{
        {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
        TINYGLTF_TYPE_VEC2,
        "FLOAT VEC2 or a normalized UNSIGNED_BYTE/UNSIGNED_SHORT VEC2"};
    return readUnsignedNormalized<glm::vec2, 2>(model, accessor, format, where);
}

Result<std::vector<glm::vec4>> readWeights(const tinygltf::Model& model, int accessor, const std::string& where) {
    const Format format{
        {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
        TINYGLTF_TYPE_VEC4,
        "FLOAT VEC4 or a normalized UNSIGNED_BYTE/UNSIGNED_SHORT VEC4"};
    return readUnsignedNormalized<glm::vec4, 4>(model, accessor, format, where);
}

Result<std::vector<glm::u16vec4>> readJoints(const tinygltf::Model& model, int accessor, std::size_t jointCount,
                                             const std::string& where) {
    const Format format{{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                        TINYGLTF_TYPE_VEC4,
                        "UNSIGNED_BYTE or UNSIGNED_SHORT VEC4"};
    auto span = checkedSpan(model, accessor, format, where);
    if (!span) return span.error();
    const bool bytes = span->componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    std::vector<glm::u16vec4> out(span->count);
    for (std::size_t i = 0; i < span->count; ++i) {
        const unsigned char* element = span->data + i * span->stride;
        for (int c = 0; c < 4; ++c) {
            const auto at = static_cast<std::size_t>(c);
            const std::uint16_t j = bytes ? load<std::uint8_t>(element + at) : load<std::uint16_t>(element + 2 * at);
            if (j >= jointCount) {
                return elementError(span->name, "element " + std::to_string(i) + " names joint " + std::to_string(j) +
                                                    " of a skin with " + std::to_string(jointCount));
            }
            out[i][c] = j;
        }
    }
    return out;
}

Result<std::vector<glm::dmat4>> readMat4(const tinygltf::Model& model, int accessor, const std::string& where) {
    const Format format{{TINYGLTF_COMPONENT_TYPE_FLOAT}, TINYGLTF_TYPE_MAT4, "FLOAT MAT4"};
    auto span = checkedSpan(model, accessor, format, where);
    if (!span) return span.error();
    std::vector<glm::dmat4> out(span->count);
    for (std::size_t i = 0; i < span->count; ++i) {
        const unsigned char* element = span->data + i * span->stride;
        for (int c = 0; c < 16; ++c) {
            const float v = load<float>(element + 4 * static_cast<std::size_t>(c));
            if (!std::isfinite(v)) return elementError(span->name, "element " + std::to_string(i) + " not finite");
            out[i][c / 4][c % 4] = v;  // column-major, as glTF stores it
        }
    }
    return out;
}

}  // namespace shadow::gltf
