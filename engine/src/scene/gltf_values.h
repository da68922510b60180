// Typed reads of tinygltf's generic JSON values (extras and extension objects), each failing
// with an error that names the element. tinygltf only parses the core schema; everything the
// engine reads from `extras` or `KHR_lights_punctual` goes through these so that a string
// where a number is due, a NaN or a negative size is reported instead of silently defaulted.
#pragma once

#include <shadow/result.h>
#include <tiny_gltf.h>

#include <string>

namespace shadow::gltf {

/// `"<where>: <what>"`, the shape of every import error before the file name is prefixed.
[[nodiscard]] Error elementError(const std::string& where, const std::string& what,
                                 ErrorCode code = ErrorCode::InvalidValue);

/// `"<array>[<i>]"`: element `i` of a glTF array as messages name it (`nodes[3]`).
[[nodiscard]] std::string indexed(const std::string& array, std::size_t i);

/// The member `key` of `object`, or null when `object` is not an object or lacks the key.
/// (tinygltf's `Value::Get` asserts on non-objects, so never call it on unchecked input.)
[[nodiscard]] const tinygltf::Value* member(const tinygltf::Value& object, const std::string& key);

/// A finite JSON number.
[[nodiscard]] Result<double> readFiniteNumber(const tinygltf::Value& v, const std::string& where);
/// A finite number >= 0 that is also finite as a float.
[[nodiscard]] Result<float> readNonNegativeFloat(const tinygltf::Value& v, const std::string& where);
/// An integral number in [1, INT_MAX] (JSON `2.0` counts as the integer 2).
[[nodiscard]] Result<int> readPositiveInt(const tinygltf::Value& v, const std::string& where);
/// An integral number in [0, INT_MAX], used for indices into glTF arrays.
[[nodiscard]] Result<int> readIndex(const tinygltf::Value& v, const std::string& where);
/// A JSON boolean.
[[nodiscard]] Result<bool> readBool(const tinygltf::Value& v, const std::string& where);
/// A JSON string.
[[nodiscard]] Result<std::string> readString(const tinygltf::Value& v, const std::string& where);

}  // namespace shadow::gltf
