#include "scene/gltf_values.h"

#include <climits>
#include <cmath>
#include <limits>

namespace shadow::gltf {

Error elementError(const std::string& where, const std::string& what, ErrorCode code) {
    return Error{code, where + ": " + what, where};
}

std::string indexed(const std::string& array, std::size_t i) { return array + "[" + std::to_string(i) + "]"; }

const tinygltf::Value* member(const tinygltf::Value& object, const std::string& key) {
    if (!object.IsObject()) return nullptr;
    const auto& map = object.Get<tinygltf::Value::Object>();
    const auto it = map.find(key);
    return it == map.end() ? nullptr : &it->second;
}

Result<double> readFiniteNumber(const tinygltf::Value& v, const std::string& where) {
    if (!v.IsNumber()) return elementError(where, "must be a number");
    const double d = v.GetNumberAsDouble();
    if (!std::isfinite(d)) return elementError(where, "not finite");
    return d;
}

Result<float> readNonNegativeFloat(const tinygltf::Value& v, const std::string& where) {
    auto d = readFiniteNumber(v, where);
    if (!d) return d.error();
    if (*d < 0.0) return elementError(where, "must be a non-negative number");
    if (*d > static_cast<double>(std::numeric_limits<float>::max())) {
        return elementError(where, "not finite as a 32-bit float");
    }
    return static_cast<float>(*d);
}

namespace {

/// Integral numbers in [lowest, INT_MAX]. Checked on the double so that `1e30` or `2.5` is
/// reported rather than converted with undefined behaviour.
Result<int> readIntegral(const tinygltf::Value& v, const std::string& where, int lowest, const char* what) {
    if (v.IsInt()) {
        const int i = v.GetNumberAsInt();
        if (i < lowest) return elementError(where, what);
        return i;
    }
    if (!v.IsNumber()) return elementError(where, what);
    const double d = v.GetNumberAsDouble();
    if (!std::isfinite(d) || d != std::floor(d) || d < lowest || d > INT_MAX) {
        return elementError(where, what);
    }
    return static_cast<int>(d);
}

}  // namespace

Result<int> readPositiveInt(const tinygltf::Value& v, const std::string& where) {
    return readIntegral(v, where, 1, "must be a positive integer");
}

Result<int> readIndex(const tinygltf::Value& v, const std::string& where) {
    return readIntegral(v, where, 0, "must be a non-negative integer index");
}

Result<bool> readBool(const tinygltf::Value& v, const std::string& where) {
    if (!v.IsBool()) return elementError(where, "must be true or false");
    return v.Get<bool>();
}

Result<std::string> readString(const tinygltf::Value& v, const std::string& where) {
    if (!v.IsString()) return elementError(where, "must be a string");
    return v.Get<std::string>();
}

}  // namespace shadow::gltf
