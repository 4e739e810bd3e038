// Differential tests of the collision detection (BBUpdate, BBCollision, TriTri; seeds/002 Alg.
// 1-3) against the brute-force CPU twin (src/cpu/collision_twin.cpp): for every broad phase
// (octree depth 1-3, masked, all-pairs) and every pair rule (between objects, self, both), the
// GPU's candidate set equals the twin's exactly, and with robust precision the intersection set
// equals the exact rational oracle's. Inputs are seeded random triangle soups (strips, so
// neighbouring faces share nodes) of 1, L-1, L+1 and a large prime number of faces (L = 128),
// moved away from the rest pose the octree was built on. Discrete outputs: no tolerance anywhere;
// both sides compute the face boxes in the same float operations.

#include "core/gpu_layout.hpp"
#include "cpu/collision_twin.hpp"
#include "cpu/contact_twin.hpp"
#include "model/features.hpp"
#include "model/flat_model.hpp"
#include "model/octree_layout.hpp"
#include "passes/collision_detection.hpp"
#include "support/collision_buffers.hpp"

#include <glcollide/error.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/common.hpp>

#include <algorithm>
#include <map>
#include <random>
#include <sstream>
#include <tuple>

namespace glcollide {
namespace {

using Pairs = std::vector<std::array<std::uint32_t, 2>>;

constexpr double kThickness = 0.01; // m

struct Soup {
    model::FlatModel model;         // rest pose (the octree is built on it)
    std::vector<glm::vec3> current; // positions the GPU detects on
};

/// `faces` triangles split over `objects` objects; each object is a random-walk triangle strip
/// (face k uses nodes k, k+1, k+2) in the unit cube with steps up to 0.15 m, then every node is
/// moved by up to 0.03 m and each object by `objectOffset` * its index, so the current pose is not
/// the rest pose.
Soup makeSoup(std::uint32_t faces, std::uint32_t objects, std::uint32_t seed, glm::vec3 objectOffset = {}) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), step(-0.15f, 0.15f), jitter(-0.03f, 0.03f);
    Soup s;
    model::FlatModel& m = s.model;
    std::uint32_t faceBegin = 0;
    for (std::uint32_t o = 0; o < objects; ++o) {
        const std::uint32_t n = faces / objects + (o + 1 == objects ? faces % objects : 0u);
        model::ObjectRange r;
        r.firstNode = static_cast<std::uint32_t>(m.positions.size());
        r.firstFace = faceBegin;
        r.faceCount = n;
        r.nodeCount = n == 0 ? 0 : n + 2;
        glm::vec3 p(unit(rng), unit(rng), unit(rng));
        for (std::uint32_t k = 0; k < r.nodeCount; ++k) {
            p = glm::clamp(p + glm::vec3(step(rng), step(rng), step(rng)), glm::vec3(0.0f), glm::vec3(1.0f));
            m.positions.emplace_back(p); // float values: exactly what the GPU gets
            s.current.push_back(p + glm::vec3(jitter(rng), jitter(rng), jitter(rng)) +
                                objectOffset * static_cast<float>(o));
        }
        for (std::uint32_t k = 0; k < n; ++k)
            m.faceIndices.insert(m.faceIndices.end(),
                                 {r.firstNode + k, r.firstNode + k + 1, r.firstNode + k + 2});
        m.objects.push_back(r);
        faceBegin += n;
    }
    m.velocities.assign(m.positions.size(), glm::dvec3(0.0));
    m.masses.assign(m.positions.size(), 1.0);
    m.inverseMasses.assign(m.positions.size(), 1.0);
    return s;
}

passes::DeviceBuffers upload(const Soup& s) {
    return test::collisionBuffers(s.current, s.model.faceIndices);
}

struct Mode {
    BroadPhase broadPhase;
    int depth;
};

std::string modeName(const Mode& m) {
    switch (m.broadPhase) {
    case BroadPhase::Octree:
        return "Octree" + std::to_string(m.depth);
    case BroadPhase::Masked:
        return "Masked" + std::to_string(m.depth);
    case BroadPhase::AllPairs:
        return "AllPairs";
    case BroadPhase::Bvh:
        return "Bvh";
    }
    return "?";
}

const Mode kModes[] = {{BroadPhase::Octree, 1}, {BroadPhase::Octree, 2}, {BroadPhase::Octree, 3},
                       {BroadPhase::Masked, 1}, {BroadPhase::Masked, 2}, {BroadPhase::AllPairs, 2},
                       {BroadPhase::Bvh, 2}};
const std::uint32_t kFaceCounts[] = {1, GLC_WORKGROUP_SIZE - 1, GLC_WORKGROUP_SIZE + 1, 1009};
const cpu::PairRules kRules[] = {{true, false}, {false, true}, {true, true}};

passes::CollisionConfig configFor(const Mode& mode, const cpu::PairRules& rules, TriTriPrecision precision,
                                  std::uint32_t capacity = 4096) {
    passes::CollisionConfig c;
    c.betweenObjects = rules.betweenObjects;
    c.selfCollisions = rules.selfCollisions;
    c.settings.broadPhase = mode.broadPhase;
    c.settings.octreeDepth = mode.depth;
    c.settings.precision = precision;
    c.settings.thickness = kThickness;
    c.settings.initialCapacity = capacity;
    return c;
}

/// The twin's answer for a soup and rule, computed once per (faces, rules).
struct Expected {
    Pairs candidates, intersections;
};
const Expected& expected(const Soup& soup, std::uint32_t faces, const cpu::PairRules& rules) {
    static std::map<std::tuple<std::uint32_t, bool, bool>, Expected> cache;
    const auto key = std::make_tuple(faces, rules.betweenObjects, rules.selfCollisions);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    const model::OctreeLayout layout = model::buildOctree(soup.model, 1);
    Expected e;
    e.candidates =
        cpu::twinCandidates(soup.model.faceIndices, layout.faceObject, soup.current, kThickness, rules);
    e.intersections = cpu::twinIntersections(soup.model.faceIndices, soup.current, e.candidates);
    return cache.emplace(key, std::move(e)).first->second;
}

std::uint32_t seedFor(std::uint32_t faces) {
    return 1234u + faces;
}

class CollisionDetectionGl
    : public ::testing::TestWithParam<std::tuple<Mode, std::uint32_t, cpu::PairRules>> {};

TEST_P(CollisionDetectionGl, CandidatesAndIntersectionsMatchTheTwin) {
    const auto& [mode, faces, rules] = GetParam();
    const Soup soup = makeSoup(faces, 3, seedFor(faces));
    const passes::DeviceBuffers buffers = upload(soup);
    const Expected& e = expected(soup, faces, rules);
    passes::CollisionDetection detection(configFor(mode, rules, TriTriPrecision::Robust, 1u << 16),
                                         soup.model);
    const passes::CollisionCounts counts = detection.detect(buffers, nullptr);
    EXPECT_EQ(counts.candidates, e.candidates.size());
    EXPECT_EQ(detection.readCandidates(), e.candidates);
    EXPECT_EQ(counts.intersections, e.intersections.size());
    EXPECT_EQ(detection.readIntersections(), e.intersections) << "robust TriTri vs the exact oracle";
    // The Representative-Triangle expansion of those candidates equals the twin's.
    const cpu::FeaturePairList features =
        cpu::featurePairs(soup.model.faceIndices, detection.layout().faceOwned, e.candidates);
    EXPECT_EQ(counts.vertexFacePairs, features.vertexFace.size());
    EXPECT_EQ(counts.edgeEdgePairs, features.edgeEdge.size());
    EXPECT_EQ(detection.readVertexFacePairs(), features.vertexFace);
    EXPECT_EQ(detection.readEdgeEdgePairs(), features.edgeEdge);
    EXPECT_EQ(counts.vertexFacePairsWithoutOwnership, 6 * e.candidates.size());
    EXPECT_EQ(counts.edgeEdgePairsWithoutOwnership, 9 * e.candidates.size());
    EXPECT_EQ(counts.reruns, 0u); // 2^16 entries hold every list of these soups (growth: CapacityOne...)
    if (faces == 1009) {
        // The soup is dense enough that every rule finds work.
        EXPECT_GT(e.candidates.size(), 100u);
        EXPECT_GT(e.intersections.size(), 10u);
        RecordProperty("candidates", static_cast<int>(e.candidates.size()));
        RecordProperty("intersections", static_cast<int>(e.intersections.size()));
        RecordProperty("exact_fallbacks", static_cast<int>(counts.exactFallbacks));
    }
    // Detecting again on the same positions gives the same sets (counters are reset per call).
    detection.detect(buffers, nullptr);
    EXPECT_EQ(detection.readCandidates(), e.candidates);
}

std::string caseName(const ::testing::TestParamInfo<CollisionDetectionGl::ParamType>& info) {
    const auto& [mode, faces, rules] = info.param;
    const char* r = rules.betweenObjects ? (rules.selfCollisions ? "Both" : "Between") : "Self";
    return modeName(mode) + "_" + std::to_string(faces) + "_" + r;
}

INSTANTIATE_TEST_SUITE_P(Soups, CollisionDetectionGl,
                         ::testing::Combine(::testing::ValuesIn(kModes), ::testing::ValuesIn(kFaceCounts),
                                            ::testing::ValuesIn(kRules)),
                         caseName);

TEST(CollisionDetectionGlCases, FastPrecisionFindsTheSameCandidates) {
    const Soup soup = makeSoup(1009, 3, seedFor(1009));
    const passes::DeviceBuffers buffers = upload(soup);
    const cpu::PairRules rules{true, true};
    const Expected& e = expected(soup, 1009, rules);
    for (const Mode& mode : kModes) {
        passes::CollisionDetection detection(configFor(mode, rules, TriTriPrecision::Fast), soup.model);
        const passes::CollisionCounts counts = detection.detect(buffers, nullptr);
        EXPECT_EQ(detection.readCandidates(), e.candidates) << modeName(mode);
        EXPECT_EQ(counts.exactFallbacks, 0u) << modeName(mode);
        // Fast TriTri may disagree with the exact oracle near degenerate configurations; these
        // random soups have none, so a large disagreement would be a bug in the plumbing.
        const Pairs got = detection.readIntersections();
        Pairs diff;
        std::set_symmetric_difference(got.begin(), got.end(), e.intersections.begin(), e.intersections.end(),
                                      std::back_inserter(diff));
        EXPECT_LE(diff.size(), 2u) << modeName(mode);
        RecordProperty("fast_disagreements_" + modeName(mode), static_cast<int>(diff.size()));
    }
}

// Every coordinate on a 1/8 m grid: touching vertices and edges, coplanar and zero-area triangles
// everywhere, the hard cases of the narrow phase, reached through every broad phase.
TEST(CollisionDetectionGlCases, GridSnappedSoupWithTouchingAndCoplanarFaces) {
    Soup soup = makeSoup(509, 3, 77);
    for (glm::vec3& p : soup.current) p = glm::round(p * 8.0f) / 8.0f;
    for (glm::dvec3& p : soup.model.positions) p = glm::round(p * 8.0) / 8.0;
    const passes::DeviceBuffers buffers = upload(soup);
    const cpu::PairRules rules{true, true};
    const model::OctreeLayout layout = model::buildOctree(soup.model, 1);
    const Pairs candidates =
        cpu::twinCandidates(soup.model.faceIndices, layout.faceObject, soup.current, kThickness, rules);
    const Pairs intersections = cpu::twinIntersections(soup.model.faceIndices, soup.current, candidates);
    EXPECT_GT(intersections.size(), 100u);
    for (const Mode& mode : kModes) {
        passes::CollisionDetection detection(configFor(mode, rules, TriTriPrecision::Robust, 1u << 16),
                                             soup.model);
        const passes::CollisionCounts counts = detection.detect(buffers, nullptr);
        EXPECT_EQ(detection.readCandidates(), candidates) << modeName(mode);
        EXPECT_EQ(detection.readIntersections(), intersections)
            << modeName(mode) << ": robust TriTri vs the exact oracle";
        RecordProperty("exact_fallbacks_" + modeName(mode), static_cast<int>(counts.exactFallbacks));
    }
    RecordProperty("candidates", static_cast<int>(candidates.size()));
    RecordProperty("intersections", static_cast<int>(intersections.size()));
}

TEST(CollisionDetectionGlCases, BodiesFarApartHaveNoCandidates) {
    const Soup soup = makeSoup(1009, 2, 99, glm::vec3(100.0f, 0.0f, 0.0f));
    const passes::DeviceBuffers buffers = upload(soup);
    for (const Mode& mode : kModes) {
        passes::CollisionDetection detection(configFor(mode, {true, false}, TriTriPrecision::Robust),
                                             soup.model);
        const passes::CollisionCounts counts = detection.detect(buffers, nullptr);
        EXPECT_EQ(counts.boxPairs, 0u) << modeName(mode);
        EXPECT_EQ(counts.candidates, 0u) << modeName(mode);
        EXPECT_EQ(counts.intersections, 0u) << modeName(mode);
        EXPECT_TRUE(detection.readCandidates().empty());
    }
}

TEST(CollisionDetectionGlCases, CapacityOneGrowsAndFindsTheSameSets) {
    const Soup soup = makeSoup(1009, 3, seedFor(1009));
    const passes::DeviceBuffers buffers = upload(soup);
    const cpu::PairRules rules{true, true};
    for (const Mode& mode : kModes) {
        passes::CollisionDetection large(configFor(mode, rules, TriTriPrecision::Robust, 1u << 20),
                                         soup.model);
        passes::CollisionDetection small(configFor(mode, rules, TriTriPrecision::Robust, 1u), soup.model);
        const passes::CollisionCounts a = large.detect(buffers, nullptr);
        const passes::CollisionCounts b = small.detect(buffers, nullptr);
        EXPECT_EQ(a.reruns, 0u) << modeName(mode);
        EXPECT_GT(b.reruns, 0u) << modeName(mode);
        EXPECT_EQ(a.boxPairs, b.boxPairs) << modeName(mode);
        EXPECT_EQ(a.candidates, b.candidates) << modeName(mode);
        EXPECT_EQ(a.intersections, b.intersections) << modeName(mode);
        EXPECT_EQ(large.readCandidates(), small.readCandidates()) << modeName(mode);
        EXPECT_EQ(large.readIntersections(), small.readIntersections()) << modeName(mode);
        EXPECT_GT(b.vertexFaceGrowths, 0u) << modeName(mode);
        EXPECT_GT(b.edgeEdgeGrowths, 0u) << modeName(mode);
        EXPECT_EQ(large.readVertexFacePairs(), small.readVertexFacePairs()) << modeName(mode);
        EXPECT_EQ(large.readEdgeEdgePairs(), small.readEdgeEdgePairs()) << modeName(mode);
        // Once grown, the lists hold everything: the next call needs no rerun.
        EXPECT_EQ(small.detect(buffers, nullptr).reruns, 0u) << modeName(mode);
        EXPECT_EQ(small.readCandidates(), large.readCandidates()) << modeName(mode);
    }
}

// One list at a time: only that list starts with room for one entry, so only it overflows, is
// grown and rerun, and the sets equal those of a run with room for everything (and the twin's).
TEST(CollisionDetectionGlCases, EachListOverflowingAloneGrowsAndFindsTheSameSets) {
    const Soup soup = makeSoup(1009, 3, seedFor(1009));
    const passes::DeviceBuffers buffers = upload(soup);
    const cpu::PairRules rules{true, true};
    const Expected& want = expected(soup, 1009, rules);
    ASSERT_GT(want.intersections.size(), 1u); // every list has more than one entry to lose
    const cpu::FeaturePairList wantFeatures = cpu::featurePairs(
        soup.model.faceIndices, model::ownedFeatures(soup.model.faceIndices), want.candidates);
    enum class List { BoxPairs, Candidates, Intersections, VertexFace, EdgeEdge };
    for (const Mode& mode : kModes) {
        for (const List list :
             {List::BoxPairs, List::Candidates, List::Intersections, List::VertexFace, List::EdgeEdge}) {
            if (list == List::BoxPairs && mode.broadPhase != BroadPhase::Octree) continue; // no such list
            passes::CollisionConfig config = configFor(mode, rules, TriTriPrecision::Robust, 1u << 20);
            config.boxPairCapacity = list == List::BoxPairs ? 1u : 0u;
            config.candidateCapacity = list == List::Candidates ? 1u : 0u;
            config.intersectionCapacity = list == List::Intersections ? 1u : 0u;
            config.vertexFaceCapacity = list == List::VertexFace ? 1u : 0u;
            config.edgeEdgeCapacity = list == List::EdgeEdge ? 1u : 0u;
            passes::CollisionDetection detection(config, soup.model);
            const passes::CollisionCounts counts = detection.detect(buffers, nullptr);
            const std::string what = modeName(mode) + " list " + std::to_string(static_cast<int>(list));
            EXPECT_EQ(counts.boxPairGrowths, list == List::BoxPairs ? 1u : 0u) << what;
            EXPECT_EQ(counts.candidateGrowths, list == List::Candidates ? 1u : 0u) << what;
            EXPECT_EQ(counts.intersectionGrowths, list == List::Intersections ? 1u : 0u) << what;
            EXPECT_EQ(counts.vertexFaceGrowths, list == List::VertexFace ? 1u : 0u) << what;
            EXPECT_EQ(counts.edgeEdgeGrowths, list == List::EdgeEdge ? 1u : 0u) << what;
            EXPECT_EQ(counts.reruns, 1u) << what;
            EXPECT_EQ(detection.readCandidates(), want.candidates) << what;
            EXPECT_EQ(detection.readIntersections(), want.intersections) << what;
            EXPECT_EQ(detection.readVertexFacePairs(), wantFeatures.vertexFace) << what;
            EXPECT_EQ(detection.readEdgeEdgePairs(), wantFeatures.edgeEdge) << what;
        }
    }
}

// A list that cannot grow any further (here a 64-byte limit: 8 pairs; on a device,
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE) is an error naming the list, never a silent drop.
TEST(CollisionDetectionGlCases, AListBeyondTheBlockLimitIsAnErrorNotADrop) {
    const Soup soup = makeSoup(1009, 3, seedFor(1009));
    const passes::DeviceBuffers buffers = upload(soup);
    const Expected& want = expected(soup, 1009, {true, true});
    ASSERT_GT(want.candidates.size(), 8u);
    passes::CollisionConfig config =
        configFor({BroadPhase::AllPairs, 2}, {true, true}, TriTriPrecision::Robust, 1u);
    config.listByteLimit = 64;
    passes::CollisionDetection detection(config, soup.model);
    try {
        detection.detect(buffers, nullptr);
        FAIL() << "no error for " << want.candidates.size() << " candidates in a 64-byte list";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), ::testing::HasSubstr("collision list 'candidates' needs " +
                                                   std::to_string(want.candidates.size()) + " pairs"));
        EXPECT_THAT(e.what(),
                    ::testing::HasSubstr("GL_MAX_SHADER_STORAGE_BLOCK_SIZE, 64 bytes); no pair was dropped"));
    }
}

TEST(CollisionDetectionGlCases, LeafBoxesMatchTheTwin) {
    const Soup soup = makeSoup(1009, 3, seedFor(1009));
    const passes::DeviceBuffers buffers = upload(soup);
    for (int depth = 1; depth <= 3; ++depth) {
        passes::CollisionDetection detection(
            configFor({BroadPhase::Octree, depth}, {true, true}, TriTriPrecision::Robust), soup.model);
        detection.detect(buffers, nullptr);
        const model::OctreeLayout& layout = detection.layout();
        const auto twin = cpu::twinLeafBoxes(layout, soup.model.faceIndices, soup.current, kThickness);
        std::vector<gpu::GpuBox> gpu(layout.boxCount);
        detection.boxes().download(0, gpu.size() * sizeof(gpu::GpuBox), gpu.data());
        std::size_t empty = 0;
        for (std::uint32_t b = 0; b < layout.boxCount; ++b) {
            // Exact: min/max are exact and the inflation is one correctly rounded float op.
            EXPECT_EQ(glm::vec3(gpu[b].lo), twin[b].lo) << "depth " << depth << " box " << b;
            EXPECT_EQ(glm::vec3(gpu[b].hi), twin[b].hi) << "depth " << depth << " box " << b;
            empty += twin[b].lo.x > twin[b].hi.x ? 1u : 0u;
        }
        if (depth == 3) {
            EXPECT_GT(empty, 0u); // empty boxes are exercised
        }
    }
}

TEST(CollisionDetectionGlCases, FaceInfoAndObjectsAreUploaded) {
    const Soup soup = makeSoup(129, 3, 5);
    passes::CollisionDetection detection(
        configFor({BroadPhase::Octree, 2}, {true, true}, TriTriPrecision::Robust), soup.model);
    const model::OctreeLayout& layout = detection.layout();
    std::vector<gpu::GpuFaceInfo> info(soup.model.faceCount());
    detection.faceInfo().download(0, info.size() * sizeof(gpu::GpuFaceInfo), info.data());
    for (std::size_t f = 0; f < info.size(); ++f) {
        EXPECT_EQ(info[f].object, layout.faceObject[f]);
        EXPECT_EQ(info[f].box, layout.faceBox[f]);
        EXPECT_EQ(info[f].owned, layout.faceOwned[f]);
    }
    std::vector<gpu::GpuObject> objects(soup.model.objects.size());
    detection.objects().download(0, objects.size() * sizeof(gpu::GpuObject), objects.data());
    for (std::size_t o = 0; o < objects.size(); ++o) {
        EXPECT_EQ(objects[o].firstFace, soup.model.objects[o].firstFace);
        EXPECT_EQ(objects[o].faceCount, soup.model.objects[o].faceCount);
        EXPECT_EQ(objects[o].firstBox, o * 64u);
        EXPECT_EQ(objects[o].closed, 0u); // strips are open
    }
}

TEST(CollisionDetectionGlCases, PassNamesAndAllocations) {
    const Soup soup = makeSoup(127, 2, 3);
    passes::CollisionDetection octree(
        configFor({BroadPhase::Octree, 2}, {true, false}, TriTriPrecision::Robust), soup.model);
    passes::CollisionDetection masked(
        configFor({BroadPhase::Masked, 2}, {true, false}, TriTriPrecision::Robust), soup.model);
    passes::CollisionDetection all(
        configFor({BroadPhase::AllPairs, 2}, {true, false}, TriTriPrecision::Robust), soup.model);
    EXPECT_EQ(octree.passNames(),
              (std::vector<std::string>{"BBUpdate", "BBCollision", "TriTri", "FeaturePairs"}));
    EXPECT_EQ(masked.passNames(),
              (std::vector<std::string>{"BBUpdate", "BBCollision", "TriTri", "FeaturePairs"}));
    EXPECT_EQ(all.passNames(),
              (std::vector<std::string>{"BBCollision", "TriTri",
                                        "FeaturePairs"})); // its face-pair stage is timed as BBCollision
    auto has = [](const passes::CollisionDetection& d, const std::string& label) {
        const auto labels = d.allocatedLabels();
        return std::find(labels.begin(), labels.end(), label) != labels.end();
    };
    EXPECT_TRUE(has(octree, "boxPairs") && has(octree, "boxes") && !has(octree, "boxMask"));
    EXPECT_TRUE(has(masked, "boxMask") && has(masked, "boxes") && !has(masked, "boxPairs"));
    EXPECT_TRUE(!has(all, "boxes") && !has(all, "boxMask") && has(all, "candidates") && has(all, "faceInfo"));
    EXPECT_TRUE(has(all, "vertexFacePairs") && has(all, "edgeEdgePairs"));
    EXPECT_GT(octree.allocatedBytes(), all.allocatedBytes());
    passes::CollisionDetection bvh(configFor({BroadPhase::Bvh, 2}, {true, false}, TriTriPrecision::Robust),
                                   soup.model);
    EXPECT_EQ(bvh.passNames(),
              (std::vector<std::string>{"BvhBuild", "BvhRefit", "BvhTraverse", "TriTri", "FeaturePairs"}));
    EXPECT_TRUE(has(bvh, "bvhBoxes") && has(bvh, "bvhLinks") && has(bvh, "sortKeys") && !has(bvh, "boxes") &&
                !has(bvh, "boxPairs"));
}

} // namespace
} // namespace glcollide
