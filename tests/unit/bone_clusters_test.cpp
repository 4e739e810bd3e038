// Clusters by the bones of a skeleton (model/bone_clusters.hpp), checked against facts computed
// here without the cluster code: on an elbow (a tube bent by 90 degrees in its middle third) with a
// bone in each straight third and one along the bend, every face lies in the piece of the bone
// nearest it (a brute-force distance here), every piece is closed by its fans, winds exactly once
// around every point of its bone (the winding number as a sum of solid angles, Van Oosterom &
// Strackee) and, at rest, has every face — real and ghost — in front of its bone
// (n·(x − foot(x)) > 0 at each corner, double). One segment from end to end cannot do that: its
// middle leaves the bent tube.

#include "model/bone_clusters.hpp"
#include "model/radial_surfaces.hpp"
#include "scene/scene_detail.hpp"
#include "solid_angle_winding.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace glcollide {
namespace {

using test::windingNumber;

using model::Bone;
using model::Triangle;

/// The nearest point of segment ab to x, written here (not the model's squaredDistanceToBone).
glm::dvec3 foot(const glm::dvec3& x, const Bone& bone) {
    const glm::dvec3 d = bone[1] - bone[0];
    double u = glm::dot(x - bone[0], d) / glm::dot(d, d);
    u = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
    return bone[0] + u * d;
}

/// Faces of `faces` with every corner in front of the bone: n·(x − foot(x)) > 0.
std::size_t facesInFront(const std::vector<Triangle>& faces, const std::vector<glm::dvec3>& x,
                         const Bone& bone) {
    std::size_t count = 0;
    for (const Triangle& t : faces) {
        const glm::dvec3 n = glm::cross(x[t[1]] - x[t[0]], x[t[2]] - x[t[0]]);
        bool front = true;
        for (std::uint32_t k : t) front = front && glm::dot(n, x[k] - foot(x[k], bone)) > 0.0;
        count += front ? 1 : 0;
    }
    return count;
}

// An elbow like scenes/elbow.json's: radius 0.08 m, 0.5 m along the axis, bent by 90 degrees in its middle
// third (generateTube: the top third runs down the Y axis from y = 0.25, the arc turns towards +X about (r,
// 0.25 − L/3, 0) with r = (L/3) / (π/2), and the last third runs along +X).
constexpr double kLength = 0.5, kRadius = 0.08;
const double kThird = kLength / 3.0, kArc = kThird / (std::numbers::pi / 2.0);
const glm::dvec3 kBendStart(0.0, 0.25 - kThird, 0.0), kBendCentre = kBendStart + glm::dvec3(kArc, 0.0, 0.0);
const glm::dvec3 kBendEnd = kBendCentre + glm::dvec3(0.0, -kArc, 0.0);

/// Three bones with gaps of 3 cm at the joints and 3 cm inside the openings: the upper arm, the
/// chord of the middle of the bend, the forearm.
std::vector<Bone> elbowSkeleton() {
    const double gap = 0.03;
    const glm::dvec3 midArc = kBendCentre + kArc * glm::dvec3(-std::cos(std::numbers::pi / 4.0),
                                                              -std::sin(std::numbers::pi / 4.0), 0.0);
    return {Bone{glm::dvec3(0.0, 0.25 - gap, 0.0), kBendStart + glm::dvec3(0.0, gap, 0.0)},
            Bone{glm::mix(kBendStart, midArc, 0.3), glm::mix(kBendEnd, midArc, 0.3)},
            Bone{kBendEnd + glm::dvec3(gap, 0.0, 0.0), kBendEnd + glm::dvec3(kThird - gap, 0.0, 0.0)}};
}

TEST(BoneClusters, AnElbowIsWatchedByItsThreeBonesPieceByPiece) {
    const Body elbow = detail::generateTube(kRadius, kLength, 32, 31, 90.0);
    const std::vector<Bone> bones = elbowSkeleton();
    const model::BoneClusters pieces = model::boneClusters(elbow.faces, elbow.positions, bones);
    ASSERT_EQ(pieces.count, 3u); // each bone's faces are one band of the tube
    ASSERT_EQ(pieces.faceCluster.size(), elbow.faces.size());
    std::vector<std::vector<Triangle>> members(pieces.count);
    for (std::size_t f = 0; f < elbow.faces.size(); ++f) {
        const Triangle& t = elbow.faces[f];
        const glm::dvec3 c = (elbow.positions[t[0]] + elbow.positions[t[1]] + elbow.positions[t[2]]) / 3.0;
        std::size_t nearest = 0;
        for (std::size_t b = 1; b < bones.size(); ++b)
            if (glm::length(c - foot(c, bones[b])) < glm::length(c - foot(c, bones[nearest]))) nearest = b;
        EXPECT_EQ(pieces.clusterBone[pieces.faceCluster[f]], nearest) << "face " << f;
        members[pieces.faceCluster[f]].push_back(t);
    }
    for (std::uint32_t piece = 0; piece < pieces.count; ++piece) {
        SCOPED_TRACE(piece);
        EXPECT_EQ(pieces.clusterBone[piece], piece); // numbered by lowest face: top to bottom
        const model::BoneClosure closure = model::closeBoneCluster(members[piece], elbow.positions);
        ASSERT_TRUE(closure.closed);
        EXPECT_EQ(closure.ghosts.loops.size(), 2u); // a band: two loops, both filled
        std::vector<glm::dvec3> x = elbow.positions;
        for (const glm::dvec3& g : model::ghostNodePositions(closure.ghosts, elbow.positions)) x.push_back(g);
        std::vector<Triangle> surface = members[piece];
        surface.insert(surface.end(), closure.ghosts.faces.begin(), closure.ghosts.faces.end());
        const Bone& bone = bones[piece];
        // The winding number is an integer up to the atan2 sums' rounding (1e-9 for some thousand terms).
        for (double u : {0.0, 0.5, 1.0})
            EXPECT_NEAR(windingNumber(surface, x, glm::mix(bone[0], bone[1], u)), 1.0, 1e-9) << u;
        // Every real face is in front of its bone. The fans over the cuts are flat but the cuts
        // step from ring to ring (faces go to the nearest bone one by one), and a fan face over a
        // step's edge along the tube contains the tube's direction: seen edge-on from the bone, its
        // φ is about 0 and may fall below. Those few are not proven positive and keep the faces
        // near them from being freed (a cut is where pieces meet, whose pairs are tested anyway).
        EXPECT_EQ(facesInFront(members[piece], x, bone), members[piece].size());
        const std::size_t ghostsInFront = facesInFront(closure.ghosts.faces, x, bone);
        std::cout << "[elbow] piece " << piece << ": " << members[piece].size() << " faces, " << ghostsInFront
                  << " of " << closure.ghosts.faces.size() << " ghost faces in front\n";
        EXPECT_GE(ghostsInFront, closure.ghosts.faces.size() * 3 / 4);
        EXPECT_GT(closure.volume6, 0.0); // the tube's faces wind outward
    }
    // One segment from the top opening to the bottom one: its middle leaves the tube at the bend,
    // so the elbow's faces seen from it are not all in front (and the surface does not wind once
    // around its middle).
    const Bone chord{glm::dvec3(0.0, 0.22, 0.0), kBendEnd + glm::dvec3(kThird - 0.03, 0.0, 0.0)};
    const model::BoneClusters whole = model::boneClusters(elbow.faces, elbow.positions, {chord});
    EXPECT_EQ(whole.count, 1u);
    const model::BoneClosure closed = model::closeBoneCluster(elbow.faces, elbow.positions);
    ASSERT_TRUE(closed.closed);
    std::vector<glm::dvec3> x = elbow.positions;
    for (const glm::dvec3& g : model::ghostNodePositions(closed.ghosts, elbow.positions)) x.push_back(g);
    std::vector<Triangle> surface = elbow.faces;
    surface.insert(surface.end(), closed.ghosts.faces.begin(), closed.ghosts.faces.end());
    EXPECT_NEAR(windingNumber(surface, x, glm::mix(chord[0], chord[1], 0.5)), 0.0, 1e-9);
    EXPECT_LT(facesInFront(surface, x, chord), surface.size());
}

TEST(BoneClusters, ABoneSplitsItsFacesIntoConnectedPieces) {
    // Two squares of two triangles, apart; one bone between them: two pieces, by lowest face.
    const std::vector<glm::dvec3> x{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {3, 0, 0}, {4, 0, 0}, {4, 1, 0}, {3, 1, 0}};
    const std::vector<Triangle> faces{{4, 5, 6}, {0, 1, 2}, {4, 6, 7}, {0, 2, 3}};
    const model::BoneClusters pieces =
        model::boneClusters(faces, x, {Bone{glm::dvec3(2, 0, -1), glm::dvec3(2, 1, -1)}});
    EXPECT_EQ(pieces.count, 2u);
    EXPECT_EQ(pieces.faceCluster, (std::vector<std::uint32_t>{0, 1, 0, 1}));
    EXPECT_EQ(pieces.clusterBone, (std::vector<std::uint32_t>{0, 0}));
    // A tie (both squares' centroids as far from either bone) stays with the lower bone.
    const model::BoneClusters tied = model::boneClusters(
        faces, x,
        {Bone{glm::dvec3(2, 0, -1), glm::dvec3(2, 1, -1)}, Bone{glm::dvec3(2, 0, 1), glm::dvec3(2, 1, 1)}});
    EXPECT_EQ(tied.clusterBone, (std::vector<std::uint32_t>{0, 0}));
    // Each square alone is a disc: its loop is filled, and the result is closed (a flat double
    // layer, which no observer can be inside: the engine's observer check then frees nothing).
    EXPECT_TRUE(model::closeBoneCluster({faces[1], faces[3]}, x).closed);
}

TEST(BoneClusters, TheDistanceIsToTheSegmentsNearestPoint) {
    // Squared distances against the formula written here, at points beyond both ends and beside.
    const Bone bone{glm::dvec3(0, 0, 0), glm::dvec3(0, 2, 0)};
    for (const glm::dvec3& p :
         {glm::dvec3(1, 1, 0), glm::dvec3(0, -3, 0), glm::dvec3(0, 5, 4), glm::dvec3(0.5, 0.5, 0.5)})
        EXPECT_NEAR(model::squaredDistanceToBone(p, bone), glm::dot(p - foot(p, bone), p - foot(p, bone)),
                    1e-15);
}

TEST(BoneClusters, BadInputThrows) {
    const std::vector<glm::dvec3> x{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const Bone bone{glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 1)};
    EXPECT_THROW(model::boneClusters({{0, 1, 2}}, x, {}), std::invalid_argument);
    EXPECT_THROW(model::boneClusters({{0, 1, 2}}, x, {Bone{glm::dvec3(1), glm::dvec3(1)}}),
                 std::invalid_argument);
    EXPECT_THROW(model::boneClusters({{0, 1, 3}}, x, {bone}), std::out_of_range);
    // A piece whose loop cannot be filled (a pinch: two triangles touching at one node) stays open.
    const std::vector<glm::dvec3> bowtie{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
    EXPECT_FALSE(model::closeBoneCluster({{0, 1, 2}, {0, 3, 4}}, bowtie).closed);
}

} // namespace
} // namespace glcollide
