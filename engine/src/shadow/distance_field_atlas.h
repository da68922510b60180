// The GPU side of the distance-field technique (sdf): each field caster's mesh baked once into a
// signed distance field (shadow/distance_field.h) and packed as a brick into one 3D texture, and
// the frame's field casters as instance records the shader reads (shaders/shadow_sdf.glsl has
// their layout).
#pragma once

#include <shadow/components.h>
#include <shadow/distance_field.h>
#include <shadow/ecs.h>
#include <shadow/shadow_planner.h>
#include <shadow/warnings.h>

#include "gl/objects.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

namespace shadow::gpu {

/// Where a mesh's field stands in the atlas, and what the shader needs to sample it.
struct FieldBrick {
    glm::ivec3 origin{0};  ///< atlas texel of its voxel (0, 0, 0)
    glm::ivec3 size{0};    ///< voxels per axis
    glm::vec3 firstCentre{0.0f};
    glm::vec3 lastCentre{0.0f};
    float voxelSize = 0.0f;
    bool sheet = false;  ///< no voxel inside (an open mesh): a zero-thickness sheet to the march
    Aabb meshBounds;     ///< of the mesh's positions (local)
};

class DistanceFieldAtlas {
public:
    /// Voxels per field (`DistanceFieldSettings::voxelBudget`).
    explicit DistanceFieldAtlas(int voxelBudget = 64 * 64 * 64);

    /// Gathers the field casters of every sdf light of `frame` in `ShadowLightPlan::fieldFirst`
    /// order, baking and uploading the field of each mesh not seen before. A mesh whose field
    /// does not bake is warned about once (`CasterWithoutField`) and gets an empty record.
    void update(const ShadowFrame& frame, const World& world, std::vector<Warning>& warnings);
    /// The instance records of the last `update`, positions relative to `wsCamera`, in a buffer
    /// texture (RGBA32F); uploaded again only when the camera or the instances changed.
    [[nodiscard]] GLuint instances(const glm::dvec3& wsCamera);
    /// The buffer texture as last uploaded by `instances` (0 before).
    [[nodiscard]] GLuint uploadedInstances() const { return bufferTexture_.get(); }
    [[nodiscard]] GLuint atlas() const { return atlas_.get(); }
    /// The voxels per field it was made with.
    [[nodiscard]] int voxelBudget() const { return settings_.voxelBudget; }
    /// GPU memory of the atlas and the instance buffer (bytes).
    [[nodiscard]] long long bytes() const;
    /// Fields baked so far, and the seconds the bakes took in total.
    [[nodiscard]] int fieldsBaked() const { return baked_; }
    [[nodiscard]] double bakeSeconds() const { return bakeSeconds_; }

private:
    struct Entry {
        std::weak_ptr<const MeshData> mesh;
        std::optional<FieldBrick> brick;  ///< empty when the bake failed
    };
    struct Instance {
        const FieldBrick* brick = nullptr;
        glm::dmat4 worldFromLocal{1.0};  ///< from the field's space (the mesh's, scaled for a scaled field)
        double scale = 1.0;              ///< metres per unit of the field's space
        glm::dvec3 wsCentre{0.0};        ///< of its field's box (world)
        double radius = -1.0;            ///< of the sphere around its field's box (m); < 0 for none
        std::uint64_t morton = 0;        ///< its place in its light's spatial order (`sortSpatially`)
    };
    /// A light's instances: [first, first + count) of `instances_`, its clusters from `cluster`.
    struct Range {
        int first = 0;
        int count = 0;
        int cluster = 0;
    };
    /// A mesh, and the scale baked into its field (1, 1, 1 for a uniform scale, which the
    /// instance applies).
    struct Key {
        const MeshData* mesh = nullptr;
        glm::vec3 scale{1.0f};
        bool operator==(const Key& o) const { return mesh == o.mesh && scale == o.scale; }
    };
    struct KeyHash {
        std::size_t operator()(const Key& k) const {
            std::size_t h = std::hash<const void*>{}(k.mesh);
            for (int c = 0; c < 3; ++c) h = h * 1000003u ^ std::hash<float>{}(k.scale[c]);
            return h;
        }
    };

    const FieldBrick* brickOf(const std::shared_ptr<const MeshData>& mesh, const glm::vec3& scale,
                              const std::string& who, std::vector<Warning>& warnings);
    /// The record of field caster `caster` (its field baked on first use).
    Instance instanceOf(const World& world, Entity caster, const std::string& who, std::vector<Warning>& warnings);
    /// Sorts `instances_` from `first` to the end by the Morton order of their centres.
    void sortSpatially(std::size_t first);
    static void writeInstance(float* record, const Instance& in, const glm::dvec3& wsCamera);
    void writeClusters(const glm::dvec3& wsCamera);
    FieldBrick place(const DistanceField& field);
    void grow(int depth);

    DistanceFieldSettings settings_;
    std::unordered_map<Key, Entry, KeyHash> entries_;
    Texture atlas_;
    glm::ivec3 atlasSize_{0};
    /// Where `place` would put a brick of `size` voxels (its first voxel's texel).
    [[nodiscard]] glm::ivec3 nextPlace(const glm::ivec3& size) const;
    glm::ivec3 cursor_{0};  ///< where the next brick goes: x in the row, y of the row, z of the slab
    int rowHeight_ = 0;
    int slabDepth_ = 0;
    int maxSize_ = 2048;  ///< GL_MAX_3D_TEXTURE_SIZE
    int baked_ = 0;
    double bakeSeconds_ = 0.0;

    std::vector<Instance> instances_;
    std::vector<Range> ranges_;
    int clusterCount_ = 0;
    std::vector<float> records_;
    Buffer buffer_;
    Texture bufferTexture_;
    std::size_t bufferFloats_ = 0;
    bool uploaded_ = false;
    glm::dvec3 uploadedFor_{0.0};
};

}  // namespace shadow::gpu
