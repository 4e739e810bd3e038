// The linear BVH broad phase on the GPU against independent references:
//  * the radix sort against std::stable_sort;
//  * the tree the GPU builds against the CPU twin (src/cpu/bvh_twin.cpp) given the GPU's sorted
//    keys (integer arithmetic: exact), the keys against the twin's Morton codes, the boxes against
//    the twin's refit (exact float min/max), and the traversal's node visits against the twin's;
//  * refit equals rebuild on the same positions; the rebuild cadence in frames;
//  * traversal that resumes across dispatches (a budget of 1, 3 and 16 node visits per dispatch)
//    loses no pair; candidates of a folded cloth equal the brute force and the octree's;
//  * scenes full of equal Morton codes (the tie rule): the twin's tree, the brute force's pairs.
// The parameterised soups of collision_detection_gl_test.cpp run the BVH through every pair rule,
// at 1, L-1, L+1 and a large prime number of faces, and with capacity 1 on every list.

#include "core/gpu_layout.hpp"
#include "cpu/bvh_twin.hpp"
#include "cpu/collision_twin.hpp"
#include "gl/handles.hpp"
#include "gl/program.hpp"
#include "model/face_box.hpp"
#include "model/flat_model.hpp"
#include "passes/broad_phase/radix_sort.hpp"
#include "passes/collision_detection.hpp"
#include "support/collision_buffers.hpp"

#include <glcollide/error.hpp>

#include <gtest/gtest.h>

#include <glm/common.hpp>

#include <epoxy/gl.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <string>

namespace glcollide {
namespace {

using Pairs = std::vector<std::array<std::uint32_t, 2>>;

constexpr double kThickness = 0.01; // m

template <typename T> std::vector<T> download(const gl::Buffer& b, std::size_t count) {
    std::vector<T> out(count);
    if (count) b.download(0, count * sizeof(T), out.data());
    return out;
}

// ---------------------------------------------------------------------------------------------
// Radix sort

void expectSortsLikeStdStableSort(std::uint32_t count, std::uint32_t keyBits, std::uint32_t distinct) {
    std::mt19937 rng(count * 7 + keyBits + distinct);
    const std::uint32_t mask = keyBits == 32 ? 0xffffffffu : (1u << keyBits) - 1;
    std::vector<std::uint32_t> palette(distinct);
    for (std::uint32_t& k : palette) k = static_cast<std::uint32_t>(rng()) & mask;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs(count);
    for (std::uint32_t i = 0; i < count; ++i) pairs[i] = {palette[rng() % distinct], i};
    passes::RadixSort sort(count);
    std::vector<std::uint32_t> keys, values;
    for (auto [k, v] : pairs) {
        keys.push_back(k);
        values.push_back(v);
    }
    sort.load(keys, values);
    sort.sort(count, keyBits);
    std::stable_sort(pairs.begin(), pairs.end(), [](auto a, auto b) { return a.first < b.first; });
    const auto gotKeys = download<std::uint32_t>(sort.keys(), count);
    const auto gotValues = download<std::uint32_t>(sort.values(), count);
    std::size_t wrong = 0;
    for (std::uint32_t i = 0; i < count; ++i)
        wrong += gotKeys[i] != pairs[i].first || gotValues[i] != pairs[i].second ? 1 : 0;
    EXPECT_EQ(wrong, 0u) << count << " keys of " << keyBits << " bits, " << distinct << " distinct";
}

TEST(RadixSortGl, EqualsStdStableSort) {
    for (std::uint32_t count : {1u, 2u, 255u, 256u, 257u, 1009u, 100003u})
        for (std::uint32_t distinct : {1u, 7u, 100000u}) {
            expectSortsLikeStdStableSort(count, 30, distinct);
            expectSortsLikeStdStableSort(count, 32, distinct);
        }
}

TEST(RadixSortGl, RefusesMoreKeysThanItsCapacity) {
    passes::RadixSort sort(10);
    EXPECT_THROW(sort.sort(11, 30), Error);
}

// ---------------------------------------------------------------------------------------------
// Scenes

struct Scene {
    model::FlatModel model;
    std::vector<glm::vec3> current;
    std::vector<std::uint32_t> faceObject;
};

void finish(Scene& s) {
    model::FlatModel& m = s.model;
    m.velocities.assign(m.positions.size(), glm::dvec3(0.0));
    m.masses.assign(m.positions.size(), 1.0);
    m.inverseMasses.assign(m.positions.size(), 1.0);
    s.faceObject.assign(m.faceCount(), 0);
    for (std::uint32_t o = 0; o < m.objects.size(); ++o)
        for (std::uint32_t f = 0; f < m.objects[o].faceCount; ++f)
            s.faceObject[m.objects[o].firstFace + f] = o;
    if (s.current.empty())
        for (const glm::dvec3& p : m.positions) s.current.emplace_back(p);
}

/// Random-walk triangle strips, `objects` of them, in the unit cube.
Scene strips(std::uint32_t faces, std::uint32_t objects, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), step(-0.15f, 0.15f);
    Scene s;
    for (std::uint32_t o = 0; o < objects; ++o) {
        const std::uint32_t n = faces / objects + (o + 1 == objects ? faces % objects : 0u);
        model::ObjectRange r;
        r.firstNode = static_cast<std::uint32_t>(s.model.positions.size());
        r.firstFace = static_cast<std::uint32_t>(s.model.faceCount());
        r.faceCount = n;
        r.nodeCount = n == 0 ? 0 : n + 2;
        glm::vec3 p(unit(rng), unit(rng), unit(rng));
        for (std::uint32_t k = 0; k < r.nodeCount; ++k) {
            p = glm::clamp(p + glm::vec3(step(rng), step(rng), step(rng)), glm::vec3(0.0f), glm::vec3(1.0f));
            s.model.positions.emplace_back(p);
        }
        for (std::uint32_t k = 0; k < n; ++k)
            s.model.faceIndices.insert(s.model.faceIndices.end(),
                                       {r.firstNode + k, r.firstNode + k + 1, r.firstNode + k + 2});
        s.model.objects.push_back(r);
    }
    finish(s);
    return s;
}

/// A square cloth of `cells` x `cells` quads (2 triangles each) folded like an accordion into
/// layers `spacing` apart, each `cells / layers` rows long: every layer lies within the contact
/// distance of the next, the self-colliding cloth of the BVH paper.
Scene foldedCloth(std::uint32_t cells, std::uint32_t layers, double spacing) {
    Scene s;
    const double h = 1.0 / cells;
    const std::uint32_t rowsPerLayer = cells / layers;
    for (std::uint32_t i = 0; i <= cells; ++i) {
        const std::uint32_t layer = std::min(i / rowsPerLayer, layers - 1);
        const std::uint32_t along = i - layer * rowsPerLayer;
        const double y = (layer % 2 == 0 ? along : rowsPerLayer - along) * h;
        for (std::uint32_t j = 0; j <= cells; ++j) s.model.positions.emplace_back(j * h, y, layer * spacing);
    }
    const auto node = [&](std::uint32_t i, std::uint32_t j) { return i * (cells + 1) + j; };
    for (std::uint32_t i = 0; i < cells; ++i)
        for (std::uint32_t j = 0; j < cells; ++j) {
            s.model.faceIndices.insert(s.model.faceIndices.end(),
                                       {node(i, j), node(i, j + 1), node(i + 1, j + 1)});
            s.model.faceIndices.insert(s.model.faceIndices.end(),
                                       {node(i, j), node(i + 1, j + 1), node(i + 1, j)});
        }
    model::ObjectRange r;
    r.nodeCount = static_cast<std::uint32_t>(s.model.positions.size());
    r.faceCount = 2 * cells * cells;
    s.model.objects.push_back(r);
    finish(s);
    return s;
}

/// `base` `copies` times over, every copy its own object at the same positions: every face
/// centroid, hence every Morton code, appears `copies` times.
Scene coincidentCopies(const Scene& base, std::uint32_t copies) {
    Scene s;
    const auto nodes = static_cast<std::uint32_t>(base.model.positions.size());
    const auto faces = static_cast<std::uint32_t>(base.model.faceCount());
    for (std::uint32_t c = 0; c < copies; ++c) {
        s.model.positions.insert(s.model.positions.end(), base.model.positions.begin(),
                                 base.model.positions.end());
        for (std::uint32_t i : base.model.faceIndices) s.model.faceIndices.push_back(c * nodes + i);
        for (model::ObjectRange r : base.model.objects) {
            r.firstNode += c * nodes;
            r.firstFace += c * faces;
            s.model.objects.push_back(r);
        }
    }
    finish(s);
    return s;
}

/// Adds an object of `count` separate triangles (no shared nodes) that share one vertex box, the
/// cube of half-side `halfSide` at `centre`: two opposite corners of the cube and a third vertex
/// inside it, different for each. Their centroids (the box's centre) are bitwise equal, so all of
/// them get one Morton code, and every two of them are a candidate pair.
void addSameCentroidTriangles(Scene& s, std::uint32_t count, const glm::dvec3& centre, double halfSide,
                              std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> inside(-0.9 * halfSide, 0.9 * halfSide);
    model::ObjectRange r;
    r.firstNode = static_cast<std::uint32_t>(s.model.positions.size());
    r.firstFace = static_cast<std::uint32_t>(s.model.faceCount());
    r.nodeCount = 3 * count;
    r.faceCount = count;
    for (std::uint32_t k = 0; k < count; ++k) {
        const std::uint32_t first = r.firstNode + 3 * k;
        s.model.positions.push_back(centre - glm::dvec3(halfSide));
        s.model.positions.push_back(centre + glm::dvec3(halfSide));
        s.model.positions.push_back(centre + glm::dvec3(inside(rng), inside(rng), inside(rng)));
        s.model.faceIndices.insert(s.model.faceIndices.end(), {first, first + 1, first + 2});
    }
    s.model.objects.push_back(r);
    s.current.clear();
    finish(s);
}

passes::DeviceBuffers upload(const Scene& s) {
    return test::collisionBuffers(s.current, s.model.faceIndices);
}

void setPositions(passes::DeviceBuffers& b, const std::vector<glm::vec3>& current) {
    const std::vector<glm::vec4> p = test::positionsWithUnitW(current);
    b.positions.upload(0, p.size() * sizeof(glm::vec4), p.data());
}

passes::CollisionConfig bvhConfig(const cpu::PairRules& rules,
                                  BvhRebuild rebuild = BvhRebuild::EverySubstep) {
    passes::CollisionConfig c;
    c.betweenObjects = rules.betweenObjects;
    c.selfCollisions = rules.selfCollisions;
    c.settings.broadPhase = BroadPhase::Bvh;
    c.settings.thickness = kThickness;
    c.settings.precision = TriTriPrecision::Fast;
    c.settings.bvh.rebuild = rebuild;
    return c;
}

Pairs bruteForce(const Scene& s, const std::vector<glm::vec3>& at, const cpu::PairRules& rules) {
    return cpu::twinCandidates(s.model.faceIndices, s.faceObject, at, kThickness, rules);
}

struct Tree {
    std::vector<std::uint32_t> keys, faces;
    std::vector<glm::uvec4> links;
    std::vector<gpu::GpuBox> boxes;
};

Tree readTree(const passes::CollisionDetection& d, std::uint32_t faces) {
    Tree t;
    t.keys = download<std::uint32_t>(d.broadPhaseBuffer("sortKeys"), faces);
    t.faces = download<std::uint32_t>(d.broadPhaseBuffer("sortValues"), faces);
    t.links = download<glm::uvec4>(d.broadPhaseBuffer("bvhLinks"), 2 * std::size_t{faces} - 1);
    t.boxes = download<gpu::GpuBox>(d.broadPhaseBuffer("bvhBoxes"), 2 * std::size_t{faces} - 1);
    return t;
}

/// bvh_hierarchy.comp alone, on sorted keys and their faces given by the test: its links.
std::vector<glm::uvec4> hierarchyKernel(const std::vector<std::uint32_t>& sortedKeys,
                                        const std::vector<std::uint32_t>& sortedFaces) {
    const auto n = static_cast<std::uint32_t>(sortedKeys.size());
    passes::RadixSort sorted(n); // only its buffers: the kernel reads the sorted pairs there
    sorted.load(sortedKeys, sortedFaces);
    sorted.bindForReading();
    const gl::Buffer links =
        gl::makeBuffer("bvhLinks", std::vector<glm::uvec4>(2 * std::size_t{n} - 1, glm::uvec4(0)));
    links.bindStorage(GLC_BIND_BVH_LINKS);
    const gl::ComputeProgram hierarchy("bvh_hierarchy");
    hierarchy.set("u_faceCount", n);
    hierarchy.use();
    hierarchy.dispatch1D(n, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    return download<glm::uvec4>(links, 2 * std::size_t{n} - 1);
}

/// The number of nodes whose links differ between two trees (0: equal); a count, not the whole
/// vectors, in a failure message.
std::size_t nodesWithOtherLinks(const std::vector<glm::uvec4>& got, const std::vector<glm::uvec4>& want) {
    if (got.size() != want.size()) return std::max(got.size(), want.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < got.size(); ++i) differing += got[i] != want[i] ? 1 : 0;
    return differing;
}

/// The scene's Morton codes as the twin computes them, sorted stably, with their faces.
std::pair<std::vector<std::uint32_t>, std::vector<std::uint32_t>> twinSortedKeys(const Scene& s) {
    const auto faces = static_cast<std::uint32_t>(s.model.faceCount());
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (std::uint32_t f = 0; f < faces; ++f) {
        lo = glm::min(lo, cpu::faceCentroid(s.model.faceIndices, s.current, f));
        hi = glm::max(hi, cpu::faceCentroid(s.model.faceIndices, s.current, f));
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (std::uint32_t f = 0; f < faces; ++f)
        pairs.emplace_back(cpu::mortonCode(cpu::faceCentroid(s.model.faceIndices, s.current, f), lo, hi), f);
    std::stable_sort(pairs.begin(), pairs.end(), [](auto a, auto b) { return a.first < b.first; });
    std::pair<std::vector<std::uint32_t>, std::vector<std::uint32_t>> sorted;
    for (auto [key, face] : pairs) {
        sorted.first.push_back(key);
        sorted.second.push_back(face);
    }
    return sorted;
}

void expectBoxesEqualTwinRefit(const Tree& t, const Scene& s, const std::vector<glm::vec3>& at,
                               const std::string& what) {
    const std::vector<cpu::FloatBox> want =
        cpu::twinRefit(t.links, s.model.faceIndices, at, model::halfThicknessFloat(kThickness));
    std::size_t wrong = 0;
    for (std::size_t n = 0; n < want.size(); ++n)
        wrong += glm::vec3(t.boxes[n].lo) != want[n].lo || glm::vec3(t.boxes[n].hi) != want[n].hi ? 1 : 0;
    EXPECT_EQ(wrong, 0u) << what << ": node boxes differing from the twin's refit";
}

// ---------------------------------------------------------------------------------------------
// Build

TEST(BvhGl, TreeKeysAndBoxesMatchTheTwin) {
    for (std::uint32_t faces : {1u, 2u, 127u, 129u, 1009u}) {
        const Scene s = strips(faces, 2, faces);
        const passes::DeviceBuffers buffers = upload(s);
        passes::CollisionDetection d(bvhConfig({true, true}), s.model);
        const passes::CollisionCounts counts = d.detect(buffers, nullptr);
        EXPECT_TRUE(counts.bvhRebuilt);
        const Tree t = readTree(d, faces);
        const std::string what = std::to_string(faces) + " faces";
        EXPECT_TRUE(std::is_sorted(t.keys.begin(), t.keys.end())) << what;
        std::vector<std::uint32_t> sortedFaces = t.faces;
        std::sort(sortedFaces.begin(), sortedFaces.end());
        for (std::uint32_t f = 0; f < faces; ++f)
            ASSERT_EQ(sortedFaces[f], f) << what << ": not a permutation";
        // The hierarchy is integer arithmetic on the keys: exactly the twin's.
        EXPECT_EQ(t.links, cpu::twinHierarchy(t.keys, t.faces)) << what;
        expectBoxesEqualTwinRefit(t, s, s.current, what);
        // Morton codes: the twin's, up to one cell per axis. The GPU may round 1024 / extent
        // differently (GLSL allows 2.5 ulp for division), which moves a centroid on a cell
        // boundary by one cell; equal ties keep the face order (stable sort).
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (std::uint32_t f = 0; f < faces; ++f) {
            lo = glm::min(lo, cpu::faceCentroid(s.model.faceIndices, s.current, f));
            hi = glm::max(hi, cpu::faceCentroid(s.model.faceIndices, s.current, f));
        }
        const auto cell = [](std::uint32_t code, int axis) {
            std::uint32_t v = 0;
            for (int b = 0; b < 10; ++b) v |= ((code >> (3 * b + (2 - axis))) & 1u) << b;
            return static_cast<int>(v);
        };
        std::size_t exact = 0;
        for (std::uint32_t i = 0; i < faces; ++i) {
            const std::uint32_t want =
                cpu::mortonCode(cpu::faceCentroid(s.model.faceIndices, s.current, t.faces[i]), lo, hi);
            exact += want == t.keys[i] ? 1 : 0;
            for (int axis = 0; axis < 3; ++axis)
                EXPECT_LE(std::abs(cell(want, axis) - cell(t.keys[i], axis)), 1)
                    << what << " face " << t.faces[i];
        }
        RecordProperty("morton_exact_" + std::to_string(faces), static_cast<int>(exact));
    }
}

TEST(BvhGl, NodeVisitsEqualTheTwinTraversal) {
    const Scene s = strips(1009, 3, 5);
    const passes::DeviceBuffers buffers = upload(s);
    const cpu::PairRules rules{true, true};
    passes::CollisionDetection d(bvhConfig(rules), s.model);
    const passes::CollisionCounts counts = d.detect(buffers, nullptr);
    const Tree t = readTree(d, 1009);
    std::vector<cpu::FloatBox> boxes =
        cpu::twinRefit(t.links, s.model.faceIndices, s.current, model::halfThicknessFloat(kThickness));
    std::uint64_t visits = 0;
    Pairs twin = cpu::twinBvhCandidates(t.links, boxes, s.model.faceIndices, s.faceObject, rules, &visits);
    std::sort(twin.begin(), twin.end());
    EXPECT_EQ(d.readCandidates(), twin);
    EXPECT_EQ(counts.bvhNodeVisits, visits);
    EXPECT_EQ(counts.bvhRounds, 1u);
}

// Equal Morton codes: the tree tells them apart by their sorted index (the tie rule of
// bvh_hierarchy.comp's delta), which only shows where codes repeat; the random strips above have
// (almost) none. The kernel alone first, on sorted random keys with few distinct values (runs of
// equal keys up to the whole input), at 1, 2, 3, L-1, L+1 and two primes of leaves (L = 128, the
// work group): its links are the twin's, whose tie rule tests/unit/bvh_twin_test.cpp checks
// against the definition of a radix tree.
TEST(BvhGl, HierarchyKernelEqualsTheTwinOnKeysFullOfTies) {
    for (std::uint32_t n : {1u, 2u, 3u, 127u, 129u, 1009u, 4099u})
        for (std::uint32_t distinct : {1u, 2u, 7u, n / 4 + 1}) {
            std::mt19937 rng(n * 31 + distinct);
            std::uniform_int_distribution<std::uint32_t> value(0, distinct - 1);
            std::vector<std::uint32_t> keys(n), faces(n);
            for (std::uint32_t& k : keys) k = value(rng) * 7919u % (1u << 30); // 30-bit codes
            std::sort(keys.begin(), keys.end());
            std::iota(faces.begin(), faces.end(), 0u);
            std::shuffle(faces.begin(), faces.end(), rng);
            EXPECT_EQ(nodesWithOtherLinks(hierarchyKernel(keys, faces), cpu::twinHierarchy(keys, faces)), 0u)
                << n << " keys, " << distinct << " distinct values";
        }
}

// The same through the whole broad phase, on two scenes full of equal codes: two coincident
// copies of a strip (every code twice), and a strip beside 300 triangles with one centroid (one
// run of 300 equal codes). The GPU's tree on its own keys is the twin's, and the candidates are
// the brute force's.
TEST(BvhGl, EqualMortonCodesGiveTheTwinsTreeAndEveryPair) {
    struct Case {
        std::string name;
        Scene scene;
        std::size_t minTies; // sorted positions whose key equals the previous one, at least
        std::size_t minRun;  // the longest run of one key, at least
    };
    std::vector<Case> cases;
    cases.push_back(
        {"two coincident copies of a 509-face strip", coincidentCopies(strips(509, 1, 23), 2), 509, 2});
    Scene sameCentroid = strips(300, 1, 29);
    addSameCentroidTriangles(sameCentroid, 300, glm::dvec3(0.5), 0.02, 31);
    cases.push_back({"300 triangles with one centroid beside a strip", std::move(sameCentroid), 299, 300});
    const cpu::PairRules rules{true, true};
    for (const Case& c : cases) {
        const Scene& s = c.scene;
        const auto faces = static_cast<std::uint32_t>(s.model.faceCount());
        // A tree built with a wrong tie rule can have no finite walk, and the traversal would rerun
        // with ever more rounds and never return: check the kernel on this scene's codes (the
        // twin's, within a cell of the GPU's) before the whole broad phase runs.
        const auto [twinKeys, twinFaces] = twinSortedKeys(s);
        ASSERT_EQ(nodesWithOtherLinks(hierarchyKernel(twinKeys, twinFaces),
                                      cpu::twinHierarchy(twinKeys, twinFaces)),
                  0u)
            << c.name;
        const passes::DeviceBuffers buffers = upload(s);
        passes::CollisionDetection d(bvhConfig(rules), s.model);
        d.detect(buffers, nullptr);
        const Tree t = readTree(d, faces);
        std::size_t ties = 0, run = 1, longestRun = 1;
        for (std::uint32_t i = 1; i < faces; ++i) {
            run = t.keys[i] == t.keys[i - 1] ? run + 1 : 1;
            ties += run > 1 ? 1 : 0;
            longestRun = std::max(longestRun, run);
        }
        // The scene really is full of equal keys, or the test would test nothing.
        EXPECT_GE(ties, c.minTies) << c.name;
        EXPECT_GE(longestRun, c.minRun) << c.name;
        EXPECT_EQ(nodesWithOtherLinks(t.links, cpu::twinHierarchy(t.keys, t.faces)), 0u) << c.name;
        const Pairs want = bruteForce(s, s.current, rules);
        EXPECT_GT(want.size(), std::size_t{faces}) << c.name; // coincident faces all meet
        EXPECT_EQ(d.readCandidates(), want) << c.name;
    }
}

// ---------------------------------------------------------------------------------------------
// Refit and cadence

TEST(BvhGl, RefitEqualsRebuildOnTheSamePositions) {
    Scene s = strips(1009, 2, 11);
    passes::DeviceBuffers buffers = upload(s);
    const cpu::PairRules rules{true, true};
    passes::CollisionDetection refitOnly(bvhConfig(rules, BvhRebuild::Never), s.model);
    const passes::CollisionCounts built = refitOnly.detect(buffers, nullptr);
    EXPECT_TRUE(built.bvhRebuilt);
    const Tree atRest = readTree(refitOnly, 1009);
    // The same positions again: a refit reproduces the built boxes exactly.
    EXPECT_FALSE(refitOnly.detect(buffers, nullptr).bvhRebuilt);
    const Tree again = readTree(refitOnly, 1009);
    EXPECT_EQ(again.links, atRest.links);
    expectBoxesEqualTwinRefit(again, s, s.current, "refit on the build positions");
    for (std::size_t n = 0; n < atRest.boxes.size(); ++n) {
        EXPECT_EQ(again.boxes[n].lo, atRest.boxes[n].lo);
        EXPECT_EQ(again.boxes[n].hi, atRest.boxes[n].hi);
    }
    // Moved positions: the old tree refit holds the twin's boxes for that tree and finds the same
    // candidates as a tree rebuilt there, and as the brute force.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> move(-0.1f, 0.1f);
    for (glm::vec3& p : s.current) p += glm::vec3(move(rng), move(rng), move(rng));
    setPositions(buffers, s.current);
    const passes::CollisionCounts refit = refitOnly.detect(buffers, nullptr);
    EXPECT_FALSE(refit.bvhRebuilt);
    const Tree moved = readTree(refitOnly, 1009);
    EXPECT_EQ(moved.links, atRest.links);
    expectBoxesEqualTwinRefit(moved, s, s.current, "refit on moved positions");
    passes::CollisionDetection rebuilt(bvhConfig(rules, BvhRebuild::EverySubstep), s.model);
    const passes::CollisionCounts fresh = rebuilt.detect(buffers, nullptr);
    EXPECT_EQ(refitOnly.readCandidates(), bruteForce(s, s.current, rules));
    EXPECT_EQ(rebuilt.readCandidates(), refitOnly.readCandidates());
    RecordProperty("node_visits_refit", static_cast<int>(refit.bvhNodeVisits));
    RecordProperty("node_visits_rebuilt", static_cast<int>(fresh.bvhNodeVisits));
}

TEST(BvhGl, RebuildCadenceCountsFrames) {
    const Scene s = strips(129, 1, 2);
    const passes::DeviceBuffers buffers = upload(s);
    const auto rebuilds = [&](BvhRebuild rebuild, int frames) {
        passes::CollisionConfig c = bvhConfig({false, true}, rebuild);
        c.settings.bvh.rebuildFrames = frames;
        c.substepsPerFrame = 3;
        passes::CollisionDetection d(c, s.model);
        std::string pattern;
        for (int i = 0; i < 12; ++i) pattern += d.detect(buffers, nullptr).bvhRebuilt ? 'B' : '.';
        return pattern;
    };
    EXPECT_EQ(rebuilds(BvhRebuild::EverySubstep, 1), "BBBBBBBBBBBB");
    EXPECT_EQ(rebuilds(BvhRebuild::EveryFrame, 1), "B..B..B..B..");
    EXPECT_EQ(rebuilds(BvhRebuild::EveryNFrames, 2), "B.....B.....");
    EXPECT_EQ(rebuilds(BvhRebuild::Never, 1), "B...........");
}

// ---------------------------------------------------------------------------------------------
// Traversal

// A budget of a few node visits per dispatch is far below the tree's depth: every query stops
// many times and resumes from its saved node; the stage reruns with more rounds until all finish.
TEST(BvhGl, TraversalResumesAcrossDispatchesWithoutLosingPairs) {
    const Scene s = strips(1009, 3, 17);
    const passes::DeviceBuffers buffers = upload(s);
    const cpu::PairRules rules{true, true};
    const Pairs want = bruteForce(s, s.current, rules);
    ASSERT_GT(want.size(), 1000u);
    passes::CollisionDetection unlimited(bvhConfig(rules), s.model);
    const passes::CollisionCounts reference = unlimited.detect(buffers, nullptr);
    for (std::uint32_t budget : {1u, 3u, 16u}) {
        passes::CollisionConfig c = bvhConfig(rules);
        c.settings.bvh.visitsPerRound = budget;
        passes::CollisionDetection d(c, s.model);
        const passes::CollisionCounts first = d.detect(buffers, nullptr);
        EXPECT_EQ(d.readCandidates(), want) << budget;
        EXPECT_GT(first.bvhRounds, 1u) << budget;
        EXPECT_GT(first.reruns, 0u) << budget;
        // Resumed or not, the walk is the same: the same nodes are visited in all.
        EXPECT_EQ(first.bvhNodeVisits, reference.bvhNodeVisits) << budget;
        // Once it has enough rounds, the next substep needs no rerun.
        const passes::CollisionCounts next = d.detect(buffers, nullptr);
        EXPECT_EQ(next.reruns, 0u) << budget;
        EXPECT_EQ(d.readCandidates(), want) << budget;
    }
}

TEST(BvhGl, FoldedClothCandidatesEqualTheBruteForceAndTheOctree) {
    const Scene s = foldedCloth(60, 6, 0.6 * kThickness);
    const passes::DeviceBuffers buffers = upload(s);
    const cpu::PairRules rules{false, true};
    const Pairs want = bruteForce(s, s.current, rules);
    ASSERT_GT(want.size(), s.model.faceCount()); // every layer meets the next
    passes::CollisionDetection bvh(bvhConfig(rules), s.model);
    bvh.detect(buffers, nullptr);
    EXPECT_EQ(bvh.readCandidates(), want);
    passes::CollisionConfig octree = bvhConfig(rules);
    octree.settings.broadPhase = BroadPhase::Octree;
    octree.settings.octreeDepth = 3;
    passes::CollisionDetection oct(octree, s.model);
    oct.detect(buffers, nullptr);
    EXPECT_EQ(oct.readCandidates(), want);
}

TEST(BvhGl, MemoryPerFaceStaysWithinTheBudget) {
    const Scene s = foldedCloth(100, 4, 0.6 * kThickness);
    passes::CollisionDetection bvh(bvhConfig({false, true}), s.model);
    const double perFace =
        static_cast<double>(bvh.broadPhaseBytes()) / static_cast<double>(s.model.faceCount());
    RecordProperty("bytes_per_face", std::to_string(perFace));
    EXPECT_LE(perFace, 192.0); // the budget: tree, sort buffers and traversal state
}

} // namespace
} // namespace glcollide
