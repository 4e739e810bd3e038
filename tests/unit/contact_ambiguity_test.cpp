// cpu::ambiguousContactEnergy: the contacts that a float evaluation of contact_pair.glsl may count
// differently from the double twin, because they sit at a boundary of the closest-feature regions
// that decides which feature pair carries a contact (decision 0024, "Known failures"). Checked
// against hand-made configurations whose answer follows from the geometry: edge pairs clearly
// inside or outside their segments, just past an end, exactly and nearly parallel (the case that
// made a GPU count one contact more: in float, a ≈ 0 denominator makes the closest point any
// number), and vertices near a face's edge that the face owns or does not own.

#include "cpu/contact_twin.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace glcollide {
namespace {

constexpr double kThickness = 0.01, kStiffness = 500.0;
constexpr std::uint32_t kOwnAll =
    GLC_OWN_VERTEX0 | GLC_OWN_VERTEX1 | GLC_OWN_VERTEX2 | GLC_OWN_EDGE01 | GLC_OWN_EDGE12 | GLC_OWN_EDGE20;

ContactParams params() {
    ContactParams p;
    p.thickness = kThickness;
    p.stiffness = kStiffness;
    return p;
}

double penalty(double distance) {
    return 0.5 * kStiffness * (kThickness - distance) * (kThickness - distance);
}

/// Two triangles: face 0 = nodes 0 1 2, face 1 = nodes 3 4 5; edge 0 of each face is its nodes
/// 0 → 1, so the edge-edge pair (3·0 + 0, 3·1 + 0) is the segments x[0]x[1] and x[3]x[4].
struct TwoFaces {
    std::vector<glm::dvec3> x, v;
    std::vector<std::uint32_t> faces{0, 1, 2, 3, 4, 5}, owned{kOwnAll, kOwnAll};
    std::vector<std::uint8_t> closed{0, 0};
    std::vector<double> inverseMasses = std::vector<double>(6, 1.0);

    TwoFaces(glm::dvec3 p0, glm::dvec3 p1, glm::dvec3 q0, glm::dvec3 q1)
        : x{p0, p1, p0 + glm::dvec3(0, -0.5, 0.1), q0, q1, q0 + glm::dvec3(0, 0.5, 0.1)},
          v(6, glm::dvec3(0.0)) {}
    cpu::ContactInput input() const { return {&x, &v, &faces, &owned, &closed, &inverseMasses}; }
    double edgeEdgeAmbiguity() const {
        return cpu::ambiguousContactEnergy(params(), input(), cpu::FeaturePairList{{}, {{0, 3}}});
    }
    bool edgeEdgeCounted() const {
        return !cpu::contactGeometries(params(), input(), cpu::FeaturePairList{{}, {{0, 3}}}).empty();
    }
};

TEST(ContactAmbiguity, EdgesCrossingWellInsideOrMissingWellOutsideAreDecided) {
    const TwoFaces inside({0, 0, 0}, {1, 0, 0}, {0.5, 0.004, -0.5}, {0.5, 0.004, 0.5});
    EXPECT_TRUE(inside.edgeEdgeCounted());
    EXPECT_EQ(inside.edgeEdgeAmbiguity(), 0.0);
    const TwoFaces outside({0, 0, 0}, {1, 0, 0}, {1.01, 0.004, -0.5}, {1.01, 0.004, 0.5}); // 1 % past the end
    EXPECT_FALSE(outside.edgeEdgeCounted());
    EXPECT_EQ(outside.edgeEdgeAmbiguity(), 0.0);
    const TwoFaces far({0, 0, 0}, {1, 0, 0}, {0.5, 0.02, -0.5}, {0.5, 0.02, 0.5}); // beyond the thickness
    EXPECT_EQ(far.edgeEdgeAmbiguity(), 0.0);
}

TEST(ContactAmbiguity, EdgesMeetingAtAnEndAreAmbiguous) {
    for (const double past : {-1e-9, 0.0, 1e-9}) { // the closest point just inside, at, just past the end
        const TwoFaces pair({0, 0, 0}, {1, 0, 0}, {1.0 + past, 0.004, -0.5}, {1.0 + past, 0.004, 0.5});
        EXPECT_NEAR(pair.edgeEdgeAmbiguity(), penalty(0.004), 1e-9 * penalty(0.004)) << past;
    }
}

// Seed 13 of IntersectionFreeDrops: a cloth edge parallel to a box edge 6 mm above it, whose
// closest points in double are the cloth edge's end (no edge-edge contact; the vertex-face pair
// has it). In float a·e − b² is rounding noise, and the GPU counted the pair as well.
TEST(ContactAmbiguity, ParallelEdgesWithinTheThicknessAreAmbiguous) {
    const TwoFaces parallel({0, 0, 0}, {1, 0, 0}, {0.3, 0.006, 0}, {1.3, 0.006, 0});
    EXPECT_NEAR(parallel.edgeEdgeAmbiguity(), penalty(0.006), 1e-9 * penalty(0.006));
    const TwoFaces nearlyParallel({0, 0, 0}, {1, 0, 0}, {0.3, 0.006, 0}, {1.3, 0.006, 1e-7});
    EXPECT_NEAR(nearlyParallel.edgeEdgeAmbiguity(), penalty(0.006), 1e-6 * penalty(0.006));
    // Clearly skew edges in parallel planes are decided (the same 6 mm, 45° apart).
    const TwoFaces skew({0, 0, 0}, {1, 0, 0}, {0.3, 0.006, -0.2}, {0.7, 0.006, 0.2});
    EXPECT_EQ(skew.edgeEdgeAmbiguity(), 0.0);
}

/// Face 0 = nodes 0 1 2 in the plane y = 0 (normal +y), its edge 2 → 0 along z = 0; node 3 at
/// (0.5, 0.004, z).
struct VertexNearAnEdge {
    std::vector<glm::dvec3> x, v;
    std::vector<std::uint32_t> faces{0, 1, 2}, owned;
    std::vector<std::uint8_t> closed{0};
    std::vector<double> inverseMasses = std::vector<double>(4, 1.0);

    VertexNearAnEdge(double z, std::uint32_t ownership)
        : x{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0.5, 0.004, z}}, v(4, glm::dvec3(0.0)), owned{ownership} {}
    cpu::ContactInput input() const { return {&x, &v, &faces, &owned, &closed, &inverseMasses}; }
    double ambiguity() const {
        return cpu::ambiguousContactEnergy(params(), input(), cpu::FeaturePairList{{{3, 0}}, {}});
    }
};

TEST(ContactAmbiguity, AVertexNearAnEdgeTheFaceDoesNotOwnIsAmbiguous) {
    const std::uint32_t notEdge20 = kOwnAll & ~GLC_OWN_EDGE20;
    // Over the interior far from every edge: decided, whoever owns the edges.
    EXPECT_EQ(VertexNearAnEdge(0.25, notEdge20).ambiguity(), 0.0);
    // At the unowned edge, either side: the interior counts it, the edge region does not.
    for (const double z : {1e-9, -1e-9})
        EXPECT_NEAR(VertexNearAnEdge(z, notEdge20).ambiguity(), penalty(0.004), 1e-6 * penalty(0.004)) << z;
    // At an owned edge both regions count it: nothing to decide.
    for (const double z : {1e-9, -1e-9}) EXPECT_EQ(VertexNearAnEdge(z, kOwnAll).ambiguity(), 0.0) << z;
    // Past the edge by more than the slack of the face's size: decided.
    EXPECT_EQ(VertexNearAnEdge(-1e-3, notEdge20).ambiguity(), 0.0);
}

} // namespace
} // namespace glcollide
