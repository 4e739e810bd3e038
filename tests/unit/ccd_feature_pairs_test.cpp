// Continuous detection's expansion (cpu::ccdFeaturePairs, the twin of feature_pairs.comp with
// GLC_CCD_COMPLETE) against a brute force without ownership (cpu::ccdCoverage): on folded cloths
// and crumpled soups with self-collisions, every feature pair of every valid face pair whose swept
// boxes overlap (and whose own swept feature boxes overlap) is in the lists, where ownership alone
// loses some, and none is there twice (a contact counted twice doubles its force); the entries
// beyond discrete detection's expansion are exactly orphans (their owner faces share a node), and
// the response finds contacts among them. GL-free; the GPU's lists are compared with this twin in
// tests/gl/continuous_detection_gl_test.cpp and the GPU's forces in
// tests/gl/contact_response_gl_test.cpp.

#include "core/contact_params.hpp"
#include "cpu/ccd_twin.hpp"
#include "cpu/contact_twin.hpp"
#include "cpu/feature_coverage.hpp"
#include "model/features.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <cstdio>
#include <random>
#include <string>

namespace glcollide {
namespace {

struct SelfScene {
    std::vector<std::uint32_t> faces, object;
    std::vector<glm::vec3> x0, x1;
    double thickness = 0.01;
};

// Faces of a grid cloth whose (along + 1) x (across + 1) nodes start at node `first`.
void addGrid(SelfScene& s, std::uint32_t first, std::uint32_t along, std::uint32_t across,
             std::uint32_t objectIndex) {
    const auto node = [&](std::uint32_t i, std::uint32_t j) { return first + j * (along + 1) + i; };
    for (std::uint32_t j = 0; j < across; ++j)
        for (std::uint32_t i = 0; i < along; ++i) {
            s.faces.insert(s.faces.end(), {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j),
                                           node(i + 1, j + 1), node(i, j + 1)});
            s.object.insert(s.object.end(), {objectIndex, objectIndex});
        }
}

// The hairpin of feature_pairs_test.cpp (40 x 10 cells of 0.02 m, sheets `gap` apart), each node
// moved by up to `jitter` per axis over the substep.
SelfScene foldedCloth(double gap, float jitter, std::uint32_t seed) {
    const std::uint32_t along = 40, across = 10;
    const double cell = 0.02, pi = 3.14159265358979323846, r = gap / 2;
    const double flat = (along * cell - pi * r) / 2;
    SelfScene s;
    for (std::uint32_t j = 0; j <= across; ++j)
        for (std::uint32_t i = 0; i <= along; ++i) {
            const double t = i * cell;
            double px = t, py = 0.0;
            if (t > flat && t <= flat + pi * r) {
                px = flat + r * std::sin((t - flat) / r);
                py = r - r * std::cos((t - flat) / r);
            } else if (t > flat + pi * r) {
                px = flat - (t - flat - pi * r);
                py = gap;
            }
            s.x0.emplace_back(static_cast<float>(px), static_cast<float>(py), static_cast<float>(j * cell));
        }
    addGrid(s, 0, along, across, 0);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> move(-jitter, jitter);
    for (const glm::vec3& p : s.x0) s.x1.push_back(p + glm::vec3(move(rng), move(rng), move(rng)));
    return s;
}

// Two grid cloths of 12 x 12 cells of 0.02 m, every node displaced by up to one cell per axis
// (crumpled: faces a ring or two apart on the mesh come within the thickness) and moved by up to
// half a cell over the substep; the second cloth overlaps the first.
SelfScene crumpledSoup(std::uint32_t seed) {
    const std::uint32_t n = 12;
    const float cell = 0.02f;
    SelfScene s;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> crumple(-cell, cell), move(-cell / 2, cell / 2);
    for (std::uint32_t o = 0; o < 2; ++o) {
        addGrid(s, static_cast<std::uint32_t>(s.x0.size()), n, n, o);
        for (std::uint32_t j = 0; j <= n; ++j)
            for (std::uint32_t i = 0; i <= n; ++i)
                s.x0.emplace_back(static_cast<float>(i) * cell + crumple(rng) + 0.05f * static_cast<float>(o),
                                  crumple(rng) + 0.01f * static_cast<float>(o),
                                  static_cast<float>(j) * cell + crumple(rng));
    }
    for (const glm::vec3& p : s.x0) s.x1.push_back(p + glm::vec3(move(rng), move(rng), move(rng)));
    return s;
}

struct Expansions {
    std::vector<cpu::IndexPair> candidates;
    cpu::FeaturePairList plain, complete;
};
Expansions expand(const SelfScene& s, const cpu::PairRules& rules) {
    Expansions e;
    e.candidates = cpu::twinSweptCandidates(s.faces, s.object, s.x0, s.x1, s.thickness, rules);
    const std::vector<std::uint32_t> owned = model::ownedFeatures(s.faces);
    e.plain = cpu::featurePairs(s.faces, owned, e.candidates);
    e.complete = cpu::ccdFeaturePairs(s.faces, owned, model::featureOwners(s.faces), e.candidates);
    return e;
}

bool sharesNode(const std::vector<std::uint32_t>& faces, std::uint32_t f, std::uint32_t g) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (faces[3 * std::size_t{f} + i] == faces[3 * std::size_t{g} + j]) return true;
    return false;
}

// The owner of a node or an edge, independently of model::featureOwners: the lowest face that has it.
std::uint32_t lowestFaceWith(const std::vector<std::uint32_t>& faces, std::uint32_t a, std::uint32_t b) {
    for (std::uint32_t f = 0; 3 * std::size_t{f} < faces.size(); ++f) {
        const std::uint32_t* n = &faces[3 * std::size_t{f}];
        const bool hasA = n[0] == a || n[1] == a || n[2] == a, hasB = n[0] == b || n[1] == b || n[2] == b;
        if (hasA && hasB) return f;
    }
    return 0xffffffffu;
}

// The entries of `complete` that are not in `plain` (both sorted); fails unless plain ⊆ complete.
std::vector<cpu::IndexPair> extras(const std::vector<cpu::IndexPair>& complete,
                                   const std::vector<cpu::IndexPair>& plain, const std::string& what) {
    EXPECT_TRUE(std::includes(complete.begin(), complete.end(), plain.begin(), plain.end()))
        << what << ": discrete detection's entries must all be there";
    std::vector<cpu::IndexPair> out;
    std::set_difference(complete.begin(), complete.end(), plain.begin(), plain.end(),
                        std::back_inserter(out));
    return out;
}

// The response's contacts from both expansions, at the end positions, with a thickness that makes
// many pairs act: the orphans only add contacts (each feature pair is a contact at most once).
std::size_t contactsGained(const SelfScene& s, const Expansions& e, const std::string& what) {
    std::vector<glm::dvec3> x, v;
    for (std::size_t n = 0; n < s.x1.size(); ++n) {
        x.emplace_back(s.x1[n]);
        v.emplace_back((glm::dvec3(s.x1[n]) - glm::dvec3(s.x0[n])) / 1e-3);
    }
    const std::vector<std::uint32_t> owned = model::ownedFeatures(s.faces);
    const std::vector<std::uint8_t> closed(s.faces.size() / 3, 0u);
    CollisionSettings settings;
    settings.thickness = s.thickness;
    settings.stiffness = 1000.0;
    settings.friction = 0.3;
    const ContactParams params = contactParams(settings);
    const cpu::ContactInput in{&x, &v, &s.faces, &owned, &closed};
    const std::size_t plain = cpu::contactGeometries(params, in, e.plain).size();
    const std::size_t complete = cpu::contactGeometries(params, in, e.complete).size();
    EXPECT_GT(plain, 0u) << what;
    EXPECT_GE(complete, plain) << what;
    EXPECT_EQ(cpu::contactForces(params, in, e.complete).contacts, complete)
        << what << ": forces and geometry agree";
    return complete - plain;
}

// Returns the contacts the orphans add.
std::size_t expectCompleteAndOnce(const SelfScene& s, const std::string& what, bool expectLoss) {
    const cpu::PairRules rules{true, true};
    const Expansions e = expand(s, rules);
    EXPECT_FALSE(e.candidates.empty()) << what;
    const cpu::CcdCoverage lost =
        cpu::ccdCoverage(s.faces, s.object, s.x0, s.x1, s.thickness, rules, e.plain);
    const cpu::CcdCoverage got =
        cpu::ccdCoverage(s.faces, s.object, s.x0, s.x1, s.thickness, rules, e.complete);
    EXPECT_EQ(got.vertexFaceMissing, 0u) << what << ": of " << got.vertexFaceNeeded;
    EXPECT_EQ(got.edgeEdgeMissing, 0u) << what << ": of " << got.edgeEdgeNeeded;
    EXPECT_EQ(got.vertexFaceRepeated, 0u) << what << ": vertex-face pairs listed twice";
    EXPECT_EQ(got.edgeEdgeRepeated, 0u) << what << ": edge-edge pairs listed twice";
    if (expectLoss) { // the scene exercises the gap: ownership alone misses some
        EXPECT_GT(lost.vertexFaceMissing + lost.edgeEdgeMissing, 0u) << what;
    }
    // Discrete detection's entries are all there; every other entry is an orphan: a vertex not in
    // the face, or edges apart, whose owner faces share a node.
    const std::vector<cpu::IndexPair> vertexFace = extras(e.complete.vertexFace, e.plain.vertexFace, what);
    const std::vector<cpu::IndexPair> edgeEdge = extras(e.complete.edgeEdge, e.plain.edgeEdge, what);
    for (const cpu::IndexPair& p : vertexFace) {
        const std::uint32_t f = p[1];
        EXPECT_TRUE(s.faces[3 * f] != p[0] && s.faces[3 * f + 1] != p[0] && s.faces[3 * f + 2] != p[0]);
        EXPECT_TRUE(sharesNode(s.faces, lowestFaceWith(s.faces, p[0], p[0]), f)) << what << ": not an orphan";
    }
    for (const cpu::IndexPair& p : edgeEdge) {
        const auto a = model::faceEdge(s.faces, p[0] / 3, static_cast<int>(p[0] % 3));
        const auto b = model::faceEdge(s.faces, p[1] / 3, static_cast<int>(p[1] % 3));
        EXPECT_FALSE(a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]);
        EXPECT_TRUE(
            sharesNode(s.faces, lowestFaceWith(s.faces, a[0], a[1]), lowestFaceWith(s.faces, b[0], b[1])))
            << what << ": not an orphan";
    }
    const std::size_t gained = contactsGained(s, e, what);
    std::printf("%s: %zu candidates; vertex-face %zu + %zu orphans (missed without them %llu of %llu); "
                "edge-edge %zu + %zu orphans (missed without them %llu of %llu); contacts gained %zu\n",
                what.c_str(), e.candidates.size(), e.plain.vertexFace.size(), vertexFace.size(),
                static_cast<unsigned long long>(lost.vertexFaceMissing),
                static_cast<unsigned long long>(lost.vertexFaceNeeded), e.plain.edgeEdge.size(),
                edgeEdge.size(), static_cast<unsigned long long>(lost.edgeEdgeMissing),
                static_cast<unsigned long long>(lost.edgeEdgeNeeded), gained);
    return gained;
}

TEST(CcdFeaturePairs, FoldedClothsListEveryNearFeaturePairOnce) {
    std::size_t gained = 0;
    for (const double gap : {0.004, 0.006, 0.009})
        for (std::uint32_t seed = 1; seed <= 2; ++seed)
            gained += expectCompleteAndOnce(
                foldedCloth(gap, 0.002f, seed),
                "folded gap " + std::to_string(gap) + " seed " + std::to_string(seed), true);
    EXPECT_GT(gained, 0u) << "the orphans must be contacts somewhere, or the response's side is untested";
}

TEST(CcdFeaturePairs, CrumpledSoupsListEveryNearFeaturePairOnce) {
    for (std::uint32_t seed = 1; seed <= 4; ++seed)
        expectCompleteAndOnce(crumpledSoup(seed), "crumpled seed " + std::to_string(seed), true);
}

// Between objects only, no owner face shares a node with a face of another object: nothing to add.
TEST(CcdFeaturePairs, WithoutSelfCollisionsNothingIsAdded) {
    const SelfScene s = crumpledSoup(5);
    const Expansions e = expand(s, {true, false});
    ASSERT_FALSE(e.candidates.empty());
    EXPECT_EQ(e.complete.vertexFace, e.plain.vertexFace);
    EXPECT_EQ(e.complete.edgeEdge, e.plain.edgeEdge);
    const cpu::CcdCoverage c =
        cpu::ccdCoverage(s.faces, s.object, s.x0, s.x1, s.thickness, {true, false}, e.plain);
    EXPECT_EQ(c.vertexFaceMissing + c.edgeEdgeMissing, 0u);
}

} // namespace
} // namespace glcollide
