// A minimal Wavefront OBJ reader for the Stanford bunny of Debian's glmark2-data: positions and
// polygon faces (fanned into triangles); normals are computed smooth, by area-weighted average.
#include <shadow/scene.h>

#include <fstream>
#include <sstream>

namespace shadow {
namespace {

/// Smooth vertex normals from area-weighted face normals.
void smoothNormals(MeshData& mesh) {
    std::vector<glm::dvec3> sum(mesh.positions.size(), glm::dvec3(0.0));
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::dvec3 a(mesh.positions[mesh.indices[t]]);
        const glm::dvec3 b(mesh.positions[mesh.indices[t + 1]]);
        const glm::dvec3 c(mesh.positions[mesh.indices[t + 2]]);
        const glm::dvec3 n = glm::cross(b - a, c - a);  // length = twice the area
        for (int k = 0; k < 3; ++k) sum[mesh.indices[t + k]] += n;
    }
    mesh.normals.resize(mesh.positions.size());
    for (std::size_t i = 0; i < sum.size(); ++i) {
        const double len = glm::length(sum[i]);
        mesh.normals[i] = len > 0.0 ? glm::vec3(sum[i] / len) : glm::vec3(0, 1, 0);
    }
}

}  // namespace

Result<std::shared_ptr<MeshData>> loadObjMesh(const std::string& path) {
    std::ifstream in(path);
    if (!in) return Error{ErrorCode::FileUnreadable, path + ": cannot open"};
    auto mesh = std::make_shared<MeshData>();
    mesh->name = path.substr(path.find_last_of('/') + 1);
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        std::istringstream ls(line);
        std::string tag;
        ls >> tag;
        if (tag == "v") {
            glm::vec3 p;
            if (!(ls >> p.x >> p.y >> p.z) || !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                return Error{ErrorCode::MalformedFile, path + ":" + std::to_string(lineNo) + ": bad vertex"};
            }
            mesh->positions.push_back(p);
        } else if (tag == "f") {
            std::vector<std::uint32_t> face;
            std::string item;
            while (ls >> item) {
                // "i", "i/t", "i//n", "i/t/n"; negative indices count from the end.
                long index = 0;
                try {
                    index = std::stol(item.substr(0, item.find('/')));
                } catch (...) {
                    return Error{ErrorCode::MalformedFile,
                                 path + ":" + std::to_string(lineNo) + ": bad face index '" + item + "'"};
                }
                const long count = static_cast<long>(mesh->positions.size());
                if (index < 0) index = count + index + 1;
                if (index < 1 || index > count) {
                    return Error{ErrorCode::InvalidValue,
                                 path + ":" + std::to_string(lineNo) + ": face index " + item + " out of range"};
                }
                face.push_back(static_cast<std::uint32_t>(index - 1));
            }
            for (std::size_t k = 2; k < face.size(); ++k) {
                mesh->indices.insert(mesh->indices.end(), {face[0], face[k - 1], face[k]});
            }
        }
    }
    if (mesh->indices.empty()) return Error{ErrorCode::MalformedFile, path + ": no faces"};
    smoothNormals(*mesh);
    computeBounds(*mesh);
    computeClosed(*mesh);
    return mesh;
}

}  // namespace shadow
