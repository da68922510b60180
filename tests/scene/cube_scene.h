// A glTF file the sample programs' tests write: a 1 m cube with no ground, camera or light (the
// default rig's case), optionally with a lamp. Header-only: tests/CMakeLists.txt globs only
// *_test.cpp files.
#pragma once

#include <shadow/scene.h>

#include "scene/gltf_test_support.h"

#include <filesystem>
#include <vector>

namespace shadow::test {

/// A 1 m cube standing on y = 0 (no ground, no light, no camera); with `lamp`, a point light
/// above it too.
inline std::filesystem::path writeCube(const std::filesystem::path& path, bool lamp) {
    const auto box = makeBoxMesh(glm::vec3(0.5f));
    gltf_test::Doc doc;
    std::vector<float> positions, normals;
    for (std::size_t i = 0; i < box->positions.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            positions.push_back(box->positions[i][k]);
            normals.push_back(box->normals[i][k]);
        }
    }
    const std::vector<std::uint16_t> indices(box->indices.begin(), box->indices.end());
    doc.push(
        "meshes",
        {{"primitives",
          gltf_test::json::array(
              {{{"attributes", {{"POSITION", doc.floats(positions, "VEC3")}, {"NORMAL", doc.floats(normals, "VEC3")}}},
                {"indices", doc.indices(indices)}}})}});
    std::vector<int> roots = {doc.node({{"name", "cube"}, {"mesh", 0}, {"translation", {0.0, 0.5, 0.0}}})};
    if (lamp) {
        doc.light({{"type", "point"}, {"intensity", 30.0}});
        roots.push_back(doc.node({{"name", "lamp"},
                                  {"translation", {0.0, 3.0, 0.0}},
                                  {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}));
    }
    doc.scene(roots);
    return doc.write(path);
}

}  // namespace shadow::test
