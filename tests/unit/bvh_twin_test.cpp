// The BVH twin (src/cpu/bvh_twin.cpp) against independent references: its tree against the
// definition of a binary radix tree (every node reached once from the root, ranges of sorted
// leaves, escape = the next node of a recursive depth-first walk), its boxes against the union
// of the face boxes below each node, and its candidates against the brute force
// (cpu::twinCandidates). Keys come with many duplicates (the tie rule) at 1, 2, 3, L-1, L+1 and a
// large prime number of faces (L = 128). Discrete results: no tolerance.

#include "cpu/bvh_twin.hpp"
#include "cpu/collision_twin.hpp"

#include <gtest/gtest.h>

#include <glm/common.hpp>

#include <algorithm>
#include <functional>
#include <numeric>
#include <random>

namespace glcollide::cpu {
namespace {

constexpr std::uint32_t kSizes[] = {1, 2, 3, 127, 129, 1009};

std::vector<std::uint32_t> sortedRandomKeys(std::uint32_t n, std::uint32_t distinct, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::uint32_t> key(0, distinct - 1);
    std::vector<std::uint32_t> keys(n);
    for (std::uint32_t& k : keys) k = key(rng) * 7919u % (1u << 30);
    std::sort(keys.begin(), keys.end());
    return keys;
}

struct Walk {
    std::vector<std::uint32_t> preorder;    // nodes in depth-first order, left first
    std::vector<std::uint32_t> first, last; // sorted leaf range per node
    std::vector<int> reached;               // times each node was reached from the root
};

Walk walk(const std::vector<glm::uvec4>& links) {
    const auto n = static_cast<std::uint32_t>((links.size() + 1) / 2);
    Walk w;
    w.first.assign(links.size(), 0);
    w.last.assign(links.size(), 0);
    w.reached.assign(links.size(), 0);
    std::function<void(std::uint32_t)> visit = [&](std::uint32_t node) {
        ++w.reached[node];
        w.preorder.push_back(node);
        if (node >= n - 1) {
            w.first[node] = w.last[node] = node - (n - 1);
            return;
        }
        visit(links[node].x);
        visit(links[node].y);
        w.first[node] = w.first[links[node].x];
        w.last[node] = w.last[links[node].y];
    };
    visit(0);
    return w;
}

TEST(BvhTwin, HierarchyIsABinaryRadixTreeWithEscapeLinks) {
    for (std::uint32_t n : kSizes) {
        for (std::uint32_t distinct : {1u, 5u, 1000000u}) {
            const std::vector<std::uint32_t> keys = sortedRandomKeys(n, distinct, n * 31 + distinct);
            std::vector<std::uint32_t> faces(n);
            std::iota(faces.begin(), faces.end(), 100u);
            const std::vector<glm::uvec4> links = twinHierarchy(keys, faces);
            const std::string what = std::to_string(n) + " faces, " + std::to_string(distinct) + " keys";
            ASSERT_EQ(links.size(), 2 * std::size_t{n} - 1) << what;
            const Walk w = walk(links);
            EXPECT_EQ(w.preorder.size(), links.size()) << what;
            for (std::size_t node = 0; node < links.size(); ++node) {
                EXPECT_EQ(w.reached[node], 1) << what << " node " << node;
                if (node == 0) {
                    EXPECT_EQ(links[node].z, kBvhNone) << what;
                } else {
                    const glm::uvec4& parent = links[links[node].z];
                    EXPECT_TRUE(parent.x == node || parent.y == node) << what << " node " << node;
                }
            }
            for (std::uint32_t i = 0; i < n; ++i) {
                EXPECT_EQ(links[n - 1 + i].x, faces[i]) << what;
                EXPECT_EQ(links[n - 1 + i].y, i) << what;
            }
            // Children split their parent's range; the escape is the preorder successor of the
            // subtree, which starts at the leaf after the range.
            for (std::size_t k = 0; k < w.preorder.size(); ++k) {
                const std::uint32_t node = w.preorder[k];
                if (node < n - 1) {
                    EXPECT_EQ(w.first[links[node].x], w.first[node]) << what;
                    EXPECT_EQ(w.last[links[node].x] + 1, w.first[links[node].y]) << what;
                    EXPECT_EQ(w.last[links[node].y], w.last[node]) << what;
                }
                const std::size_t after = k + (w.last[node] - w.first[node]) * 2 + 1; // subtree size 2m-1
                const std::uint32_t want = after < w.preorder.size() ? w.preorder[after] : kBvhNone;
                EXPECT_EQ(links[node].w, want) << what << " escape of node " << node;
                if (want != kBvhNone) {
                    EXPECT_EQ(w.first[want], w.last[node] + 1) << what;
                }
            }
        }
    }
}

// A strip soup in the unit cube, two objects, as in tests/gl/collision_detection_gl_test.cpp.
struct Soup {
    std::vector<std::uint32_t> faceIndices, faceObject;
    std::vector<glm::vec3> positions;
};

Soup makeSoup(std::uint32_t faces, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), step(-0.15f, 0.15f);
    Soup s;
    glm::vec3 p(unit(rng), unit(rng), unit(rng));
    for (std::uint32_t k = 0; k < faces + 2; ++k) {
        p = glm::clamp(p + glm::vec3(step(rng), step(rng), step(rng)), glm::vec3(0.0f), glm::vec3(1.0f));
        s.positions.push_back(p);
    }
    for (std::uint32_t f = 0; f < faces; ++f) {
        s.faceIndices.insert(s.faceIndices.end(), {f, f + 1, f + 2});
        s.faceObject.push_back(f < faces / 2 ? 0u : 1u);
    }
    return s;
}

std::vector<glm::uvec4> treeOf(const Soup& s) {
    const auto n = static_cast<std::uint32_t>(s.faceObject.size());
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (std::uint32_t f = 0; f < n; ++f) {
        lo = glm::min(lo, faceCentroid(s.faceIndices, s.positions, f));
        hi = glm::max(hi, faceCentroid(s.faceIndices, s.positions, f));
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> keyed;
    for (std::uint32_t f = 0; f < n; ++f)
        keyed.emplace_back(mortonCode(faceCentroid(s.faceIndices, s.positions, f), lo, hi), f);
    std::stable_sort(keyed.begin(), keyed.end(), [](auto a, auto b) { return a.first < b.first; });
    std::vector<std::uint32_t> keys, faces;
    for (auto [k, f] : keyed) {
        keys.push_back(k);
        faces.push_back(f);
    }
    return twinHierarchy(keys, faces);
}

TEST(BvhTwin, BoxesAreUnionsAndCandidatesEqualTheBruteForce) {
    constexpr float kHalf = 0.005f;
    for (std::uint32_t n : kSizes) {
        const Soup s = makeSoup(n, n);
        const std::vector<glm::uvec4> links = treeOf(s);
        const std::vector<FloatBox> boxes = twinRefit(links, s.faceIndices, s.positions, kHalf);
        for (std::size_t node = 0; node + 1 < n; ++node) {
            const FloatBox &a = boxes[links[node].x], &b = boxes[links[node].y];
            EXPECT_EQ(boxes[node].lo, glm::min(a.lo, b.lo));
            EXPECT_EQ(boxes[node].hi, glm::max(a.hi, b.hi));
        }
        for (const PairRules rules :
             {PairRules{true, false}, PairRules{false, true}, PairRules{true, true}}) {
            std::vector<FacePair> got = twinBvhCandidates(links, boxes, s.faceIndices, s.faceObject, rules);
            std::sort(got.begin(), got.end());
            EXPECT_EQ(std::adjacent_find(got.begin(), got.end()), got.end()) << n << ": a pair found twice";
            EXPECT_EQ(got, twinCandidates(s.faceIndices, s.faceObject, s.positions, 2.0 * kHalf, rules)) << n;
        }
    }
}

TEST(BvhTwin, MortonCodeInterleavesTenBitsPerAxis) {
    const glm::vec3 lo(0.0f), hi(1024.0f);
    EXPECT_EQ(mortonCode({0.5f, 0.5f, 0.5f}, lo, hi), 0u);
    EXPECT_EQ(mortonCode({1.5f, 0.5f, 0.5f}, lo, hi), 4u); // x in the highest bit of each triple
    EXPECT_EQ(mortonCode({0.5f, 1.5f, 0.5f}, lo, hi), 2u);
    EXPECT_EQ(mortonCode({0.5f, 0.5f, 1.5f}, lo, hi), 1u);
    EXPECT_EQ(mortonCode({1023.5f, 1023.5f, 1023.5f}, lo, hi), (1u << 30) - 1);
    EXPECT_EQ(mortonCode({2000.0f, -5.0f, 1024.0f}, lo, hi), 0x24924924u | 0x09249249u); // clamped x and z
    EXPECT_EQ(mortonCode({7.0f, 7.0f, 7.0f}, glm::vec3(7.0f), glm::vec3(7.0f)), 0u);     // flat bounds
    // A cube grid over the largest extent: a thin axis gets few cells, not 1024.
    const glm::vec3 thinHi(1024.0f, 2.0f, 1024.0f);
    EXPECT_EQ(mortonCode({0.5f, 1.5f, 0.5f}, lo, thinHi), 2u);
    EXPECT_EQ(mortonCode({0.5f, 1.99f, 0.5f}, lo, thinHi), 2u);
}

} // namespace
} // namespace glcollide::cpu
