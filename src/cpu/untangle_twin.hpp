#pragma once
// CPU twin of Untangle (shaders/passes/untangle_pairs.comp and untangle_apply.comp; decision 0024,
// "Deep intersections"), in double: every face pair that intersects at x0 pushes its two
// triangles so that their intersection segment shrinks, and each node moves by a bounded step
// along the sum of its pushes. The method is intersection contour minimisation (Volino and
// Magnenat-Thalmann 2006) with the orientation of closed objects as the push direction where it
// is known (Ye and Zhao's "repulsive normals"):
// - the segment of two intersecting triangles ends at two piercings: an edge of one triangle
//   through the other (intersectionPiercings);
// - at a piercing of edge (p0, p1) through face F (unit normal n), the edge is pushed relative to
//   the face along R: n when F belongs to a closed object other than the edge's (its normals point
//   outwards: the edge's end behind F is inside the object, and the push brings it out; within one
//   closed surface neither side of a self-intersection is known to be the wrong one), otherwise the sign of n
//   that moves the piercing point towards the segment's other end (for a push δ·n the point moves in F's
//   plane by −δ·e∥/(n·e), e = p1 − p0: towards Q − P when δ·(u·e)/(n·e) < 0), which shortens the intersection
//   contour (zero when the edge is perpendicular to the contour: a straight contour of two crossing sheets
//   does not shrink, ICM's known limit);
// - the unit relative push is split over the five nodes like a constraint projection: weights
//   a = (1 − s, s, −b0, −b1, −b2) (s along the edge, b the piercing's barycentrics in F), node i
//   moves by a_i·w_i/W·R with W = Σ a_j²·w_j (w the inverse masses, pinned nodes 0), each part
//   clamped to length 1;
// - a node moves by step·D/max(1, |D|), D the sum of its parts: at most `step` per substep.

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace glcollide::cpu {

/// Where an edge of one triangle passes through the other.
struct Piercing {
    bool edgeOfFirst = true;             ///< the edge is the first triangle's
    std::array<int, 2> edge{};           ///< the edge's corners in its triangle (0..2)
    double s = 0.0;                      ///< the point along the edge, p0 + s·(p1 − p0)
    std::array<double, 3> barycentric{}; ///< the point in the other triangle
    glm::dvec3 point{0.0};
};

/// The piercings of two triangles in a fixed order (the first triangle's edges 01, 12, 20 through
/// the second, then the second's through the first), at most two: an edge crosses the other's
/// plane strictly (its ends on opposite sides) at a point inside the closed triangle. Generic
/// intersecting triangles have exactly two (the segment's ends); touching or coplanar ones fewer.
std::vector<Piercing> intersectionPiercings(const std::array<glm::dvec3, 3>& a,
                                            const std::array<glm::dvec3, 3>& b);

struct UntangleInput {
    std::vector<glm::dvec3> positions;               ///< x0 per node
    std::vector<double> inverseMass;                 ///< per node (0: pinned)
    std::vector<std::array<std::uint32_t, 3>> faces; ///< node indices
    std::vector<std::uint32_t> faceObject;           ///< per face: its object
    std::vector<bool> objectClosed;                  ///< per object: closed (outward normals)
    std::vector<std::array<std::uint32_t, 2>> pairs; ///< face pairs that intersect at x0
    double step = 0.0;                               ///< m: the most a node moves
};

struct UntangleResult {
    std::vector<glm::dvec3> displacement; ///< per node
    std::vector<glm::dvec3> pushSum;      ///< per node: D, the sum of its parts (unitless)
    std::uint32_t movedNodes = 0;         ///< nodes with a non-zero displacement
    std::uint32_t unresolvedPairs = 0;    ///< pairs with fewer than two piercings (no push)
};

UntangleResult untangleStep(const UntangleInput& in);

} // namespace glcollide::cpu
