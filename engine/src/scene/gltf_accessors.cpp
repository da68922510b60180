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

/// A range of elements known to lie inside its buffer.
struct CheckedSpan {
    const unsigned char* data = nullptr;
    std::size_t count = 0;
    std::size_t stride = 0;
    int componentType = 0;
    int components = 0;
    bool normalized = false;
    std::string name;  ///< `<where>: accessors[i]`, for messages about elements
};

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

/// Checks accessor `index` against `format` and its bufferView and buffer; returns where its
/// elements are.
Result<CheckedSpan> checkedSpan(const tinygltf::Model& model, int index, const Format& format,
                                const std::string& where) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
        return elementError(where, "accessor " + std::to_string(index) + " does not exist");
    }
    const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
    const std::string name = where + ": " + indexed("accessors", static_cast<std::size_t>(index));
    if (a.sparse.isSparse) return elementError(name, "sparse accessors are not supported");
    if (auto st = checkFormat(a, format, name); !st) return st.error();
    if (a.bufferView < 0) return elementError(name, "has no bufferView");
    const auto viewIndex = static_cast<std::size_t>(a.bufferView);
    if (viewIndex >= model.bufferViews.size()) {
        return elementError(name, indexed("bufferViews", viewIndex) + " does not exist");
    }
    const tinygltf::BufferView& view = model.bufferViews[viewIndex];
    const std::string viewName = where + ": " + indexed("bufferViews", viewIndex);
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
        return elementError(viewName, "buffer " + std::to_string(view.buffer) + " does not exist");
    }
    const auto bufferIndex = static_cast<std::size_t>(view.buffer);
    const std::vector<unsigned char>& bytes = model.buffers[bufferIndex].data;
    if (!fits(view.byteOffset, 1, view.byteLength, 1, bytes.size())) {
        return elementError(viewName, "exceeds " + indexed("buffers", bufferIndex));
    }
    CheckedSpan span;
    span.components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    const auto elementSize =
        static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType))) *
        static_cast<std::size_t>(span.components);
    span.stride = view.byteStride != 0 ? view.byteStride : elementSize;
    if (span.stride < elementSize) {
        return elementError(name,
                            "byteStride of " + indexed("bufferViews", viewIndex) + " is smaller than one element");
    }
    if (!fits(a.byteOffset, span.stride, a.count, elementSize, view.byteLength)) {
        return elementError(name, "exceeds " + indexed("bufferViews", viewIndex));
    }
    span.data = bytes.data() + view.byteOffset + a.byteOffset;
    span.count = a.count;
    span.componentType = a.componentType;
    span.normalized = a.normalized;
    span.name = name;
    return span;
}

template <typename T>
T load(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));  // glTF data need not be aligned for the host
    return value;
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

}  // namespace shadow::gltf
