// Checked reads of glTF accessors. tinygltf parses the JSON but does not check that an
// accessor's elements lie inside its bufferView and buffer, nor that component types suit the
// semantic; every read of binary data in the importer goes through here, and nothing is read
// before the whole range has been checked. An accessor without bufferView reads as zeros, and a
// sparse accessor's values replace elements on top (glTF 2.0, 3.6.2.1 and 3.6.2.3).
//
// Errors name the use and then the accessor: `meshes[0].primitives[1].indices: accessors[2]:
// exceeds bufferViews[1]`.
#pragma once

#include <shadow/math.h>
#include <glm/gtc/type_precision.hpp>
#include <shadow/result.h>
#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <vector>

namespace shadow::gltf {

/// Float VEC3 elements (POSITION, NORMAL, translation and scale keys), all finite.
[[nodiscard]] Result<std::vector<glm::vec3>> readVec3(const tinygltf::Model& model, int accessor,
                                                      const std::string& where);

/// Float SCALAR elements (animation key times), all finite.
[[nodiscard]] Result<std::vector<float>> readScalars(const tinygltf::Model& model, int accessor,
                                                     const std::string& where);

/// VEC4 rotation keys: float, or normalized (u)int8/(u)int16 as the glTF spec allows for
/// rotation outputs. All finite; not normalised (the animation system does that).
[[nodiscard]] Result<std::vector<glm::vec4>> readRotations(const tinygltf::Model& model, int accessor,
                                                           const std::string& where);

/// Triangle indices: UNSIGNED_BYTE/SHORT/INT SCALAR, every value < `vertexCount`.
[[nodiscard]] Result<std::vector<std::uint32_t>> readIndices(const tinygltf::Model& model, int accessor,
                                                             std::size_t vertexCount, const std::string& where);

/// TANGENT: float VEC4 (xyz the tangent, w the handedness), all finite.
[[nodiscard]] Result<std::vector<glm::vec4>> readTangents(const tinygltf::Model& model, int accessor,
                                                          const std::string& where);

/// TEXCOORD_n: float VEC2, or normalized unsigned 8/16-bit integers. All finite.
[[nodiscard]] Result<std::vector<glm::vec2>> readTexcoords(const tinygltf::Model& model, int accessor,
                                                           const std::string& where);

/// WEIGHTS_n: float VEC4, or normalized unsigned 8/16-bit integers. All finite; not normalised.
[[nodiscard]] Result<std::vector<glm::vec4>> readWeights(const tinygltf::Model& model, int accessor,
                                                         const std::string& where);

/// JOINTS_n: unsigned 8/16-bit integer VEC4, every value < `jointCount` (the skin's joints).
[[nodiscard]] Result<std::vector<glm::u16vec4>> readJoints(const tinygltf::Model& model, int accessor,
                                                           std::size_t jointCount, const std::string& where);

/// Float MAT4 elements (a skin's inverseBindMatrices), column-major, all finite.
[[nodiscard]] Result<std::vector<glm::dmat4>> readMat4(const tinygltf::Model& model, int accessor,
                                                       const std::string& where);

}  // namespace shadow::gltf
