// Bake time of the Stanford bunny's distance field (engine/src/sdf/) at the voxel budgets of
// docs/distance_fields.md: the median of three bakes each, after the OBJ is loaded. Times are
// printed, never asserted. Run build/bin/distance_field_bake.
#include <shadow/distance_field.h>
#include <shadow/scene.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

namespace {

using namespace shadow;

constexpr int kRuns = 3;

/// Median wall time (s) of `kRuns` bakes, and the last field.
double medianBakeSeconds(const MeshData& mesh, const DistanceFieldSettings& settings, DistanceField& field) {
    std::vector<double> seconds;
    for (int run = 0; run < kRuns; ++run) {
        const auto start = std::chrono::steady_clock::now();
        Result<DistanceField> baked = bakeDistanceField(mesh, settings);
        seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        if (!baked.ok()) {
            std::fprintf(stderr, "bake failed: %s\n", baked.error().message.c_str());
            return -1.0;
        }
        field = std::move(baked).value();
    }
    std::sort(seconds.begin(), seconds.end());
    return seconds[kRuns / 2];
}

}  // namespace

int main() {
    const Result<std::shared_ptr<MeshData>> bunny = loadObjMesh(kBunnyObjPath);
    if (!bunny.ok()) {
        std::fprintf(stderr, "%s\n", bunny.error().message.c_str());
        return 1;
    }
    const MeshData& mesh = **bunny;
    std::printf("bunny: %zu triangles; hardware threads: %u; median of %d bakes\n", mesh.indices.size() / 3,
                std::thread::hardware_concurrency(), kRuns);
    std::printf("%-8s %-8s %-16s %-10s %-12s %s\n", "budget", "threads", "grid", "voxels", "bytes", "bake (s)");
    struct Case {
        int edge;
        int threads;
    };
    for (const Case c : {Case{64, 1}, Case{64, 0}, Case{128, 1}, Case{128, 0}}) {
        DistanceFieldSettings settings;
        settings.voxelBudget = c.edge * c.edge * c.edge;
        settings.threads = c.threads;
        DistanceField field;
        const double seconds = medianBakeSeconds(mesh, settings, field);
        if (seconds < 0.0) return 1;
        char grid[32];
        std::snprintf(grid, sizeof grid, "%dx%dx%d", field.size.x, field.size.y, field.size.z);
        std::printf("%d^3    %-8s %-16s %-10zu %-12zu %.3f\n", c.edge, c.threads == 0 ? "all" : "1", grid,
                    field.distances.size(), field.byteSize(), seconds);
    }
    return 0;
}
