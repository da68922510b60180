#include "scene/gltf_schema.h"

#include <climits>
#include <string>
#include <vector>

#include "scene/gltf_values.h"

namespace shadow::gltf {
namespace {

using nlohmann::json;

/// The members checked, as a JSON document of the same shape: a string names a leaf's type
/// (`number`, `integer`: within `int`, `size`: a JSON integer >= 0, `string`, `boolean`,
/// `object`, or one of those with `[]` for an array of them); an object lists its members (`*`: every member); an array of one
/// entry describes every element. Texture references share one shape (`kTextureInfo`).
constexpr const char* kTextureInfo = R"({"index": "integer", "texCoord": "integer", "scale": "number",
                                         "strength": "number"})";

json schema() {
    json s = json::parse(R"({
      "scene": "integer",
      "scenes": [{"nodes": "integer[]"}],
      "nodes": [{"children": "integer[]", "mesh": "integer", "camera": "integer", "skin": "integer",
                 "matrix": "number[]", "translation": "number[]", "rotation": "number[]", "scale": "number[]",
                 "weights": "number[]", "name": "string"}],
      "meshes": [{"primitives": [{"attributes": {"*": "integer"}, "indices": "integer", "material": "integer",
                                  "mode": "integer", "targets": [{"*": "integer"}]}],
                  "weights": "number[]", "name": "string"}],
      "materials": [{"alphaMode": "string", "alphaCutoff": "number", "doubleSided": "boolean",
                     "emissiveFactor": "number[]", "name": "string",
                     "pbrMetallicRoughness": {"baseColorFactor": "number[]", "metallicFactor": "number",
                                              "roughnessFactor": "number"}}],
      "textures": [{"source": "integer", "sampler": "integer"}],
      "samplers": [{"magFilter": "integer", "minFilter": "integer", "wrapS": "integer", "wrapT": "integer"}],
      "images": [{"uri": "string", "mimeType": "string", "bufferView": "integer", "name": "string"}],
      "accessors": [{"bufferView": "integer", "byteOffset": "size", "componentType": "integer",
                     "normalized": "boolean", "count": "size", "type": "string",
                     "sparse": {"count": "size",
                                "indices": {"bufferView": "integer", "byteOffset": "size",
                                            "componentType": "integer"},
                                "values": {"bufferView": "integer", "byteOffset": "size"}}}],
      "bufferViews": [{"buffer": "integer", "byteOffset": "size", "byteLength": "size", "byteStride": "size"}],
      "buffers": [{"uri": "string", "byteLength": "size"}],
      "animations": [{"channels": [{"sampler": "integer", "target": {"node": "integer", "path": "string"}}],
                      "samplers": [{"input": "integer", "output": "integer", "interpolation": "string"}],
                      "name": "string"}],
      "skins": [{"joints": "integer[]", "inverseBindMatrices": "integer", "skeleton": "integer"}],
      "cameras": [{"type": "string",
                   "perspective": {"aspectRatio": "number", "yfov": "number", "zfar": "number", "znear": "number"},
                   "orthographic": {"xmag": "number", "ymag": "number", "zfar": "number", "znear": "number"}}],
      "extensionsUsed": "string[]",
      "extensionsRequired": "string[]"
    })");
    const json textureInfo = json::parse(kTextureInfo);
    json& material = s["materials"][0];
    for (const char* texture : {"normalTexture", "occlusionTexture", "emissiveTexture"})
        material[texture] = textureInfo;
    for (const char* texture : {"baseColorTexture", "metallicRoughnessTexture"}) {
        material["pbrMetallicRoughness"][texture] = textureInfo;
    }
    return s;
}

const char* typeName(const json& value) {
    switch (value.type()) {
        case json::value_t::null: return "null";
        case json::value_t::boolean: return "a boolean";
        case json::value_t::string: return "a string";
        case json::value_t::array: return "an array";
        case json::value_t::object: return "an object";
        case json::value_t::number_float: return "a fractional number";
        default: return "a number";
    }
}

/// Whether `value` is of the leaf type `type` (without `[]`).
bool isOfType(const json& value, const std::string& type) {
    if (type == "number") return value.is_number();
    if (type == "integer") {
        if (value.is_number_unsigned()) return value.get<json::number_unsigned_t>() <= INT_MAX;
        if (value.is_number_integer()) {
            const auto v = value.get<json::number_integer_t>();
            return v >= INT_MIN && v <= INT_MAX;
        }
        return false;
    }
    if (type == "size") return value.is_number_unsigned();
    if (type == "string") return value.is_string();
    if (type == "boolean") return value.is_boolean();
    return value.is_object();
}

std::string article(const std::string& type) {
    if (type == "integer") return "an integer";
    if (type == "size") return "an integer >= 0";
    if (type == "object") return "an object";
    return "a " + type;
}

Status checkLeaf(const json& value, const std::string& type, const std::string& where) {
    if (type.size() > 2 && type.ends_with("[]")) {
        const std::string element = type.substr(0, type.size() - 2);
        if (!value.is_array())
            return elementError(where, "must be an array of " + element + "s, not " + typeName(value));
        for (std::size_t i = 0; i < value.size(); ++i) {
            if (!isOfType(value[i], element)) {
                return elementError(where + "[" + std::to_string(i) + "]",
                                    "must be " + article(element) + ", not " + typeName(value[i]));
            }
        }
        return Ok{};
    }
    if (!isOfType(value, type)) return elementError(where, "must be " + article(type) + ", not " + typeName(value));
    return Ok{};
}

std::string childPath(const std::string& where, const std::string& key) {
    return where.empty() ? key : where + "." + key;
}

/// `document` against `shape` (see `schema`), depth first with a stack of its own (a file's
/// arrays may be long; the schema is only a few levels deep).
Status check(const json& document, const json& shape) {
    struct Pending {
        const json* value;
        const json* shape;
        std::string where;
    };
    std::vector<Pending> stack{{&document, &shape, ""}};
    while (!stack.empty()) {
        const Pending next = std::move(stack.back());
        stack.pop_back();
        const json& value = *next.value;
        if (next.shape->is_string()) {
            if (Status s = checkLeaf(value, next.shape->get<std::string>(), next.where); !s) return s;
            continue;
        }
        if (next.shape->is_array()) {
            if (!value.is_array())
                return elementError(next.where, std::string("must be an array, not ") + typeName(value));
            for (std::size_t i = value.size(); i-- > 0;)
                stack.push_back({&value[i], &(*next.shape)[0], indexed(next.where, i)});
            continue;
        }
        if (!value.is_object())
            return elementError(next.where, std::string("must be an object, not ") + typeName(value));
        for (const auto& [key, sub] : next.shape->items()) {
            if (key == "*") {
                for (const auto& [name, item] : value.items())
                    stack.push_back({&item, &sub, childPath(next.where, name)});
            } else if (const auto found = value.find(key); found != value.end()) {
                stack.push_back({&*found, &sub, childPath(next.where, key)});
            }
        }
    }
    return Ok{};
}

}  // namespace

Status checkMemberTypes(const nlohmann::json& document) {
    static const json kSchema = schema();
    if (!document.is_object()) return Ok{};  // tinygltf has said what is wrong with it
    return check(document, kSchema);
}

}  // namespace shadow::gltf
