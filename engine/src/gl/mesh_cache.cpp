#include <shadow/mesh_cache.h>

#include "gl/gl_state.h"
#include "gl/mesh_cache_access.h"
#include "gl/no_throw.h"
#include "gl/objects.h"

#include <unordered_map>

namespace shadow {

namespace {
/// Interleaved vertex of the GPU meshes.
struct GpuVertex {
    glm::vec3 position;
    glm::vec3 normal;
};

struct GpuMesh {
    std::weak_ptr<const MeshData> source;  // tells a reused address from the mesh uploaded
    gpu::VertexArray vao;
    gpu::Buffer vertices;
    gpu::Buffer indices;
    int indexCount = 0;
};
}  // namespace

struct MeshCache::Impl {
    // Keyed by the MeshData address: MeshData is immutable and shared while instances live.
    std::unordered_map<const MeshData*, GpuMesh> meshes;
    std::vector<Warning> pending;  ///< host errors found by calls without a FrameStats
};

MeshCache::MeshCache() : impl_((gpu::requireLoaded("MeshCache"), std::make_unique<Impl>())) {
    gpu::reportHostGlErrors("MeshCache", impl_->pending, gpu::kMaxPendingWarnings);
}
MeshCache::~MeshCache() = default;

Result<std::unique_ptr<MeshCache>> MeshCache::create() noexcept {
    return gpu::noThrow<std::unique_ptr<MeshCache>>("MeshCache", [] { return std::make_unique<MeshCache>(); });
}

std::size_t MeshCache::size() const { return impl_->meshes.size(); }

const std::vector<Warning>& MeshCache::warnings() const { return impl_->pending; }

void MeshCache::clearWarnings() { impl_->pending.clear(); }

std::vector<Warning>& MeshCache::pending() { return impl_->pending; }

std::size_t MeshCache::collect() {
    gpu::reportHostGlErrors("MeshCache::collect", impl_->pending, gpu::kMaxPendingWarnings);
    return collectInPass();
}

std::size_t MeshCache::collectInPass() {
    return std::erase_if(impl_->meshes, [](const auto& entry) { return entry.second.source.expired(); });
}

int MeshCache::bind(const std::shared_ptr<const MeshData>& mesh) {
    gpu::reportHostGlErrors("MeshCache::bind", impl_->pending, gpu::kMaxPendingWarnings);
    return bindInPass(mesh);
}

int MeshCache::bindInPass(const std::shared_ptr<const MeshData>& meshPtr) {
    const MeshData& mesh = *meshPtr;
    auto it = impl_->meshes.find(&mesh);
    if (it != impl_->meshes.end() && it->second.source.lock() != meshPtr) {
        impl_->meshes.erase(it);  // the old mesh died and its address was reused
        it = impl_->meshes.end();
    }
    if (it == impl_->meshes.end()) {
        std::vector<GpuVertex> vertices(mesh.positions.size());
        for (std::size_t i = 0; i < vertices.size(); ++i) {
            vertices[i].position = mesh.positions[i];
            vertices[i].normal = i < mesh.normals.size() ? mesh.normals[i] : glm::vec3(0, 1, 0);
        }
        GpuMesh g;
        g.source = meshPtr;
        const std::string label = "Mesh/" + mesh.name;
        g.vertices = gpu::makeBuffer(label + "/vertices", static_cast<GLsizeiptr>(vertices.size() * sizeof(GpuVertex)),
                                     vertices.data(), 0);
        g.indices =
            gpu::makeBuffer(label + "/indices", static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                            mesh.indices.data(), 0);
        GLuint vao = 0;
        gl.CreateVertexArrays(1, &vao);
        g.vao = gpu::VertexArray(vao);
        g.vao.label(label);
        gl.VertexArrayVertexBuffer(vao, 0, g.vertices.get(), 0, sizeof(GpuVertex));
        gl.VertexArrayElementBuffer(vao, g.indices.get());
        gl.EnableVertexArrayAttrib(vao, 0);
        gl.VertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(GpuVertex, position));
        gl.VertexArrayAttribBinding(vao, 0, 0);
        gl.EnableVertexArrayAttrib(vao, 1);
        gl.VertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, offsetof(GpuVertex, normal));
        gl.VertexArrayAttribBinding(vao, 1, 0);
        g.indexCount = static_cast<int>(mesh.indices.size());
        it = impl_->meshes.emplace(&mesh, std::move(g)).first;
    }
    gl.BindVertexArray(it->second.vao.get());
    return it->second.indexCount;
}

}  // namespace shadow
