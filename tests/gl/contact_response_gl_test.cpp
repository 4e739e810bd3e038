// FeaturePairs (the Representative-Triangle expansion) and ContactResponse against their twins
// (src/cpu/contact_twin.cpp: the expansion exactly, the forces in double precision) and against
// hand-computed forces. The GPU gets float positions; the twin the same floats widened to double.
// The candidates are given, as a broad phase would leave them in their list; the GPU expands them
// (a stage chain of the one FeaturePairs stage) and the response reads the two feature-pair lists.

#include "core/gpu_layout.hpp"
#include "cpu/collision_twin.hpp"
#include "cpu/contact_twin.hpp"
#include "model/features.hpp"
#include "passes/collision/feature_pairs.hpp"
#include "passes/contact_response.hpp"
#include "support/append_list_access.hpp"
#include "support/contact_objects.hpp"

#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <random>
#include <string>

namespace glcollide {
namespace {

using test::readList;

constexpr std::uint32_t kOwnAll =
    GLC_OWN_VERTEX0 | GLC_OWN_VERTEX1 | GLC_OWN_VERTEX2 | GLC_OWN_EDGE01 | GLC_OWN_EDGE12 | GLC_OWN_EDGE20;

struct Soup {
    std::vector<glm::dvec3> positions, velocities; // float values widened to double
    std::vector<std::uint32_t> faces, owned, faceObject;
    std::vector<std::uint8_t> objectClosed;
    std::vector<std::array<std::uint32_t, 2>> candidates;
};

std::vector<glm::vec4> pack(const std::vector<glm::dvec3>& v, float w) {
    std::vector<glm::vec4> out;
    for (const glm::dvec3& p : v)
        out.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z), w);
    return out;
}

template <typename T> gl::Buffer upload(const char* label, const std::vector<T>& v) {
    return gl::Buffer(label, v.size() * sizeof(T), v.data());
}

struct GpuResult {
    std::vector<glm::dvec3> forces;
    std::vector<glm::ivec4> fixedPoint; // the sums as the GPU left them
    std::uint32_t contacts = 0;
    cpu::FeaturePairList pairs; // the expansion's lists, sorted
    std::uint32_t reruns = 0;   // stage-chain reruns (a feature-pair list overflowed)
};

// `ccdComplete`: the expansion of continuous detection (GLC_CCD_COMPLETE), which adds the orphan
// feature pairs.
GpuResult runGpu(const Soup& s, const ContactParams& params, std::uint32_t listCapacity = 1u << 16,
                 bool ccdComplete = false) {
    passes::DeviceBuffers b;
    b.nodeCount = static_cast<std::uint32_t>(s.positions.size());
    b.faceCount = static_cast<std::uint32_t>(s.faces.size() / 3);
    b.positions = upload("positions", pack(s.positions, 1.0f));
    b.velocities = upload("velocities", pack(s.velocities, 0.0f));
    b.faces = upload("faces", s.faces);
    b.contactForces = upload("contactForces", std::vector<glm::ivec4>(s.positions.size(), glm::ivec4(0)));
    std::vector<gpu::GpuFaceInfo> info;
    for (std::size_t f = 0; f < s.owned.size(); ++f) info.push_back({s.faceObject[f], 0u, s.owned[f], 0u});
    const std::vector<gpu::GpuObject> objects =
        test::gpuObjects(test::nodeObjectsOfFaces(s.faces, s.faceObject, s.positions.size()), s.objectClosed);
    std::vector<glm::uvec2> pairs;
    for (const auto& [a, c] : s.candidates) pairs.emplace_back(a, c);
    const gl::Buffer faceInfo = upload("faceInfo", info), objectBuffer = upload("objects", objects);
    // The candidate list as a broad phase leaves it: its entries and its count.
    passes::AppendLists lists(0);
    const auto count = static_cast<std::uint32_t>(pairs.size());
    lists.declare(GLC_LIST_CANDIDATES,
                  {"candidates", "pairs", sizeof(glm::uvec2), GLC_BIND_FACE_PAIRS, std::max(count, 1u)});
    passes::StageChain chain;
    passes::FeaturePairs expansion(ccdComplete);
    const gl::Buffer orphans = upload("featureOrphans", model::orphanTable(s.faces, s.positions.size()));
    orphans.bindStorage(GLC_BIND_FEATURE_ORPHANS);
    expansion.addStages(chain, lists, listCapacity, listCapacity);
    test::fillCandidates(lists, pairs);
    b.faces.bindStorage(GLC_BIND_FACES);
    faceInfo.bindStorage(GLC_BIND_FACE_INFO);
    GpuResult r;
    EXPECT_EQ(lists.count(GLC_LIST_CANDIDATES), count);
    r.reruns = chain.run(lists, nullptr);
    passes::ContactResponsePass pass;
    pass.dispatch(b, {&lists, &faceInfo, &objectBuffer}, params);
    r.fixedPoint.resize(s.positions.size());
    b.contactForces.download(0, r.fixedPoint.size() * sizeof(glm::ivec4), r.fixedPoint.data());
    gpu::GpuCollisionCounters c{};
    lists.counters().download(0, sizeof c, &c);
    for (const glm::ivec4& q : r.fixedPoint)
        r.forces.push_back(glm::dvec3(q.x, q.y, q.z) / params.forceScale);
    r.contacts = c.stats[GLC_STAT_CONTACTS];
    r.pairs = {readList(lists, GLC_LIST_VERTEX_FACE), readList(lists, GLC_LIST_EDGE_EDGE)};
    EXPECT_EQ(c.lists[GLC_LIST_VERTEX_FACE].count, r.pairs.vertexFace.size());
    EXPECT_EQ(c.lists[GLC_LIST_EDGE_EDGE].count, r.pairs.edgeEdge.size());
    return r;
}

cpu::FeaturePairList cpuPairs(const Soup& s) {
    return cpu::featurePairs(s.faces, s.owned, s.candidates);
}

cpu::ContactResult runCpu(const Soup& s, const ContactParams& params) {
    std::vector<std::uint8_t> faceClosed;
    for (std::uint32_t o : s.faceObject) faceClosed.push_back(s.objectClosed[o]);
    const std::vector<std::uint32_t> nodeObject =
        test::nodeObjectsOfFaces(s.faces, s.faceObject, s.positions.size());
    cpu::ContactInput in{&s.positions, &s.velocities, &s.faces, &s.owned, &faceClosed};
    in.nodeObject = &nodeObject;
    in.faceObject = &s.faceObject;
    return cpu::contactForces(params, in, s.candidates);
}

ContactParams testParams(double thickness, double friction = 0.0) {
    CollisionSettings settings;
    settings.response = ContactResponse::Penalty; // the forces these tests check (not the default)
    settings.thickness = thickness;
    settings.stiffness = 1000.0;
    settings.damping = 0.5;
    settings.friction = friction;
    return contactParams(settings);
}

constexpr double kFloatU = 0x1p-24; // unit roundoff of float

// Bound on |GPU - k (h - d)| for penalty forces on a probe whose offset d from the closest point is
// exact in float (a face lying exactly in a coordinate plane: the closest point's normal
// coordinate is exactly 0 and its rounding in the other two enters |diff| only at second order;
// or the closest point is a corner). The float evaluation rounds h (u h), the length d (2u d),
// h - d (u (h - d)), k times the depth (u f) and the direction's component (2u f): k (u h + 2u d
// + u h) + 3u f <= 4u (k h + f); doubled, 8u (k h + f), for the weights when the force is spread
// over a face's corners. The fixed-point sum adds at most 0.5/forceScale per contribution (round
// to nearest; the scale is a power of two, so f * scale is exact).
double penaltyTolerance(const ContactParams& p, double force, int contributions) {
    return 8.0 * kFloatU * (p.stiffness * p.thickness + std::abs(force)) + contributions * 0.5 / p.forceScale;
}

// Isolated triangles (no shared nodes, so every face owns all its features) scattered in a box
// small enough that many come within the thickness; pairs between the two objects are candidates.
Soup randomSoup(std::uint32_t faceCount, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> centre(0.0f, 0.2f), offset(-0.03f, 0.03f), speed(-0.2f, 0.2f);
    Soup s;
    for (std::uint32_t f = 0; f < faceCount; ++f) {
        const glm::dvec3 c(centre(rng), centre(rng), centre(rng));
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 p = glm::vec3(c) + glm::vec3(offset(rng), offset(rng), offset(rng));
            s.positions.emplace_back(p);
            s.velocities.emplace_back(glm::vec3(speed(rng), speed(rng), speed(rng)));
            s.faces.push_back(3 * f + static_cast<std::uint32_t>(k));
        }
        s.owned.push_back(kOwnAll);
        s.faceObject.push_back(f % 2);
    }
    s.objectClosed = {0, 0};
    for (std::uint32_t a = 0; a < faceCount; ++a)
        for (std::uint32_t b = a + 1; b < faceCount; ++b)
            if ((a % 2) != (b % 2)) s.candidates.push_back({a, b});
    return s;
}

// Two objects, each a random-walk triangle strip (face k uses nodes k, k+1, k+2 of its object) in
// a box small enough for many contacts: neighbouring faces share vertices and edges, so ownership
// (model::ownedFeatures, as the engine assigns it) leaves most faces only some of their features.
Soup stripSoup(std::uint32_t faceCount, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> start(0.0f, 0.15f), step(-0.04f, 0.04f), speed(-0.2f, 0.2f);
    Soup s;
    for (std::uint32_t o = 0; o < 2; ++o) {
        const auto first = static_cast<std::uint32_t>(s.positions.size());
        const std::uint32_t faces = faceCount / 2 + (o == 1 ? faceCount % 2 : 0u);
        glm::vec3 p(start(rng), start(rng), start(rng));
        for (std::uint32_t k = 0; k < faces + 2; ++k) {
            p += glm::vec3(step(rng), step(rng), step(rng));
            // Reflected back into the box (not clamped: no faces in the box's planes).
            for (int c = 0; c < 3; ++c) p[c] = p[c] < 0.0f ? -p[c] : (p[c] > 0.15f ? 0.3f - p[c] : p[c]);
            s.positions.emplace_back(p);
            s.velocities.emplace_back(glm::vec3(speed(rng), speed(rng), speed(rng)));
        }
        for (std::uint32_t k = 0; k < faces; ++k) {
            s.faces.insert(s.faces.end(), {first + k, first + k + 1, first + k + 2});
            s.faceObject.push_back(o);
        }
    }
    s.owned = model::ownedFeatures(s.faces);
    s.objectClosed = {0, 0};
    const auto faces = static_cast<std::uint32_t>(s.owned.size());
    for (std::uint32_t a = 0; a < faces; ++a)
        for (std::uint32_t b = a + 1; b < faces; ++b)
            if (s.faceObject[a] != s.faceObject[b]) s.candidates.push_back({a, b});
    return s;
}

// Forces against the twin: per node, each contribution within the float evaluation bound below.
void expectForcesMatchTheTwin(const Soup& soup, const ContactParams& params, const GpuResult& gpu,
                              const cpu::ContactResult& cpu, const std::string& what) {
    for (std::size_t n = 0; n < soup.positions.size(); ++n) {
        // Per contribution: float evaluation of closest points, normals and the force, a few
        // tens of u (u = 2^-24) of the force cap, times an allowance of 8 for the
        // conditioning of the closest-point parameters: 2^-16 of the cap (measured on
        // llvmpipe: 2.4e-7 of the cap, 64x below), plus the fixed-point rounding of
        // 0.5/scale per component. A rule difference or a 0.1 % stiffness error is far above.
        const double tolerance =
            std::max(1u, cpu.contributions[n]) * (params.forceCap / 65536.0 + 0.5 / params.forceScale);
        for (int k = 0; k < 3; ++k)
            ASSERT_NEAR(gpu.forces[n][k], cpu.forces[n][k], tolerance) << what << " node " << n;
    }
}

// The ways the response runs. Penalty: dt = 0, sides from the current positions, each contact
// independent. Bridson (decision 0019, dt = 0.01 s): a contact acts while v_n < the target speed,
// and its force is divided by the largest count of active contacts on its moved nodes (the count
// pass into .w): in these dense soups most nodes have several, so the twin comparison sees the
// averaging, which a single contact cannot (tests/mutants/dyn-contact-no-averaging.patch). With
// friction (μ = 0.5, dt = 0.01 s; with the penalty the count pass counts the pushing contacts):
// the soups' relative speeds (up to ~0.7 m/s) make the stop term |v_t| / (W dt count) and μ f of
// the same order, so both branches of the friction's min act.
struct ResponseMode {
    const char* name;
    bool bridson;
    double friction;
};
constexpr ResponseMode kResponseModes[] = {{"penalty", false, 0.0},
                                           {"bridson", true, 0.0},
                                           {"penalty+friction", false, 0.5},
                                           {"bridson+friction", true, 0.5}};

ContactParams inMode(double thickness, const ResponseMode& mode) {
    ContactParams p = testParams(thickness, mode.friction);
    if (mode.bridson || mode.friction > 0.0) p.substep = 0.01;
    p.velocityResponse = mode.bridson;
    return p;
}

// Whether the mode's forces use the count pass (Bridson's averaging, or friction's).
bool counts(const ResponseMode& mode) {
    return mode.bridson || mode.friction > 0.0;
}

// Bridson's count pass against the twin's, and how many nodes have several active contacts.
std::uint32_t expectActiveCountsMatchTheTwin(const GpuResult& gpu, const cpu::ContactResult& cpu,
                                             const std::string& what) {
    std::uint32_t several = 0, differ = 0;
    for (std::size_t n = 0; n < cpu.approaching.size(); ++n) {
        if (cpu.approaching[n] >= 2) ++several;
        if (static_cast<std::uint32_t>(gpu.fixedPoint[n].w) != cpu.approaching[n]) ++differ;
    }
    // A contact whose normal speed is within rounding of its target may be active on one side
    // only (as a depth within rounding of 0 changes the contact count below): a few nodes.
    EXPECT_LE(differ, 2u + cpu.approaching.size() / 500) << what << ": nodes whose active count differs";
    return several;
}

TEST(ContactResponseGl, MatchesTheTwinOnRandomTriangleSoups) {
    for (const ResponseMode& mode : kResponseModes)
        for (std::uint32_t faces : {2u, 40u, 129u}) {
            const std::string what = std::string(mode.name) + ", faces " + std::to_string(faces);
            const Soup soup = randomSoup(faces, 7u + faces);
            const ContactParams params = inMode(0.03, mode);
            const GpuResult gpu = runGpu(soup, params);
            const cpu::ContactResult cpu = runCpu(soup, params);
            // Isolated triangles own every feature: 6 vertex-face and 9 edge-edge pairs per candidate.
            const cpu::FeaturePairList want = cpuPairs(soup);
            EXPECT_EQ(want.vertexFace.size(), 6 * soup.candidates.size());
            EXPECT_EQ(want.edgeEdge.size(), 9 * soup.candidates.size());
            EXPECT_EQ(gpu.pairs.vertexFace, want.vertexFace) << what;
            EXPECT_EQ(gpu.pairs.edgeEdge, want.edgeEdge) << what;
            EXPECT_EQ(gpu.reruns, 0u);
            // Dense in contacts (measured: 44 and 792 with the penalty; 31 and 621 act with
            // Bridson's response, the others separating faster than its target speed).
            if (faces >= 40) {
                EXPECT_GT(cpu.contacts, mode.bridson ? faces / 2 : faces) << what << ": too few contacts";
            }
            std::uint32_t several = 0;
            if (counts(mode)) {
                several = expectActiveCountsMatchTheTwin(gpu, cpu, what);
                // The averaging must matter: many nodes with several active contacts (measured 28
                // and 276).
                if (faces >= 40) {
                    EXPECT_GT(several, faces / 2) << what;
                }
            }
            // Contacts whose depth is within rounding of 0 may be counted on one side only; each
            // such contact adds almost no force, so only the count may differ, by a few.
            EXPECT_NEAR(static_cast<double>(gpu.contacts), static_cast<double>(cpu.contacts),
                        2.0 + 0.002 * cpu.contacts)
                << what;
            glm::dvec3 total(0.0);
            double worst = 0.0;
            for (std::size_t n = 0; n < soup.positions.size(); ++n)
                for (int k = 0; k < 3; ++k)
                    worst = std::max(worst, std::abs(gpu.forces[n][k] - cpu.forces[n][k]) /
                                                (std::max(1u, cpu.contributions[n]) * params.forceCap));
            std::printf("%s: contacts gpu %u cpu %u, %u nodes with several active contacts, worst error per "
                        "contribution %.3g of the cap\n",
                        what.c_str(), gpu.contacts, cpu.contacts, several, worst);
            expectForcesMatchTheTwin(soup, params, gpu, cpu, what);
            for (std::size_t n = 0; n < soup.positions.size(); ++n) total += gpu.forces[n];
            // Momentum: every contact applies opposite forces; only the fixed-point rounding
            // (0.5/scale per add, 4 adds per contact per component) may remain.
            const double roundoff = 4.0 * 0.5 / params.forceScale * std::max(1u, gpu.contacts);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(total[k], 0.0, roundoff) << what;
        }
}

// Strips share vertices and edges: the expansion emits only owned features, each feature pair
// once (no duplicate in the sorted lists), equal to the twin's, and far fewer than 6 + 9 per
// candidate; the forces match the twin's, with the penalty and with Bridson's response, each
// with and without friction.
TEST(ContactResponseGl, StripsExpandOnlyOwnedFeaturesOnceAndMatchTheTwin) {
    const Soup soup = stripSoup(301, 11);
    for (const ResponseMode& mode : kResponseModes) {
        const std::string what = std::string("strips, ") + mode.name;
        const ContactParams params = inMode(0.02, mode);
        const GpuResult gpu = runGpu(soup, params, 1u << 20);
        const cpu::ContactResult cpu = runCpu(soup, params);
        const cpu::FeaturePairList want = cpuPairs(soup);
        EXPECT_EQ(gpu.reruns, 0u);
        EXPECT_EQ(gpu.pairs.vertexFace, want.vertexFace);
        EXPECT_EQ(gpu.pairs.edgeEdge, want.edgeEdge);
        EXPECT_EQ(std::adjacent_find(want.vertexFace.begin(), want.vertexFace.end()), want.vertexFace.end());
        EXPECT_EQ(std::adjacent_find(want.edgeEdge.begin(), want.edgeEdge.end()), want.edgeEdge.end());
        // A strip face owns one new vertex and two new edges (the first face all three of each):
        // about 2 vertex-face and 4 edge-edge pairs per candidate instead of 6 and 9.
        EXPECT_LT(want.vertexFace.size(), 3 * soup.candidates.size());
        EXPECT_LT(want.edgeEdge.size(), 5 * soup.candidates.size());
        EXPECT_GT(cpu.contacts, 50u) << what << ": the strips should be dense in contacts";
        EXPECT_NEAR(static_cast<double>(gpu.contacts), static_cast<double>(cpu.contacts),
                    2.0 + 0.002 * cpu.contacts)
            << what;
        std::uint32_t several = 0;
        if (counts(mode)) {
            several = expectActiveCountsMatchTheTwin(gpu, cpu, what);
            EXPECT_GT(several, 100u) << what << ": the averaging must matter (measured 273 nodes)";
        }
        expectForcesMatchTheTwin(soup, params, gpu, cpu, what);
        std::printf("%s: %zu candidates, %zu vertex-face and %zu edge-edge pairs (without ownership %zu and "
                    "%zu), contacts %u, %u nodes with several active contacts\n",
                    what.c_str(), soup.candidates.size(), want.vertexFace.size(), want.edgeEdge.size(),
                    6 * soup.candidates.size(), 9 * soup.candidates.size(), gpu.contacts, several);
    }
}

// One crumpled grid cloth of 12 x 12 cells of 0.02 m (every node displaced by up to a cell per
// axis) with self-collisions: faces a ring or two apart on the mesh are candidates, so continuous
// detection's expansion adds orphans.
Soup crumpledClothSoup(std::uint32_t seed, double thickness) {
    const std::uint32_t n = 12;
    const float cell = 0.02f;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> crumple(-cell, cell), speed(-0.5f, 0.5f);
    Soup s;
    std::vector<glm::vec3> x;
    for (std::uint32_t j = 0; j <= n; ++j)
        for (std::uint32_t i = 0; i <= n; ++i) {
            x.emplace_back(static_cast<float>(i) * cell + crumple(rng), crumple(rng),
                           static_cast<float>(j) * cell + crumple(rng));
            s.positions.emplace_back(x.back());
            s.velocities.emplace_back(speed(rng), speed(rng), speed(rng));
        }
    const auto node = [&](std::uint32_t i, std::uint32_t j) { return j * (n + 1) + i; };
    for (std::uint32_t j = 0; j < n; ++j)
        for (std::uint32_t i = 0; i < n; ++i)
            s.faces.insert(s.faces.end(), {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j),
                                           node(i + 1, j + 1), node(i, j + 1)});
    s.faceObject.assign(s.faces.size() / 3, 0u);
    s.objectClosed = {0u};
    s.owned = model::ownedFeatures(s.faces);
    s.candidates = cpu::twinCandidates(s.faces, s.faceObject, x, thickness, {false, true});
    return s;
}

// Continuous detection's expansion on the GPU equals its twin, orphans included (feature pairs
// whose owner faces share a node, each listed once), and the response finds contacts among them:
// in every response mode the GPU's contacts are the twin's over the complete lists (the count may
// differ by contacts whose depth is within rounding of 0, as in the soups above), more than over
// discrete detection's lists; the discrete lists are still the twin's featurePairs. Every other
// candidate is given as (higher, lower) face, which no broad phase does: the orphan table's bits
// are for (lower, higher), and FeaturePairs must read them either way.
TEST(ContactResponseGl, OrphanFeaturePairsAreContactsOnce) {
    const double h = 0.01;
    Soup soup = crumpledClothSoup(7, h);
    for (std::size_t i = 1; i < soup.candidates.size(); i += 2)
        std::swap(soup.candidates[i][0], soup.candidates[i][1]);
    const cpu::FeaturePairList complete =
        cpu::ccdFeaturePairs(soup.faces, soup.owned, model::featureOwners(soup.faces), soup.candidates);
    const cpu::FeaturePairList plain = cpuPairs(soup);
    ASSERT_GT(complete.vertexFace.size() + complete.edgeEdge.size(),
              plain.vertexFace.size() + plain.edgeEdge.size())
        << "the soup must have orphans";
    std::vector<std::uint8_t> faceClosed(soup.faces.size() / 3, 0u);
    for (const ResponseMode& mode : kResponseModes) {
        const std::string what = std::string("crumpled cloth, ") + mode.name;
        const ContactParams params = inMode(h, mode);
        const GpuResult discrete = runGpu(soup, params, 1u << 20, false);
        const GpuResult continuous = runGpu(soup, params, 1u << 20, true);
        EXPECT_EQ(discrete.pairs.vertexFace, plain.vertexFace) << what;
        EXPECT_EQ(discrete.pairs.edgeEdge, plain.edgeEdge) << what;
        EXPECT_EQ(continuous.pairs.vertexFace, complete.vertexFace) << what;
        EXPECT_EQ(continuous.pairs.edgeEdge, complete.edgeEdge) << what;
        const cpu::ContactResult twin = cpu::contactForces(
            params, {&soup.positions, &soup.velocities, &soup.faces, &soup.owned, &faceClosed}, complete);
        EXPECT_GT(discrete.contacts, 0u) << what;
        EXPECT_GT(continuous.contacts, discrete.contacts) << what << ": the orphans must add contacts";
        EXPECT_NEAR(static_cast<double>(continuous.contacts), static_cast<double>(twin.contacts),
                    2.0 + 0.002 * twin.contacts)
            << what;
    }
}

// Room for one pair in each feature-pair list: both overflow, grow and the expansion reruns
// (once: the chain grows every overflowing list of the stage together); the lists and the
// fixed-point sums are identical to a run with room for everything (integer sums do not depend
// on the order the rerun appends in).
TEST(ContactResponseGl, CapacityOneFeatureListsGrowAndGiveIdenticalForces) {
    const Soup soup = stripSoup(301, 11);
    const ContactParams params = testParams(0.02);
    const GpuResult large = runGpu(soup, params, 1u << 20);
    const GpuResult tiny = runGpu(soup, params, 1);
    EXPECT_EQ(large.reruns, 0u);
    EXPECT_EQ(tiny.reruns, 1u);
    EXPECT_EQ(tiny.pairs.vertexFace, large.pairs.vertexFace);
    EXPECT_EQ(tiny.pairs.edgeEdge, large.pairs.edgeEdge);
    EXPECT_EQ(tiny.fixedPoint, large.fixedPoint);
    EXPECT_EQ(tiny.contacts, large.contacts);
    EXPECT_GT(large.contacts, 0u);
}

// One unit triangle in the plane y = 0 (normal +y, CCW seen from +y) and a second, tiny
// triangle whose first vertex is the probe; only that vertex is owned, so exactly one
// vertex-face contact can act (plus none of the probe face's edges).
Soup probeAboveFace(double probeHeight, bool closed) {
    Soup s;
    s.positions = {{-1, 0, -1},
                   {-1, 0, 2},
                   {2, 0, -1}, // normal = (b-a)x(c-a) = (0,0,3)x(3,0,0) = (0,9,0)
                   {0.25, probeHeight, 0.25},
                   {0.25, probeHeight + 5.0, 0.25},
                   {0.25 + 1e-3, probeHeight + 5.0, 0.25}};
    for (glm::dvec3& p : s.positions) p = glm::dvec3(glm::vec3(p)); // what the GPU sees
    s.velocities.assign(6, glm::dvec3(0.0));
    s.faces = {0, 1, 2, 3, 4, 5};
    s.owned = {kOwnAll, GLC_OWN_VERTEX0};
    s.faceObject = {0, 1};
    s.objectClosed = {static_cast<std::uint8_t>(closed ? 1 : 0), 0};
    s.candidates = {{0, 1}};
    return s;
}

TEST(ContactResponseGl, VertexAboveAFaceIsPushedOutWithThePenaltyForce) {
    const ContactParams params = testParams(0.1);
    const double height = static_cast<float>(0.04);
    const GpuResult gpu = runGpu(probeAboveFace(height, false), params);
    const double expected = params.stiffness * (params.thickness - height); // k (h - d)
    EXPECT_EQ(gpu.contacts, 1u);
    // The face lies exactly in y = 0; the probe's force is one contribution, the face's three.
    EXPECT_NEAR(gpu.forces[3].y, expected, penaltyTolerance(params, expected, 1));
    EXPECT_NEAR(gpu.forces[0].y + gpu.forces[1].y + gpu.forces[2].y, -expected,
                penaltyTolerance(params, expected, 3));
    EXPECT_EQ(gpu.forces[4], glm::dvec3(0.0));
}

TEST(ContactResponseGl, ClosedObjectsPushAnotherObjectsShallowPenetrationOutAlongTheNormal) {
    const ContactParams params = testParams(0.1);
    const double depthBelow = static_cast<float>(0.03);
    // Closed: the vertex 0.03 below the face is pushed up with k (h + 0.03).
    // Tolerances: penaltyTolerance (the face lies exactly in y = 0; the signed distance is exact).
    const GpuResult closed = runGpu(probeAboveFace(-depthBelow, true), params);
    const double pushedOut = params.stiffness * (params.thickness + depthBelow);
    EXPECT_NEAR(closed.forces[3].y, pushedOut, penaltyTolerance(params, pushedOut, 1));
    // Open (cloth): the same vertex is on the other side and is pushed further down, k (h - 0.03).
    const GpuResult open = runGpu(probeAboveFace(-depthBelow, false), params);
    const double pushedDown = -params.stiffness * (params.thickness - depthBelow);
    EXPECT_NEAR(open.forces[3].y, pushedDown, penaltyTolerance(params, pushedDown, 1));
    // Out of range on either side: nothing.
    EXPECT_EQ(runGpu(probeAboveFace(0.2, true), params).contacts, 0u);
    EXPECT_EQ(runGpu(probeAboveFace(-0.2, true), params).contacts, 0u);
    // The closed object's own vertex behind its face is not inside it: the body is thinner than the
    // thickness there, and pushing the vertex out would push it through the face. It keeps the side
    // it is on (at rest: sides from the positions), as on an open surface; the twin agrees.
    Soup own = probeAboveFace(-depthBelow, true);
    own.faceObject = {0, 0};
    own.objectClosed = {1};
    const GpuResult thin = runGpu(own, params);
    EXPECT_EQ(thin.contacts, 1u);
    EXPECT_NEAR(thin.forces[3].y, pushedDown, penaltyTolerance(params, pushedDown, 1));
    const cpu::ContactResult twin = runCpu(own, params);
    EXPECT_EQ(twin.contacts, 1u);
    EXPECT_NEAR(twin.forces[3].y, pushedDown, penaltyTolerance(params, pushedDown, 1));
}

// A vertex exactly in another object's face plane, at rest (decision 0024, "Coplanar input"): it had
// no side and got no contact, so sheets laid in one plane never came apart. Now the object whose
// nodes come first goes to the positive side of the normal turned towards GLC_COPLANAR_DIRECTION,
// the other object to the negative side, with the full depth h. A probe inside the big face (normal
// +y): pushed along -y when its nodes come last, +y when first. A probe on the big face's corner
// (d = 0, a node on a node): one of the two coincident vertices carries the contact, along its
// face's normal; the two objects are pushed apart with k·h. Within one object: no contact (before,
// the inside probe got one along a direction of rounding noise, diff / d with d ~ 1e-17).
// GPU and twin alike, node by node.
Soup coplanarProbe(glm::dvec3 at, bool probeFirst) {
    Soup s = probeAboveFace(0.0, false);
    s.positions[3] = at;
    if (!probeFirst) return s;
    // The probe's triangle takes nodes 0-2 (the probe is node 0), the face nodes 3-5; face 0 stays
    // the big face (object 0), face 1 the probe's (object 1).
    std::rotate(s.positions.begin(), s.positions.begin() + 3, s.positions.end());
    s.faces = {3, 4, 5, 0, 1, 2};
    return s;
}

TEST(ContactResponseGl, AVertexInAnotherObjectsFacePlaneIsPushedToTheSideTheNodeOrderGives) {
    const ContactParams params = testParams(0.1);
    const double full = params.stiffness * params.thickness; // k (h - 0)
    for (const bool onCorner : {false, true}) {
        for (const bool probeFirst : {false, true}) {
            SCOPED_TRACE(std::string("the probe ") + (onCorner ? "on a corner" : "inside") + ", its nodes " +
                         (probeFirst ? "first" : "last"));
            Soup s = coplanarProbe(onCorner ? glm::dvec3(-1.0, 0.0, -1.0) : glm::dvec3(0.25, 0.0, 0.25),
                                   probeFirst);
            const std::uint32_t probe = probeFirst ? 0u : 3u, big = probeFirst ? 3u : 0u; // first nodes
            const GpuResult gpu = runGpu(s, params);
            const cpu::ContactResult twin = runCpu(s, params);
            EXPECT_EQ(gpu.contacts, 1u);
            EXPECT_EQ(twin.contacts, 1u);
            for (std::size_t n = 0; n < s.positions.size(); ++n)
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(gpu.forces[n][c], twin.forces[n][c], penaltyTolerance(params, full, 3))
                        << "node " << n << " axis " << c;
            const glm::dvec3 onProbe = gpu.forces[probe] + gpu.forces[probe + 1] + gpu.forces[probe + 2];
            const glm::dvec3 onBig = gpu.forces[big] + gpu.forces[big + 1] + gpu.forces[big + 2];
            EXPECT_NEAR(glm::length(onProbe), full, penaltyTolerance(params, full, 3));
            EXPECT_NEAR(glm::length(onProbe + onBig), 0.0, 2.0 * penaltyTolerance(params, full, 3));
            // Apart: the object whose nodes come first along the side the rule gives it.
            const glm::dvec3 firstObject = probeFirst ? onProbe : onBig;
            if (!onCorner) {
                EXPECT_NEAR(firstObject.y, full, penaltyTolerance(params, full, 3)); // +y: the turned normal
            } else {
                EXPECT_GT(glm::dot(firstObject, glm::dvec3(0.5772, 0.5774, 0.5776)), 0.0);
            }
            s.faceObject = {0, 0}; // one object: no side to choose
            s.objectClosed = {0};
            EXPECT_EQ(runGpu(s, params).contacts, 0u);
            EXPECT_EQ(runCpu(s, params).contacts, 0u);
        }
    }
}

TEST(ContactResponseGl, AVertexSharedByTwoCandidateFacesActsOnce) {
    // Two faces share the probe vertex 3; only face 1 owns it. Both are candidates with face 0.
    Soup s = probeAboveFace(0.05, false);
    s.positions.push_back(glm::dvec3(glm::vec3(0.3f, 5.0f, 0.2f)));
    s.velocities.emplace_back(0.0);
    s.faces.insert(s.faces.end(), {3, 6, 5});
    s.owned = {kOwnAll, GLC_OWN_VERTEX0, 0u};
    s.faceObject = {0, 1, 1};
    s.candidates = {{0, 1}, {0, 2}};
    const ContactParams params = testParams(0.1);
    const GpuResult gpu = runGpu(s, params);
    EXPECT_EQ(gpu.contacts, 1u);
    // One contact's force k (h - d), d the float probe height; two would give twice that.
    const double once = params.stiffness * (params.thickness - static_cast<float>(0.05));
    EXPECT_NEAR(gpu.forces[3].y, once, penaltyTolerance(params, once, 1));
}

// A probe vertex near a vertex or an edge of a mesh is near every face around that feature; the
// contact counts once, for the face owning the feature (ownership as the octree assigns it: every
// vertex and edge owned by exactly one face). Before this rule a vertex meeting a vertex of
// valence 6 got six contacts, six times the stiffness the substep rule assumes.
Soup probeAboveFan(double probeHeight, int sides) {
    Soup s;
    s.positions.push_back({0, 0, 0}); // apex, node 0
    for (int i = 0; i < sides; ++i) {
        const double a = 2.0 * 3.14159265358979 * i / sides;
        s.positions.push_back(
            glm::dvec3(glm::vec3(static_cast<float>(std::cos(a)), -0.5f, static_cast<float>(std::sin(a)))));
    }
    for (int i = 0; i < sides; ++i) {
        const auto b = static_cast<std::uint32_t>(1 + i), c = static_cast<std::uint32_t>(1 + (i + 1) % sides);
        s.faces.insert(s.faces.end(), {0u, c, b}); // outward (upward) normals
        // Face i owns its edge apex-c (edge 01) and its ring edge c-b (edge 12); face 0 owns the apex.
        s.owned.push_back(GLC_OWN_EDGE01 | GLC_OWN_EDGE12 | GLC_OWN_VERTEX1 |
                          (i == 0 ? GLC_OWN_VERTEX0 : 0u));
        s.faceObject.push_back(0);
    }
    const auto probe = static_cast<std::uint32_t>(s.positions.size());
    s.positions.push_back(glm::dvec3(glm::vec3(0.0f, static_cast<float>(probeHeight), 0.0f)));
    s.positions.push_back(glm::dvec3(glm::vec3(0.0f, static_cast<float>(probeHeight) + 5.0f, 0.0f)));
    s.positions.push_back(glm::dvec3(glm::vec3(1e-3f, static_cast<float>(probeHeight) + 5.0f, 0.0f)));
    s.faces.insert(s.faces.end(), {probe, probe + 1, probe + 2});
    s.owned.push_back(kOwnAll);
    s.faceObject.push_back(1);
    s.velocities.assign(s.positions.size(), glm::dvec3(0.0));
    s.objectClosed = {0, 0};
    for (std::uint32_t f = 0; f < static_cast<std::uint32_t>(sides); ++f)
        s.candidates.push_back({f, static_cast<std::uint32_t>(sides)});
    return s;
}

TEST(ContactResponseGl, AVertexNearAVertexOfAFanGetsOneContact) {
    const ContactParams params = testParams(0.1);
    const double height = static_cast<float>(0.04);
    const Soup s = probeAboveFan(height, 6);
    const GpuResult gpu = runGpu(s, params);
    const cpu::ContactResult cpu = runCpu(s, params);
    const double expected = params.stiffness * (params.thickness - height); // one k (h - d), not six
    EXPECT_EQ(gpu.contacts, 1u);
    EXPECT_EQ(cpu.contacts, 1u);
    // The closest point is the apex, a corner (weight exactly 1): penaltyTolerance applies.
    EXPECT_NEAR(gpu.forces[7].y, expected, penaltyTolerance(params, expected, 1));
    EXPECT_NEAR(gpu.forces[0].y, -expected, penaltyTolerance(params, expected, 1)); // all on the apex
    EXPECT_NEAR(cpu.forces[7].y, expected, expected * 1e-12);
}

TEST(ContactResponseGl, AVertexNearAnEdgeOfTwoFacesGetsOneContact) {
    // Above the midpoint of the ridge apex-node1, shared by faces 0 and 5 of the fan; face 5 owns it.
    const ContactParams params = testParams(0.1);
    Soup s = probeAboveFan(0.0, 6);
    const glm::dvec3 ridgeMid = 0.5 * (s.positions[0] + s.positions[1]);
    const glm::dvec3 up = glm::normalize(glm::dvec3(ridgeMid.x, 1.0, ridgeMid.z)); // roughly outward
    const double gap = static_cast<float>(0.03);
    for (std::size_t k = 7; k < 10; ++k) s.positions[k] += ridgeMid + gap * up - s.positions[7];
    for (glm::dvec3& p : s.positions) p = glm::dvec3(glm::vec3(p));
    const GpuResult gpu = runGpu(s, params);
    const cpu::ContactResult cpu = runCpu(s, params);
    EXPECT_EQ(gpu.contacts, 1u);
    EXPECT_EQ(cpu.contacts, 1u);
    const double force = glm::length(gpu.forces[7]);
    // The per-contribution bound of MatchesTheTwinOnRandomTriangleSoups (2^-16 of the cap in float
    // evaluation, 0.5/forceScale fixed point) on each of three components: sqrt(3) of it on the length.
    EXPECT_NEAR(force, glm::length(cpu.forces[7]),
                std::sqrt(3.0) * (params.forceCap / 65536.0 + 0.5 / params.forceScale));
    EXPECT_LT(force, params.stiffness * params.thickness); // one contact's force at most
}

// The response with a substep length (decision 0019): sides from the previous positions x − dt·v
// and the inelastic part. GPU against twin with expectForcesMatchTheTwin's per-contribution bound
// (its inelastic term adds a few roundings of relative 2^-24 to a force below the cap, inside it).
//
// A vertex 0.02 below an open face, moving down at 3 m/s: 0.03 m in a substep of 0.01 s, so at
// its start it was 0.01 above. It went through within the substep: it is pushed back up (the
// unsigned rule of dt = 0 pushes it on down), by the impulse that stops it plus the penalty for
// depth h + 0.02 (limited), and the face gets the opposite force.
TEST(ContactResponseGl, AVertexThatCameThroughAnOpenFaceIsPushedBack) {
    const double below = static_cast<float>(0.02);
    Soup s = probeAboveFace(-below, false);
    for (std::size_t k = 3; k < 6; ++k) s.velocities[k] = {0.0, -3.0, 0.0};
    ContactParams params = testParams(0.1);
    const GpuResult still = runGpu(s, params); // dt = 0: sides from the current positions
    EXPECT_LT(still.forces[3].y, 0.0);
    params.substep = 0.01; // 10 dt = 0.1 s > the relaxation time 0.01 s: Bridson's 0.1 depth / dt
    params.velocityResponse = true;
    const GpuResult gpu = runGpu(s, params);
    const cpu::ContactResult cpu = runCpu(s, params);
    EXPECT_EQ(gpu.contacts, 1u);
    EXPECT_EQ(cpu.contacts, 1u);
    EXPECT_EQ(cpu.approaching[3], 1u);
    const glm::dvec3 w =
        cpu::closestOnTriangle(s.positions[3], s.positions[0], s.positions[1], s.positions[2]);
    const double wSum = 1.0 + glm::dot(w, w); // inverse masses 1
    // Bridson as forces (contact_force.glsl): the impulse cancelling v_n = -3 plus the penalty
    // for depth h + 0.02, at most what gives the target speed 0.1 depth / dt; one active contact.
    const double depth = params.thickness + below, perSpeed = 1.0 / (wSum * params.substep);
    const double want = std::min(3.0 * perSpeed + std::min(params.stiffness * depth + params.damping * 3.0,
                                                           0.1 * depth / params.substep * perSpeed),
                                 params.forceCap);
    EXPECT_NEAR(cpu.forces[3].y, want, want * 1e-12); // double arithmetic
    expectForcesMatchTheTwin(s, params, gpu, cpu, "substep response");
    EXPECT_GT(gpu.forces[3].y, 0.0);
    EXPECT_LT(gpu.forces[0].y + gpu.forces[1].y + gpu.forces[2].y, 0.0);
    // The same vertex at rest there came from below: it is kept below (pushed down).
    s.velocities.assign(6, glm::dvec3(0.0));
    EXPECT_LT(runGpu(s, params).forces[3].y, 0.0);
}

// Two edges that crossed within the substep: edge 0 of face A along x at y = 0 (A stands in the
// plane z = 0, above it), edge 0 of face B along z at y = −0.02 moving down at 3 m/s, so 0.01
// above A's edge at the start. B is pushed back up, A down, by the same force; both match the twin.
TEST(ContactResponseGl, EdgesThatCrossedArePushedBackToTheirSides) {
    Soup s;
    s.positions = {{-1, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.1, -0.02, -1}, {0.1, -0.02, 1}, {0.1, -2, 0}};
    for (glm::dvec3& p : s.positions) p = glm::dvec3(glm::vec3(p));
    s.velocities = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, -3, 0}, {0, -3, 0}, {0, -3, 0}};
    s.faces = {0, 1, 2, 3, 4, 5};
    s.owned = {kOwnAll, kOwnAll};
    s.faceObject = {0, 1};
    s.objectClosed = {0, 0};
    s.candidates = {{0, 1}};
    ContactParams params = testParams(0.1);
    params.substep = 0.01; // 10 dt = 0.1 s > the relaxation time 0.01 s: Bridson's 0.1 depth / dt
    params.velocityResponse = true;
    const GpuResult gpu = runGpu(s, params);
    const cpu::ContactResult cpu = runCpu(s, params);
    EXPECT_EQ(gpu.contacts, 1u);
    EXPECT_EQ(cpu.contacts, 1u);
    expectForcesMatchTheTwin(s, params, gpu, cpu, "substep response");
    EXPECT_GT(gpu.forces[3].y + gpu.forces[4].y, 0.0);
    EXPECT_LT(gpu.forces[0].y + gpu.forces[1].y, 0.0);
    // The stopping impulse plus the limited penalty for depth h + 0.02 (as in the vertex test),
    // weights (0.45, 0.55) and (0.5, 0.5). Tolerance 1e-5 relative: 0.02 and 0.1 are rounded to
    // float in the positions (relative 2^-24 each), and the closest-point parameters follow.
    const double wSum = 0.55 * 0.55 + 0.45 * 0.45 + 0.5 * 0.5 + 0.5 * 0.5, depth = 0.12;
    const double perSpeed = 1.0 / (wSum * params.substep);
    const double want = 3.0 * perSpeed + std::min(params.stiffness * depth + params.damping * 3.0,
                                                  0.1 * depth / params.substep * perSpeed);
    EXPECT_NEAR(cpu.forces[3].y + cpu.forces[4].y, std::min(want, params.forceCap), 1e-5 * want);
}

// Friction (contact_force.glsl's frictionForce) on one vertex-face contact: the probe of
// probeAboveFace 0.04 above the face (h = 0.1: the normal force k (h − 0.04) = 60 N, no normal
// speed), all its face's nodes sliding along x at `speed`, the face at rest, dt = 0.01 s, inverse
// masses 1, μ = 0.5. The friction is −x on the probe and +x on the face (by its weights), of
// magnitude min(μ·60 N = 30 N, speed / (W dt)) with W = 1 + |w|²; the normal force is unchanged.
struct SlidingProbe {
    GpuResult gpu;
    cpu::ContactResult cpu;
    double normal = 0.0, coulomb = 0.0, stop = 0.0; // N: k (h − d), μ k (h − d), speed / (W dt)
};

SlidingProbe slidingProbe(double speed, double substep) {
    Soup s = probeAboveFace(static_cast<float>(0.04), false);
    for (std::size_t k = 3; k < 6; ++k) s.velocities[k] = {static_cast<float>(speed), 0.0, 0.0};
    ContactParams params = testParams(0.1, 0.5);
    params.substep = substep;
    SlidingProbe r;
    r.gpu = runGpu(s, params);
    r.cpu = runCpu(s, params);
    const glm::dvec3 w =
        cpu::closestOnTriangle(s.positions[3], s.positions[0], s.positions[1], s.positions[2]);
    r.normal = params.stiffness * (params.thickness - s.positions[3].y);
    r.coulomb = params.friction * r.normal;
    r.stop = substep > 0.0 ? s.velocities[3].x / ((1.0 + glm::dot(w, w)) * substep) : 0.0;
    EXPECT_EQ(r.gpu.contacts, 1u);
    EXPECT_EQ(r.cpu.contacts, 1u);
    expectForcesMatchTheTwin(s, params, r.gpu, r.cpu, "sliding probe");
    return r;
}

// Tolerance of the GPU's friction on the probe: the float evaluation of |v_t|, W and the
// quotient, a few u (2^-24) each; 64u of the force allows for the closest-point weights, plus
// the fixed-point rounding 0.5/scale. The twin (double) is held to 1e-12 relative.
double frictionTolerance(const ContactParams& p, double force) {
    return 64.0 * kFloatU * std::abs(force) + 0.5 / p.forceScale;
}

// Slow sliding (0.01 m/s: the stop term, 0.75 N, is below μ f = 30 N): the friction is exactly
// what stops the relative tangential velocity in the substep, W dt F = speed, never more (which
// would reverse the sliding and, over substeps, add energy).
TEST(ContactResponseGl, FrictionStopsSlowSlidingWithoutReversingIt) {
    const SlidingProbe r = slidingProbe(0.01, 0.01);
    ASSERT_LT(r.stop, r.coulomb);
    EXPECT_NEAR(r.cpu.forces[3].x, -r.stop, 1e-12 * r.stop);
    const ContactParams p = testParams(0.1, 0.5);
    EXPECT_NEAR(r.gpu.forces[3].x, -r.stop, frictionTolerance(p, r.stop));
    EXPECT_NEAR(r.gpu.forces[0].x + r.gpu.forces[1].x + r.gpu.forces[2].x, r.stop,
                frictionTolerance(p, r.stop) * 3);
    EXPECT_NEAR(r.gpu.forces[3].y, r.normal, penaltyTolerance(p, r.normal, 1));
    EXPECT_EQ(r.gpu.forces[3].z, 0.0);
}

// Fast sliding (5 m/s: the stop term, 375 N, is above μ f = 30 N): the friction is Coulomb's μ f.
TEST(ContactResponseGl, FrictionOnFastSlidingIsMuTimesTheNormalForce) {
    const SlidingProbe r = slidingProbe(5.0, 0.01);
    ASSERT_GT(r.stop, r.coulomb);
    EXPECT_NEAR(r.cpu.forces[3].x, -r.coulomb, 1e-12 * r.coulomb);
    const ContactParams p = testParams(0.1, 0.5);
    EXPECT_NEAR(r.gpu.forces[3].x, -r.coulomb,
                penaltyTolerance(p, r.normal, 1)); // μ ≤ 1 times the normal force's
    EXPECT_NEAR(r.gpu.forces[3].y, r.normal, penaltyTolerance(p, r.normal, 1));
}

// Without a substep length (dt = 0) there is no "stops in this substep" bound: no friction.
TEST(ContactResponseGl, NoFrictionWithoutASubstepLength) {
    const SlidingProbe r = slidingProbe(5.0, 0.0);
    EXPECT_EQ(r.cpu.forces[3].x, 0.0);
    EXPECT_EQ(r.gpu.forces[3].x, 0.0);
    EXPECT_GT(r.gpu.forces[3].y, 0.0);
}

// Friction alone never adds kinetic energy. The friction forces are the difference of the runs
// with μ = 0.5 and μ = 0 (the normal forces are the same: the penalty does not use the count, and
// Bridson's count does not depend on μ). Applied over dt to nodes of inverse mass 1, they change
// the kinetic energy by ΔE = dt Σ F_i·v_i + dt²/2 Σ |F_i|², which the cap makes ≤ 0: per contact
// dt λ (−|v_t| + dt W λ count / 2) with λ ≤ |v_t| / (W dt count), and Cauchy-Schwarz bounds the
// sum over a node's contacts by its count (docs/collisions.md, "Friction between bodies").
double frictionEnergyChange(const Soup& s, const std::vector<glm::dvec3>& withFriction,
                            const std::vector<glm::dvec3>& without, double dt) {
    double change = 0.0;
    for (std::size_t n = 0; n < s.positions.size(); ++n) {
        const glm::dvec3 f = withFriction[n] - without[n];
        change += dt * glm::dot(f, s.velocities[n]) + 0.5 * dt * dt * glm::dot(f, f);
    }
    return change;
}

TEST(ContactResponseGl, FrictionAloneNeverAddsKineticEnergy) {
    for (const bool bridson : {false, true})
        for (const std::uint32_t faces : {40u, 129u}) {
            const Soup soup = randomSoup(faces, 7u + faces);
            ContactParams with = testParams(0.03, 0.5), without = testParams(0.03);
            with.substep = without.substep = 0.01;
            with.velocityResponse = without.velocityResponse = bridson;
            const cpu::ContactResult cpuWith = runCpu(soup, with), cpuWithout = runCpu(soup, without);
            const GpuResult gpuWith = runGpu(soup, with), gpuWithout = runGpu(soup, without);
            const double twin = frictionEnergyChange(soup, cpuWith.forces, cpuWithout.forces, with.substep);
            const double gpu = frictionEnergyChange(soup, gpuWith.forces, gpuWithout.forces, with.substep);
            // The GPU's forces are within expectForcesMatchTheTwin's tolerance t_n of the twin's in
            // each run: |ΔE error| ≤ Σ dt (|v_n| + dt (|F_n| + 2 t_n)) · 2√3 t_n.
            double bound = 0.0;
            for (std::size_t n = 0; n < soup.positions.size(); ++n) {
                const double t =
                    std::max(1u, cpuWith.contributions[n]) *
                    (with.forceCap / 65536.0 + 0.5 / std::min(with.forceScale, without.forceScale));
                const double f = glm::length(cpuWith.forces[n] - cpuWithout.forces[n]);
                bound += with.substep * (glm::length(soup.velocities[n]) + with.substep * (f + 2.0 * t)) *
                         2.0 * std::sqrt(3.0) * t;
            }
            std::printf(
                "%s, faces %u: friction's kinetic energy change twin %.4g J, gpu %.4g J (bound on the "
                "gpu's error %.2g J)\n",
                bridson ? "bridson" : "penalty", faces, twin, gpu, bound);
            EXPECT_LE(twin, 0.0);
            EXPECT_LT(twin, -10.0 * bound) << "friction must remove energy here, well above the GPU's error";
            EXPECT_LE(gpu, bound);
        }
}

// No candidates: empty lists, zero-group dispatches, no force.
TEST(ContactResponseGl, NoCandidatesNoPairsNoForce) {
    Soup s = probeAboveFace(0.04, false);
    s.candidates.clear();
    const GpuResult gpu = runGpu(s, testParams(0.1));
    EXPECT_TRUE(gpu.pairs.vertexFace.empty());
    EXPECT_TRUE(gpu.pairs.edgeEdge.empty());
    EXPECT_EQ(gpu.contacts, 0u);
    for (const glm::ivec4& q : gpu.fixedPoint) EXPECT_EQ(q, glm::ivec4(0));
}

} // namespace
} // namespace glcollide
