// vertexCacheOrder (components.h): T. Forsyth, "Linear-Speed Vertex Cache Optimisation" (2006).
//
// A greedy walk over the triangles. Each vertex has a score: high while it sits near the front of
// a modelled LRU cache of the last vertices drawn (the three of the triangle just drawn score a
// little less than the next few, so that the walk does not turn back on itself), plus a bonus
// that grows as it has fewer triangles left to draw (so that the walk finishes a region instead
// of leaving lone triangles behind). A triangle scores the sum of its vertices'; the walk draws,
// each step, the best triangle among those of the vertices in the cache, which is where scores
// changed. When none is left there, it takes the next triangle not drawn in the input's order.
// Each step touches the cache's vertices and their triangles only: linear in the triangle count.
#include <shadow/components.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace shadow {

namespace vertex_cache_order {

constexpr int kCacheSize = 32;               // entries of the modelled LRU cache
constexpr float kLastTriangleScore = 0.75f;  // the three vertices of the triangle just drawn
constexpr float kCacheDecayPower = 1.5f;
constexpr float kValenceBoostScale = 2.0f;
constexpr float kValenceBoostPower = 0.5f;
constexpr int kValenceTable = 64;  // valences past it score as it

/// The two parts of a vertex's score, tabulated once (each update would otherwise take two
/// powers): by its place in the cache, and by the triangles it has left (up to kValenceTable).
struct ScoreTables {
    std::array<float, kCacheSize> cache{};
    std::array<float, kValenceTable + 1> valence{};

    ScoreTables() {
        const float scaler = 1.0f / static_cast<float>(kCacheSize - 3);
        for (int k = 0; k < kCacheSize; ++k) {
            cache[static_cast<std::size_t>(k)] =
                k < 3 ? kLastTriangleScore : std::pow(1.0f - static_cast<float>(k - 3) * scaler, kCacheDecayPower);
        }
        for (int n = 1; n <= kValenceTable; ++n) {
            valence[static_cast<std::size_t>(n)] =
                kValenceBoostScale * std::pow(static_cast<float>(n), -kValenceBoostPower);
        }
    }
};

/// The score of a vertex at `position` of the cache (-1: not in it) with `remaining` triangles
/// left to draw (0: none, it scores nothing).
float vertexScore(const ScoreTables& tables, int position, std::uint32_t remaining) {
    if (remaining == 0) return -1.0f;
    const float cached = position >= 0 ? tables.cache[static_cast<std::size_t>(position)] : 0.0f;
    return cached + tables.valence[std::min<std::uint32_t>(remaining, kValenceTable)];
}

/// Each vertex's triangles not yet drawn: `triangles[first[v], first[v] + live[v])`.
struct Adjacency {
    std::vector<std::uint32_t> first, live, triangles;

    Adjacency(const std::vector<std::uint32_t>& indices, std::size_t vertexCount)
        : first(vertexCount + 1, 0), live(vertexCount, 0) {
        const std::size_t triangleCount = indices.size() / 3;
        forEachCorner(indices, triangleCount, [this](std::uint32_t v, std::size_t) { ++live[v]; });
        for (std::size_t v = 0; v < vertexCount; ++v) first[v + 1] = first[v] + live[v];
        triangles.resize(first[vertexCount]);
        std::vector<std::uint32_t> filled(vertexCount, 0);
        forEachCorner(indices, triangleCount, [this, &filled](std::uint32_t v, std::size_t t) {
            triangles[first[v] + filled[v]++] = static_cast<std::uint32_t>(t);
        });
    }

    /// Removes drawn triangle `t` from vertex `v`'s live triangles.
    void remove(std::uint32_t v, std::uint32_t t) {
        std::uint32_t* begin = triangles.data() + first[v];
        std::uint32_t* end = begin + live[v];
        std::uint32_t* at = std::find(begin, end, t);
        if (at == end) return;
        std::swap(*at, *(end - 1));
        --live[v];
    }

    /// `f(vertex, triangle)` once per distinct vertex of each triangle (a degenerate triangle
    /// names a vertex twice but counts once).
    template <class F>
    static void forEachCorner(const std::vector<std::uint32_t>& indices, std::size_t triangleCount, F&& f) {
        for (std::size_t t = 0; t < triangleCount; ++t) {
            const std::uint32_t a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
            f(a, t);
            if (b != a) f(b, t);
            if (c != a && c != b) f(c, t);
        }
    }
};

/// The walk's state: the modelled cache, each vertex's and each triangle's score.
class Walk {
public:
    Walk(const std::vector<std::uint32_t>& indices, std::size_t vertexCount)
        : indices_(indices),
          adjacency_(indices, vertexCount),
          cachePosition_(vertexCount, -1),
          score_(vertexCount),
          triangleScore_(indices.size() / 3, 0.0f) {
        for (std::size_t v = 0; v < vertexCount; ++v) score_[v] = vertexScore(tables_, -1, adjacency_.live[v]);
        Adjacency::forEachCorner(indices, indices.size() / 3,
                                 [this](std::uint32_t v, std::size_t t) { triangleScore_[t] += score_[v]; });
    }

    /// Draws triangle `t`: its distinct vertices move to the cache's front, the others keep
    /// their order behind them, and the scores of every vertex that moved follow.
    void draw(std::size_t t) {
        const std::array<std::uint32_t, 3> tri{indices_[3 * t], indices_[3 * t + 1], indices_[3 * t + 2]};
        int count = 0;
        for (std::uint32_t v : tri) {
            if (std::find(next_.begin(), next_.begin() + count, v) != next_.begin() + count) continue;
            next_[count++] = v;
            adjacency_.remove(v, static_cast<std::uint32_t>(t));
        }
        for (int k = 0; k < cached_; ++k) {
            if (std::find(tri.begin(), tri.end(), cache_[k]) == tri.end()) next_[count++] = cache_[k];
        }
        for (int k = kCacheSize; k < count; ++k) cachePosition_[next_[k]] = -1;  // dropped
        for (int k = 0; k < count; ++k) {
            const std::uint32_t v = next_[k];
            if (k < kCacheSize) cachePosition_[v] = k;
            const float updated = vertexScore(tables_, cachePosition_[v], adjacency_.live[v]);
            const float delta = updated - score_[v];
            score_[v] = updated;
            forEachLive(v, [this, delta](std::uint32_t j) { triangleScore_[j] += delta; });
        }
        cached_ = std::min(count, kCacheSize);
        cache_ = next_;  // its first `cached_` entries
    }

    /// The best triangle not drawn among the cached vertices', or `none` when they have none.
    [[nodiscard]] std::size_t best(std::size_t none) const {
        std::size_t chosen = none;
        float bestScore = -1.0f;
        for (int k = 0; k < cached_; ++k) {
            forEachLive(cache_[k], [this, &chosen, &bestScore](std::uint32_t j) {
                if (triangleScore_[j] > bestScore) {
                    bestScore = triangleScore_[j];
                    chosen = j;
                }
            });
        }
        return chosen;
    }

private:
    template <class F>
    void forEachLive(std::uint32_t v, F&& f) const {
        const std::uint32_t* live = adjacency_.triangles.data() + adjacency_.first[v];
        for (std::uint32_t j = 0; j < adjacency_.live[v]; ++j) f(live[j]);
    }

    const std::vector<std::uint32_t>& indices_;
    const ScoreTables tables_;
    Adjacency adjacency_;
    std::vector<int> cachePosition_;
    std::vector<float> score_;
    std::vector<float> triangleScore_;
    // The cache, front first, with room for the three vertices a step pushes in before the
    // entries pushed past its end are dropped.
    std::array<std::uint32_t, kCacheSize + 3> cache_{}, next_{};
    int cached_ = 0;
};

}  // namespace vertex_cache_order

std::vector<std::uint32_t> vertexCacheOrder(const std::vector<std::uint32_t>& indices, std::size_t vertexCount) {
    const std::size_t triangleCount = indices.size() / 3;
    if (indices.size() % 3 != 0 || triangleCount < 2 ||
        std::any_of(indices.begin(), indices.end(), [vertexCount](std::uint32_t i) { return i >= vertexCount; })) {
        return indices;
    }
    vertex_cache_order::Walk walk(indices, vertexCount);
    std::vector<bool> drawn(triangleCount, false);
    std::vector<std::uint32_t> out;
    out.reserve(indices.size());
    std::size_t cursor = 0;  // the input's first triangle that may not be drawn yet
    std::size_t next = 0;
    for (std::size_t step = 0; step < triangleCount; ++step) {
        if (next == triangleCount) {  // no candidate among the cache's triangles: the next in input order
            while (drawn[cursor]) ++cursor;
            next = cursor;
        }
        drawn[next] = true;
        out.insert(out.end(), indices.begin() + static_cast<std::ptrdiff_t>(3 * next),
                   indices.begin() + static_cast<std::ptrdiff_t>(3 * next + 3));
        walk.draw(next);
        next = walk.best(triangleCount);
    }
    return out;
}

}  // namespace shadow
