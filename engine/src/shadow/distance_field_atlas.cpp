#include "shadow/distance_field_atlas.h"

#include <shadow/shared_constants.h>

#include "gl/gl_api.h"
#include "gl/gl_state.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <span>
#include <cmath>
#include <string>

namespace shadow::gpu {
namespace {

/// Edge of the atlas in x and y (texels); it grows in z as fields are added. A field wider than
/// this is baked again with an eighth of the voxels until it fits.
constexpr int kAtlasEdge = 128;

/// The scale along each of a transform's own axes (the planner keeps transforms without shear).
glm::dvec3 axisScales(const glm::dmat4& m) {
    return {glm::length(glm::dvec3(m[0])), glm::length(glm::dvec3(m[1])), glm::length(glm::dvec3(m[2]))};
}

/// Scales within a thousandth of each other count as uniform: the instance applies them.
bool uniform(const glm::dvec3& s) {
    const double lo = std::min({s.x, s.y, s.z});
    const double hi = std::max({s.x, s.y, s.z});
    return hi <= lo * 1.001;
}

}  // namespace

DistanceFieldAtlas::DistanceFieldAtlas(int voxelBudget) {
    settings_.voxelBudget = voxelBudget;
    gl.GetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize_);
}

void DistanceFieldAtlas::grow(int depth) {
    // Grown to what the new brick needs (in steps of 16 slices), not doubled: a copy per new
    // field is cheap, and the atlas is most of the technique's memory.
    depth = std::min((depth + 15) / 16 * 16, maxSize_);
    Texture next = makeTexture("Shadow/distance fields", GL_TEXTURE_3D);
    gl.TextureStorage3D(next.get(), 1, GL_R32F, kAtlasEdge, kAtlasEdge, depth);
    gl.TextureParameteri(next.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TextureParameteri(next.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) {
        gl.TextureParameteri(next.get(), wrap, GL_CLAMP_TO_EDGE);
    }
    if (atlas_ && atlasSize_.z > 0) {
        gl.CopyImageSubData(atlas_.get(), GL_TEXTURE_3D, 0, 0, 0, 0, next.get(), GL_TEXTURE_3D, 0, 0, 0, 0,
                            atlasSize_.x, atlasSize_.y, atlasSize_.z);
    }
    atlas_ = std::move(next);
    atlasSize_ = glm::ivec3(kAtlasEdge, kAtlasEdge, depth);
    checkGlError("growing the distance-field atlas");
}

glm::ivec3 DistanceFieldAtlas::nextPlace(const glm::ivec3& s) const {
    glm::ivec3 at = cursor_;
    if (at.x + s.x > kAtlasEdge) at = glm::ivec3(0, at.y + rowHeight_, at.z);  // next row
    if (at.y + s.y > kAtlasEdge) at = glm::ivec3(0, 0, at.z + slabDepth_);     // next slab
    return at;
}

FieldBrick DistanceFieldAtlas::place(const DistanceField& field) {
    const glm::ivec3 s = field.size;
    const glm::ivec3 at = nextPlace(s);
    if (at.z != cursor_.z) {
        rowHeight_ = 0;
        slabDepth_ = 0;
    } else if (at.y != cursor_.y) {
        rowHeight_ = 0;
    }
    cursor_ = at;
    if (cursor_.z + s.z > atlasSize_.z) grow(cursor_.z + s.z);
    FieldBrick b;
    b.origin = cursor_;
    b.size = s;
    b.voxelSize = field.voxelSize;
    b.firstCentre = field.voxelCentre(glm::ivec3(0));
    b.lastCentre = field.voxelCentre(s - 1);
    b.sheet = std::none_of(field.distances.begin(), field.distances.end(), [](float d) { return d < 0.0f; });
    {
        const gpu::UnpackDefaults unpack;
        gl.TextureSubImage3D(atlas_.get(), 0, b.origin.x, b.origin.y, b.origin.z, s.x, s.y, s.z, GL_RED, GL_FLOAT,
                             field.distances.data());
    }
    checkGlError("uploading a distance field");
    cursor_.x += s.x;
    rowHeight_ = std::max(rowHeight_, s.y);
    slabDepth_ = std::max(slabDepth_, s.z);
    return b;
}

const FieldBrick* DistanceFieldAtlas::brickOf(const std::shared_ptr<const MeshData>& mesh, const glm::vec3& scale,
                                              const std::string& who, std::vector<Warning>& warnings) {
    const Key key{mesh.get(), scale};
    auto it = entries_.find(key);
    if (it != entries_.end() && it->second.mesh.lock() == mesh) return it->second.brick ? &*it->second.brick : nullptr;
    Entry entry{mesh, std::nullopt};
    const auto start = std::chrono::steady_clock::now();
    DistanceFieldSettings settings = settings_;
    // A non-uniform scale is baked into the field: distances in the scaled space are metres
    // over the instance's own scale, which a sheared or stretched field's would not be.
    MeshData scaled;
    const bool stretched = scale != glm::vec3(1.0f);
    if (stretched) {
        scaled.name = mesh->name;
        scaled.indices = mesh->indices;
        scaled.positions.reserve(mesh->positions.size());
        for (const glm::vec3& p : mesh->positions) scaled.positions.push_back(p * scale);
        computeBounds(scaled);
    }
    const MeshData& source = stretched ? scaled : *mesh;
    std::optional<Result<DistanceField>> baked;
    baked.emplace(bakeDistanceField(source, settings));
    // Too wide or too deep for the atlas: fewer voxels, by the cube of the longest axis's excess
    // (and a little more, for the padding's rounding), until it fits.
    auto excess = [&](const DistanceField& f) {
        return std::max({static_cast<double>(f.size.x) / kAtlasEdge, static_cast<double>(f.size.y) / kAtlasEdge,
                         static_cast<double>(f.size.z) / maxSize_});
    };
    while (*baked && excess(**baked) > 1.0 && settings.voxelBudget > kMinDistanceFieldVoxels) {
        const double shrink = 0.95 / std::pow(excess(**baked), 3.0);
        settings.voxelBudget = std::max(kMinDistanceFieldVoxels, static_cast<int>(settings.voxelBudget * shrink));
        baked.emplace(bakeDistanceField(source, settings));
    }
    const Result<DistanceField>& field = *baked;
    bakeSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++baked_;
    const bool fits = field && field->size.x <= kAtlasEdge && field->size.y <= kAtlasEdge &&
                      nextPlace(field->size).z + field->size.z <= maxSize_;
    if (fits) {
        entry.brick = place(*field);
        entry.brick->meshBounds = source.bounds;
    } else {
        const std::string why = field ? "it does not fit the atlas" : field.error().message;
        warnings.push_back({WarningCode::CasterWithoutField, who,
                            who + ": technique sdf: no distance field for mesh \"" + mesh->name + "\" (" + why +
                                "); it casts no shadow"});
    }
    it = entries_.insert_or_assign(key, std::move(entry)).first;
    return it->second.brick ? &*it->second.brick : nullptr;
}

DistanceFieldAtlas::Instance DistanceFieldAtlas::instanceOf(const World& world, Entity caster, const std::string& who,
                                                            std::vector<Warning>& warnings) {
    Instance instance;
    const Mesh* mesh = world.tryGet<Mesh>(caster);
    const WorldTransform* wt = world.tryGet<WorldTransform>(caster);
    if (mesh == nullptr || mesh->data == nullptr || wt == nullptr) return instance;
    const glm::dvec3 s = axisScales(wt->worldFromLocal);
    if (uniform(s)) {
        instance.brick = brickOf(mesh->data, glm::vec3(1.0f), who, warnings);
        instance.worldFromLocal = wt->worldFromLocal;
        instance.scale = (s.x + s.y + s.z) / 3.0;
    } else {
        // The field's space is the mesh scaled by `baked`, the scale rounded to steps of 1/64
        // of an octave (so that a scale animated by a hair does not bake again); the instance
        // keeps the rotation, the translation and what is left of the scale, within 1.1 % of
        // 1 on each axis, whose smallest is a lower bound of the distances' own scale.
        const glm::dvec3 baked = glm::exp2(glm::round(glm::log2(s) * 64.0) / 64.0);
        const glm::dvec3 rest = s / baked;
        instance.brick = brickOf(mesh->data, glm::vec3(baked), who, warnings);
        instance.worldFromLocal = wt->worldFromLocal * glm::scale(glm::dmat4(1.0), 1.0 / baked);
        instance.scale = std::min({rest.x, rest.y, rest.z});
    }
    if (instance.brick != nullptr) {
        const FieldBrick& b = *instance.brick;
        const glm::dvec3 lo = glm::dvec3(b.firstCentre) - 0.5 * static_cast<double>(b.voxelSize);
        const glm::dvec3 hi = glm::dvec3(b.lastCentre) + 0.5 * static_cast<double>(b.voxelSize);
        instance.wsCentre = glm::dvec3(instance.worldFromLocal * glm::dvec4(0.5 * (lo + hi), 1.0));
        // The field's space may carry what is left of a non-uniform scale: the largest.
        const glm::dvec3 left = axisScales(instance.worldFromLocal);
        instance.radius = 0.5 * glm::length(hi - lo) * std::max({left.x, left.y, left.z});
    }
    return instance;
}

void DistanceFieldAtlas::sortSpatially(std::size_t first) {
    // Near casters next to each other, so that a cluster's sphere is tight: by the Morton order
    // of their centres over the bounds of the centres.
    const auto begin = instances_.begin() + static_cast<std::ptrdiff_t>(first);
    DAabb bounds;
    for (auto it = begin; it != instances_.end(); ++it) bounds.extend(it->wsCentre);
    const glm::dvec3 extent = glm::max(bounds.extent(), glm::dvec3(1e-9));
    for (auto it = begin; it != instances_.end(); ++it) {  // each code once, not per comparison
        const glm::dvec3 unit = glm::clamp((it->wsCentre - bounds.min) / extent, 0.0, 1.0);
        it->morton = 0;
        for (int bit = 20; bit >= 0; --bit) {
            for (int a = 0; a < 3; ++a)
                it->morton = it->morton << 1 | ((static_cast<std::uint64_t>(unit[a] * 2097151.0) >> bit) & 1u);
        }
    }
    std::sort(begin, instances_.end(), [](const Instance& a, const Instance& b) { return a.morton < b.morton; });
}

void DistanceFieldAtlas::update(const ShadowFrame& frame, const World& world, std::vector<Warning>& warnings) {
    // Forget the fields of meshes gone (their address may come back for another mesh).
    std::erase_if(entries_, [](const auto& e) { return e.second.mesh.expired(); });
    instances_.clear();
    ranges_.clear();
    clusterCount_ = 0;
    for (const ShadowLightPlan& plan : frame.lights) {
        for (Entity caster : plan.fieldCasters) instances_.push_back(instanceOf(world, caster, plan.name, warnings));
        sortSpatially(static_cast<std::size_t>(plan.fieldFirst));
        const Range range{plan.fieldFirst, static_cast<int>(plan.fieldCasters.size()), plan.fieldClusterFirst};
        ranges_.push_back(range);
        clusterCount_ += (range.count + SG_SDF_CLUSTER - 1) / SG_SDF_CLUSTER;
    }
    uploaded_ = false;
}

void DistanceFieldAtlas::writeInstance(float* r, const Instance& in, const glm::dvec3& wsCamera) {
    if (in.brick == nullptr) {
        r[6 * 4 + 3] = -1.0f;  // no sphere: the march skips it
        return;
    }
    const FieldBrick& b = *in.brick;
    // Camera-relative world -> local, composed in double so the float rows stay exact far from
    // the origin.
    glm::dmat4 csFromLocal = in.worldFromLocal;
    csFromLocal[3] -= glm::dvec4(wsCamera, 0.0);
    const glm::dmat4 localFromCs = glm::inverse(csFromLocal);
    for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 4; ++col) r[row * 4 + col] = static_cast<float>(localFromCs[col][row]);
    }
    r[12] = b.firstCentre.x, r[13] = b.firstCentre.y, r[14] = b.firstCentre.z, r[15] = b.voxelSize;
    r[16] = b.lastCentre.x, r[17] = b.lastCentre.y, r[18] = b.lastCentre.z, r[19] = static_cast<float>(in.scale);
    r[20] = static_cast<float>(b.origin.x), r[21] = static_cast<float>(b.origin.y);
    r[22] = static_cast<float>(b.origin.z), r[23] = b.sheet ? 1.0f : 0.0f;
    // The bounding sphere of the field's box (what a ray must meet to see a distance under the
    // box's own lower bound).
    const glm::dvec3 centre = in.wsCentre - wsCamera;
    r[24] = static_cast<float>(centre.x), r[25] = static_cast<float>(centre.y);
    r[26] = static_cast<float>(centre.z), r[27] = static_cast<float>(in.radius);
    // The mesh's own bounds (local): beyond the field's centres the distance to them is a lower
    // bound far tighter than the field's padded box (exact above a plane).
    r[28] = b.meshBounds.min.x, r[29] = b.meshBounds.min.y, r[30] = b.meshBounds.min.z;
    r[32] = b.meshBounds.max.x, r[33] = b.meshBounds.max.y, r[34] = b.meshBounds.max.z;
}

void DistanceFieldAtlas::writeClusters(const glm::dvec3& wsCamera) {
    // Record texel 0: the sphere around the cluster's casters' spheres (camera-relative);
    // texel 1: the index of its first caster and their count.
    for (const Range& range : ranges_) {
        for (int c = 0; c * SG_SDF_CLUSTER < range.count; ++c) {
            float* r = &records_[static_cast<std::size_t>(range.cluster + c) * SG_SDF_INSTANCE_TEXELS * 4];
            const int first = range.first + c * SG_SDF_CLUSTER;
            const int count = std::min(SG_SDF_CLUSTER, range.count - c * SG_SDF_CLUSTER);
            const auto members =
                std::span(instances_).subspan(static_cast<std::size_t>(first), static_cast<std::size_t>(count));
            DAabb box;
            for (const Instance& in : members) {
                if (in.radius < 0.0) continue;
                box.extend(in.wsCentre - glm::dvec3(in.radius));
                box.extend(in.wsCentre + glm::dvec3(in.radius));
            }
            double radius = -1.0;
            const glm::dvec3 centre = box.empty() ? glm::dvec3(0.0) : box.center();
            for (const Instance& in : members) {
                if (in.radius >= 0.0) radius = std::max(radius, glm::length(in.wsCentre - centre) + in.radius);
            }
            const glm::dvec3 cs = centre - wsCamera;
            r[0] = static_cast<float>(cs.x), r[1] = static_cast<float>(cs.y), r[2] = static_cast<float>(cs.z);
            r[3] = static_cast<float>(radius);
            r[4] = static_cast<float>(first), r[5] = static_cast<float>(count);
        }
    }
}

GLuint DistanceFieldAtlas::instances(const glm::dvec3& wsCamera) {
    if (uploaded_ && uploadedFor_ == wsCamera) return bufferTexture_.get();
    records_.assign((instances_.size() + static_cast<std::size_t>(clusterCount_)) * SG_SDF_INSTANCE_TEXELS * 4, 0.0f);
    for (std::size_t i = 0; i < instances_.size(); ++i) {
        writeInstance(&records_[i * SG_SDF_INSTANCE_TEXELS * 4], instances_[i], wsCamera);
    }
    writeClusters(wsCamera);
    const std::size_t floats = std::max<std::size_t>(records_.size(), 4);
    if (!bufferTexture_ || floats > bufferFloats_) {
        bufferFloats_ = std::max(floats, 2 * bufferFloats_);
        buffer_ = makeBuffer("Shadow/distance-field instances", static_cast<GLsizeiptr>(bufferFloats_ * sizeof(float)),
                             nullptr, GL_DYNAMIC_STORAGE_BIT);
        bufferTexture_ = makeTexture("Shadow/distance-field instances", GL_TEXTURE_BUFFER);
        gl.TextureBuffer(bufferTexture_.get(), GL_RGBA32F, buffer_.get());
    }
    if (!records_.empty()) {
        gl.NamedBufferSubData(buffer_.get(), 0, static_cast<GLsizeiptr>(records_.size() * sizeof(float)),
                              records_.data());
    }
    checkGlError("uploading the distance-field instances");
    uploaded_ = true;
    uploadedFor_ = wsCamera;
    return bufferTexture_.get();
}

long long DistanceFieldAtlas::bytes() const {
    return static_cast<long long>(atlasSize_.x) * atlasSize_.y * atlasSize_.z * 4 +
           static_cast<long long>(bufferFloats_ * sizeof(float));
}

}  // namespace shadow::gpu
