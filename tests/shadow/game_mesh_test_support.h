// A game's own copy of a mesh, for the tests of casters drawn from the game's geometry
// (ShadowCasterDraw).
#pragma once

#include <shadow/scene.h>

#include <cstdint>

#include "gl/gl_api.h"

namespace shadow::test {

/// The game's own copy of a mesh: a vertex buffer of positions, an element buffer, a VAO.
struct GameMesh {
    GLuint vertices = 0, indices = 0, vertexArray = 0;
    int indexCount = 0;
    Aabb bounds;

    explicit GameMesh(const MeshData& mesh) {
        gl.CreateBuffers(1, &vertices);
        gl.NamedBufferStorage(vertices, static_cast<GLsizeiptr>(mesh.positions.size() * sizeof(glm::vec3)),
                              mesh.positions.data(), 0);
        gl.CreateBuffers(1, &indices);
        gl.NamedBufferStorage(indices, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                              mesh.indices.data(), 0);
        gl.CreateVertexArrays(1, &vertexArray);
        gl.VertexArrayVertexBuffer(vertexArray, 0, vertices, 0, sizeof(glm::vec3));
        gl.VertexArrayElementBuffer(vertexArray, indices);
        gl.EnableVertexArrayAttrib(vertexArray, 0);
        gl.VertexArrayAttribFormat(vertexArray, 0, 3, GL_FLOAT, GL_FALSE, 0);
        gl.VertexArrayAttribBinding(vertexArray, 0, 0);
        indexCount = static_cast<int>(mesh.indices.size());
        bounds = mesh.bounds;
    }
    ~GameMesh() {
        gl.DeleteVertexArrays(1, &vertexArray);
        gl.DeleteBuffers(1, &vertices);
        gl.DeleteBuffers(1, &indices);
    }
    GameMesh(const GameMesh&) = delete;
    GameMesh& operator=(const GameMesh&) = delete;
};

}  // namespace shadow::test
