#include <shadow/mesh_cache.h>

#include "gl/gl_state.h"
#include "gl/mesh_cache_access.h"
#include "gl/no_throw.h"
#include "gl/objects.h"

#include <shadow/shared_constants.h>

#include <algorithm>
#include <array>
#include <unordered_map>

namespace shadow {

namespace {
/// Interleaved vertex of the GPU meshes (attributes 0-2).
struct GpuVertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 texcoord;
};

/// A skinned mesh's second vertex stream (attributes 3-4).
struct GpuSkinVertex {
    glm::u16vec4 joints;
    glm::vec4 weights;
};

/// The stream of a mesh with a second texture-coordinate set or tangents (attributes 5-6):
/// apart, so that the meshes without (every built-in one) keep their 32-byte vertices.
struct GpuMapVertex {
    glm::vec2 texcoord1;
    glm::vec4 tangent;
};

struct GpuMesh {
    std::weak_ptr<const MeshData> source;  // tells a reused address from the mesh uploaded
    gpu::VertexArray vao;
    gpu::Buffer vertices;
    gpu::Buffer skinVertices;
    gpu::Buffer mapVertices;
    gpu::Buffer morphDeltas;  ///< made on the first draw with a target drawn (every weight 0: never)
    gpu::Buffer indices;
    int indexCount = 0;
};

struct GpuTexture {
    std::weak_ptr<const Texture> source;
    gpu::Texture texture;
};

GLint wrapMode(Texture::Wrap wrap) {
    switch (wrap) {
        case Texture::Wrap::ClampToEdge: return GL_CLAMP_TO_EDGE;
        case Texture::Wrap::MirroredRepeat: return GL_MIRRORED_REPEAT;
        default: return GL_REPEAT;
    }
}

/// Mip levels of a full chain for an image of `width` x `height`.
int mipLevels(int width, int height) {
    int levels = 1;
    while ((std::max(width, height) >> levels) > 0) ++levels;
    return levels;
}

gpu::Texture uploadTexture(const Texture& t, bool srgb) {
    gpu::Texture texture = gpu::makeTexture("Texture/" + t.name + (srgb ? "" : "/linear"), GL_TEXTURE_2D);
    const GLuint name = texture.get();
    gl.TextureStorage2D(name, mipLevels(t.width, t.height), srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, t.width, t.height);
    {
        const gpu::UnpackDefaults unpack;  // rows of 4-byte texels from client memory, whatever the host set
        gl.TextureSubImage2D(name, 0, 0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE, t.rgba.data());
    }
    gl.GenerateTextureMipmap(name);
    gl.TextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl.TextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TextureParameteri(name, GL_TEXTURE_WRAP_S, wrapMode(t.wrapS));
    gl.TextureParameteri(name, GL_TEXTURE_WRAP_T, wrapMode(t.wrapT));
    return texture;
}

/// The mesh's second texture-coordinate set and tangents as a vertex stream of their own
/// (binding 2, SG_ATTRIB_TEXCOORD1 and SG_ATTRIB_TANGENT); none when it has neither, and the attributes read GL's defaults.
void uploadMapVertices(const MeshData& mesh, const std::string& label, GpuMesh& g) {
    const std::size_t n = mesh.positions.size();
    const bool second = mesh.texcoords1.size() == n, tangents = mesh.tangents.size() == n;
    if (n == 0 || (!second && !tangents)) return;
    std::vector<GpuMapVertex> vertices(n);
    for (std::size_t i = 0; i < n; ++i) {
        vertices[i].texcoord1 = second ? mesh.texcoords1[i] : glm::vec2(0.0f);
        vertices[i].tangent = tangents ? mesh.tangents[i] : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    }
    g.mapVertices =
        gpu::makeBuffer(label + "/maps", static_cast<GLsizeiptr>(n * sizeof(GpuMapVertex)), vertices.data(), 0);
    const GLuint vao = g.vao.get();
    gl.VertexArrayVertexBuffer(vao, 2, g.mapVertices.get(), 0, sizeof(GpuMapVertex));
    gl.EnableVertexArrayAttrib(vao, SG_ATTRIB_TEXCOORD1);
    gl.VertexArrayAttribFormat(vao, SG_ATTRIB_TEXCOORD1, 2, GL_FLOAT, GL_FALSE, offsetof(GpuMapVertex, texcoord1));
    gl.VertexArrayAttribBinding(vao, SG_ATTRIB_TEXCOORD1, 2);
    gl.EnableVertexArrayAttrib(vao, SG_ATTRIB_TANGENT);
    gl.VertexArrayAttribFormat(vao, SG_ATTRIB_TANGENT, 4, GL_FLOAT, GL_FALSE, offsetof(GpuMapVertex, tangent));
    gl.VertexArrayAttribBinding(vao, SG_ATTRIB_TANGENT, 2);
}

/// A ring of joint matrices: each skinned draw's matrices go after the last draw's, so that no
/// upload overwrites what a queued draw still reads; a full ring starts again at its beginning.
struct JointRing {
    static constexpr GLsizeiptr kMinBytes = GLsizeiptr{256} << 10U;
    gpu::Buffer buffer;
    GLsizeiptr capacity = 0;
    GLsizeiptr cursor = 0;
    GLsizeiptr alignment = 256;

    void bind(const std::vector<glm::mat4>& matrices) {
        const auto bytes = static_cast<GLsizeiptr>(matrices.size() * sizeof(glm::mat4));
        if (bytes > capacity) {
            GLint align = 0;
            gl.GetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align);
            alignment = std::max<GLsizeiptr>(align, 16);
            capacity = std::max({2 * capacity, bytes, kMinBytes});
            buffer = gpu::makeBuffer("Skin/joints", capacity, nullptr, GL_DYNAMIC_STORAGE_BIT);
            cursor = 0;
        } else if (cursor + bytes > capacity) {
            gl.InvalidateBufferData(buffer.get());
            cursor = 0;
        }
        gl.NamedBufferSubData(buffer.get(), cursor, bytes, matrices.data());
        gl.BindBufferRange(GL_SHADER_STORAGE_BUFFER, SG_BINDING_JOINTS, buffer.get(), cursor, bytes);
        cursor += (bytes + alignment - 1) / alignment * alignment;
    }
};
/// The mesh's morph-target displacements in the layout shaders/mesh_vertex.glsl reads: per
/// vertex, per target, position, normal and tangent (zero where the mesh has none).
gpu::Buffer uploadMorphDeltas(const MeshData& mesh, const std::string& label) {
    const std::size_t n = mesh.positions.size();
    const std::size_t targets = mesh.morphTargets;
    std::vector<glm::vec4> deltas(n * targets * 3, glm::vec4(0.0f));
    const std::array<const std::vector<glm::vec3>*, 3> sources{&mesh.morphPositions, &mesh.morphNormals,
                                                               &mesh.morphTangents};
    for (std::size_t a = 0; a < 3; ++a) {
        if (sources[a]->size() != n * targets) continue;
        for (std::size_t k = 0; k < targets; ++k) {
            for (std::size_t v = 0; v < n; ++v)
                deltas[(v * targets + k) * 3 + a] = glm::vec4((*sources[a])[k * n + v], 0.0f);
        }
    }
    return gpu::makeBuffer(label + "/morph", static_cast<GLsizeiptr>(deltas.size() * sizeof(glm::vec4)), deltas.data(),
                           0);
}

}  // namespace

struct MeshCache::Impl {
    // Keyed by the MeshData address: MeshData is immutable and shared while instances live.
    std::unordered_map<const MeshData*, GpuMesh> meshes;
    /// Likewise, by Texture address: sRGB (colour) and linear (data) uploads apart.
    std::array<std::unordered_map<const Texture*, GpuTexture>, 2> textures;
    gpu::Texture white;  ///< 1x1 white: what an untextured material samples
    JointRing joints;
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
    for (auto& textures : impl_->textures) {
        std::erase_if(textures, [](const auto& entry) { return entry.second.source.expired(); });
    }
    return std::erase_if(impl_->meshes, [](const auto& entry) { return entry.second.source.expired(); });
}

void MeshCache::bindTextureInPass(const std::shared_ptr<const Texture>& texture, unsigned unit, bool srgb) {
    if (texture == nullptr || texture->width < 1 || texture->height < 1 ||
        texture->rgba.size() <
            static_cast<std::size_t>(texture->width) * static_cast<std::size_t>(texture->height) * 4U) {
        if (!impl_->white) {
            const Texture white{"white", 1, 1, {255, 255, 255, 255}};
            impl_->white = uploadTexture(white, false);
        }
        gl.BindTextureUnit(unit, impl_->white.get());
        return;
    }
    auto& textures = impl_->textures[srgb ? 0 : 1];
    auto it = textures.find(texture.get());
    if (it != textures.end() && it->second.source.lock() != texture) {
        textures.erase(it);  // the old texture died and its address was reused
        it = textures.end();
    }
    if (it == textures.end()) {
        it = textures.emplace(texture.get(), GpuTexture{texture, uploadTexture(*texture, srgb)}).first;
    }
    gl.BindTextureUnit(unit, it->second.texture.get());
}

void MeshCache::bindSkinInPass(const Skin& skin) { impl_->joints.bind(skin.frameFromMesh); }

namespace gpu {

DeformUniforms DeformUniforms::of(GLuint program) {
    DeformUniforms u;
    u.morphCount = gl.GetUniformLocation(program, "uMorphCount");
    u.morphTargets = gl.GetUniformLocation(program, "uMorphTargets");
    u.morphInfluences = gl.GetUniformLocation(program, "uMorphInfluences");
    return u;
}

int MeshCacheAccess::bindDeformed(MeshCache& cache, const std::shared_ptr<const MeshData>& mesh, GLuint program,
                                  const DeformUniforms& uniforms, const Skin* skin, const Morph* morph) {
    const int indices = cache.bindInPass(mesh);
    if (skin != nullptr) cache.bindSkinInPass(*skin);
    const std::size_t count = morph != nullptr ? std::min(morph->drawn.size(), kMaxMorphInfluences) : 0;
    if (count == 0) return indices;
    gl.ProgramUniform1i(program, uniforms.morphCount, static_cast<GLint>(count));
    std::array<glm::vec2, kMaxMorphInfluences> influences{};
    for (std::size_t i = 0; i < count; ++i) {
        influences[i] = glm::vec2(static_cast<float>(morph->drawn[i].target), morph->drawn[i].weight);
    }
    gl.ProgramUniform1i(program, uniforms.morphTargets, static_cast<GLint>(mesh->morphTargets));
    gl.ProgramUniform2fv(program, uniforms.morphInfluences, static_cast<GLsizei>(count), &influences[0].x);
    cache.bindMorphInPass(*mesh);
    return indices;
}

}  // namespace gpu

void MeshCache::bindMorphInPass(const MeshData& mesh) {
    const auto it = impl_->meshes.find(&mesh);
    if (it == impl_->meshes.end() || mesh.morphTargets == 0) return;  // bound by bindInPass first
    if (!it->second.morphDeltas) it->second.morphDeltas = uploadMorphDeltas(mesh, "Mesh/" + mesh.name);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SG_BINDING_MORPH_DELTAS, it->second.morphDeltas.get());
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
            vertices[i].texcoord = i < mesh.texcoords.size() ? mesh.texcoords[i] : glm::vec2(0.0f);
        }
        GpuMesh g;
        g.source = meshPtr;
        const std::string label = "Mesh/" + mesh.name;
        g.vertices = gpu::makeBuffer(label + "/vertices", static_cast<GLsizeiptr>(vertices.size() * sizeof(GpuVertex)),
                                     vertices.data(), 0);
        // Drawn in an order that reuses transformed vertices: every pass pays the vertex stage
        // again, and a CPU rasteriser shades each vertex once per batch it appears in.
        const std::vector<std::uint32_t> ordered = vertexCacheOrder(mesh.indices, mesh.positions.size());
        g.indices = gpu::makeBuffer(label + "/indices", static_cast<GLsizeiptr>(ordered.size() * sizeof(std::uint32_t)),
                                    ordered.data(), 0);
        g.vao = gpu::makeVertexArray(label);
        const GLuint vao = g.vao.get();
        gl.VertexArrayVertexBuffer(vao, 0, g.vertices.get(), 0, sizeof(GpuVertex));
        gl.VertexArrayElementBuffer(vao, g.indices.get());
        gl.EnableVertexArrayAttrib(vao, 0);
        gl.VertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(GpuVertex, position));
        gl.VertexArrayAttribBinding(vao, 0, 0);
        gl.EnableVertexArrayAttrib(vao, 1);
        gl.VertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, offsetof(GpuVertex, normal));
        gl.VertexArrayAttribBinding(vao, 1, 0);
        gl.EnableVertexArrayAttrib(vao, 2);
        gl.VertexArrayAttribFormat(vao, 2, 2, GL_FLOAT, GL_FALSE, offsetof(GpuVertex, texcoord));
        gl.VertexArrayAttribBinding(vao, 2, 0);
        if (mesh.joints.size() == mesh.positions.size() && mesh.weights.size() == mesh.positions.size()) {
            std::vector<GpuSkinVertex> skin(mesh.positions.size());
            for (std::size_t i = 0; i < skin.size(); ++i) skin[i] = {mesh.joints[i], mesh.weights[i]};
            g.skinVertices = gpu::makeBuffer(
                label + "/skin", static_cast<GLsizeiptr>(skin.size() * sizeof(GpuSkinVertex)), skin.data(), 0);
            gl.VertexArrayVertexBuffer(vao, 1, g.skinVertices.get(), 0, sizeof(GpuSkinVertex));
            gl.EnableVertexArrayAttrib(vao, 3);
            gl.VertexArrayAttribIFormat(vao, 3, 4, GL_UNSIGNED_SHORT, offsetof(GpuSkinVertex, joints));
            gl.VertexArrayAttribBinding(vao, 3, 1);
            gl.EnableVertexArrayAttrib(vao, 4);
            gl.VertexArrayAttribFormat(vao, 4, 4, GL_FLOAT, GL_FALSE, offsetof(GpuSkinVertex, weights));
            gl.VertexArrayAttribBinding(vao, 4, 1);
        }
        uploadMapVertices(mesh, label, g);
        g.indexCount = static_cast<int>(mesh.indices.size());
        it = impl_->meshes.emplace(&mesh, std::move(g)).first;
    }
    gl.BindVertexArray(it->second.vao.get());
    return it->second.indexCount;
}

}  // namespace shadow
