#include "cpu/oracle/ground_truth.hpp"

#include "cpu/oracle/exact_tri_tri.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <thread>
#include <utility>

namespace glcollide::cpu {
namespace {

// ---- exactIntersectingPairs ----

/// A face's float box with the sweep axis first (a = sweep axis, b and c the other two).
struct SweepBox {
    float loA, hiA, loB, hiB, loC, hiC;
    std::uint32_t face;
};

glm::dvec3 corner(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& positions,
                  std::uint32_t face, std::size_t c) {
    return glm::dvec3(positions[faceIndices[3 * static_cast<std::size_t>(face) + c]]);
}

Triangle faceTriangle(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& positions,
                      std::uint32_t face) {
    return {corner(faceIndices, positions, face, 0), corner(faceIndices, positions, face, 1),
            corner(faceIndices, positions, face, 2)};
}

/// The axis along which the face boxes' centres spread most (largest variance): the sweep along
/// it meets the fewest boxes whose intervals overlap but which are apart on the other axes.
int sweepAxis(const std::vector<FloatBox>& boxes) {
    glm::dvec3 sum(0.0), sumSq(0.0);
    for (const FloatBox& b : boxes) {
        const glm::dvec3 centre = 0.5 * (glm::dvec3(b.lo) + glm::dvec3(b.hi));
        sum += centre;
        sumSq += centre * centre;
    }
    const double n = static_cast<double>(std::max<std::size_t>(boxes.size(), 1));
    const glm::dvec3 variance = sumSq / n - (sum / n) * (sum / n);
    if (variance.x >= variance.y && variance.x >= variance.z) return 0;
    return variance.y >= variance.z ? 1 : 2;
}

/// Boxes with lo/hi exactly the min/max of the float corners (no thickness), sorted by their low
/// end on the sweep axis (ties by face, so the order is deterministic).
std::vector<SweepBox> sortedSweepBoxes(const std::vector<std::uint32_t>& faceIndices,
                                       const std::vector<glm::vec3>& positions) {
    const auto faces = static_cast<std::uint32_t>(faceIndices.size() / 3);
    std::vector<FloatBox> boxes(faces);
    for (std::uint32_t f = 0; f < faces; ++f) boxes[f] = faceBox(faceIndices, positions, f, 0.0f);
    const int a = sweepAxis(boxes);
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    std::vector<SweepBox> sweep(faces);
    for (std::uint32_t f = 0; f < faces; ++f) {
        const FloatBox& box = boxes[f];
        sweep[f] = {box.lo[a], box.hi[a], box.lo[b], box.hi[b], box.lo[c], box.hi[c], f};
    }
    std::sort(sweep.begin(), sweep.end(), [](const SweepBox& x, const SweepBox& y) {
        return x.loA != y.loA ? x.loA < y.loA : x.face < y.face;
    });
    return sweep;
}

/// The sign of det[a-d, b-d, c-d] (orient3d) when a plain double evaluation certifies it, else 0.
/// The bound is Shewchuk's static filter for orient3d, (7 + 56 eps) eps times the permanent
/// ("Adaptive Precision Floating-Point Arithmetic", 1997), which covers the rounding of the
/// differences and of every product and sum; we double it so that a compiler contracting a product
/// and a sum into one fused multiply-add (one rounding instead of two) stays covered. No underflow
/// or overflow can occur: the inputs are floats widened to double, so every product of three
/// differences lies far inside double's normal range.
int certifiedOrientation(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
    constexpr double kEps = std::numeric_limits<double>::epsilon() / 2.0; // 2^-53, unit roundoff
    constexpr double kBound = 2.0 * (7.0 + 56.0 * kEps) * kEps;
    const glm::dvec3 ad = a - d, bd = b - d, cd = c - d;
    const double bdxcdy = bd.x * cd.y, cdxbdy = cd.x * bd.y;
    const double cdxady = cd.x * ad.y, adxcdy = ad.x * cd.y;
    const double adxbdy = ad.x * bd.y, bdxady = bd.x * ad.y;
    const double det = ad.z * (bdxcdy - cdxbdy) + bd.z * (cdxady - adxcdy) + cd.z * (adxbdy - bdxady);
    const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(ad.z) +
                             (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bd.z) +
                             (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cd.z);
    const double bound = kBound * permanent;
    if (det > bound) return 1;
    if (-det > bound) return -1;
    return 0;
}

/// True only when all of u's corners are certainly strictly on one side of t's plane, which proves
/// the closed triangles disjoint (a certified nonzero sign also proves t is not degenerate).
bool certainlySeparatedByPlaneOf(const Triangle& t, const Triangle& u) {
    const int s0 = certifiedOrientation(t[0], t[1], t[2], u[0]);
    if (s0 == 0) return false;
    return certifiedOrientation(t[0], t[1], t[2], u[1]) == s0 &&
           certifiedOrientation(t[0], t[1], t[2], u[2]) == s0;
}

/// Conservative: never rejects an intersecting pair, so the exact oracle decides everything else.
/// Neighbouring faces of a smooth or convex surface, the bulk of the overlapping boxes, lie on one
/// side of each other's plane and never reach GMP.
bool certainlyDisjoint(const Triangle& t, const Triangle& u) {
    return certainlySeparatedByPlaneOf(t, u) || certainlySeparatedByPlaneOf(u, t);
}

/// All intersecting valid pairs whose first box is sweep[begin, end), against every later box.
std::vector<FacePair> sweepRange(const std::vector<SweepBox>& sweep, std::size_t begin, std::size_t end,
                                 const std::vector<std::uint32_t>& faceIndices,
                                 const std::vector<std::uint32_t>& faceObject,
                                 const std::vector<glm::vec3>& positions, const PairRules& rules) {
    std::vector<FacePair> out;
    for (std::size_t i = begin; i < end; ++i) {
        const SweepBox& s = sweep[i];
        // Sorted by loA, so every later box starts at or after s: the closed intervals on the sweep
        // axis overlap exactly while the later box starts at or before s ends.
        for (std::size_t j = i + 1; j < sweep.size() && sweep[j].loA <= s.hiA; ++j) {
            const SweepBox& t = sweep[j];
            if (t.loB > s.hiB || s.loB > t.hiB || t.loC > s.hiC || s.loC > t.hiC) continue;
            if (!validFacePair(faceIndices, faceObject, s.face, t.face, rules)) continue;
            const Triangle ts = faceTriangle(faceIndices, positions, s.face);
            const Triangle tt = faceTriangle(faceIndices, positions, t.face);
            if (certainlyDisjoint(ts, tt) || !exactTrianglesIntersect(ts, tt)) continue;
            out.push_back({std::min(s.face, t.face), std::max(s.face, t.face)});
        }
    }
    return out;
}

/// Runs job(block) for every block in [0, blocks) on all hardware threads, blocks handed out in
/// order as threads become free (work per block varies a lot between dense and sparse regions).
template <class Job> void parallelBlocks(std::size_t blocks, const Job& job) {
    const std::size_t threads =
        std::min<std::size_t>(blocks, std::max(1u, std::thread::hardware_concurrency()));
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
        for (std::size_t b = next++; b < blocks; b = next++) job(b);
    };
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
}

// ---- deepestPenetration ----

/// Faces and node positions in double: the read-only input of every query below.
struct Mesh {
    const std::vector<std::uint32_t>& faceIndices;
    const std::vector<glm::dvec3>& positions;
    const glm::dvec3& corner(std::uint32_t face, std::size_t c) const {
        return positions[faceIndices[3 * static_cast<std::size_t>(face) + c]];
    }
};

using Edge = std::array<std::uint32_t, 2>; ///< directed, node indices

/// A node of a bounding volume hierarchy over one object's faces. `boundary` is the boundary of
/// the patch its faces form, as directed edges (an edge used twice in opposite directions cancels;
/// the root of a closed surface has none).
struct PatchNode {
    glm::dvec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
    std::uint32_t begin = 0, end = 0;  ///< range in PatchTree::faces
    std::uint32_t left = 0, right = 0; ///< children; 0 for a leaf (the root is never a child)
    std::vector<Edge> boundary;
};

/// One object's faces in a hierarchy of spatial patches, for the winding number and distance
/// queries: both then cost about the square root of the face count instead of the face count.
struct PatchTree {
    std::vector<std::uint32_t> faces;
    std::vector<PatchNode> nodes; ///< nodes[0] is the root
};

/// The net directed boundary of the faces: per undirected edge, +1 for each use a->b with a < b and
/// -1 for each b->a; what is left over is the boundary, as a chain (so it is right even for
/// inconsistently oriented or non-manifold patches).
std::vector<Edge> patchBoundary(const Mesh& mesh, const std::uint32_t* first, const std::uint32_t* last) {
    std::vector<std::pair<Edge, int>> uses;
    for (const std::uint32_t* f = first; f != last; ++f)
        for (std::size_t c = 0; c < 3; ++c) {
            const std::uint32_t a = mesh.faceIndices[3 * static_cast<std::size_t>(*f) + c];
            const std::uint32_t b = mesh.faceIndices[3 * static_cast<std::size_t>(*f) + (c + 1) % 3];
            uses.push_back(a < b ? std::pair{Edge{a, b}, 1} : std::pair{Edge{b, a}, -1});
        }
    std::sort(uses.begin(), uses.end());
    std::vector<Edge> boundary;
    for (std::size_t i = 0; i < uses.size();) {
        int net = 0;
        std::size_t j = i;
        for (; j < uses.size() && uses[j].first == uses[i].first; ++j) net += uses[j].second;
        const Edge e = uses[i].first;
        for (int k = 0; k < std::abs(net); ++k) boundary.push_back(net > 0 ? e : Edge{e[1], e[0]});
        i = j;
    }
    return boundary;
}

/// Builds the subtree over faces[begin, end) by median splits of the face centroids along the
/// box's longest axis; returns its index.
std::uint32_t buildPatch(PatchTree& tree, const Mesh& mesh, std::uint32_t begin, std::uint32_t end) {
    constexpr std::uint32_t kLeafFaces = 8;
    const auto index = static_cast<std::uint32_t>(tree.nodes.size());
    tree.nodes.emplace_back();
    PatchNode node;
    node.begin = begin;
    node.end = end;
    for (std::uint32_t i = begin; i < end; ++i)
        for (std::size_t c = 0; c < 3; ++c) {
            node.lo = glm::min(node.lo, mesh.corner(tree.faces[i], c));
            node.hi = glm::max(node.hi, mesh.corner(tree.faces[i], c));
        }
    node.boundary = patchBoundary(mesh, tree.faces.data() + begin, tree.faces.data() + end);
    if (end - begin > kLeafFaces) {
        const glm::dvec3 size = node.hi - node.lo;
        const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
        const auto centroid = [&](std::uint32_t f) {
            return mesh.corner(f, 0)[axis] + mesh.corner(f, 1)[axis] + mesh.corner(f, 2)[axis];
        };
        const std::uint32_t middle = begin + (end - begin) / 2;
        std::nth_element(tree.faces.begin() + begin, tree.faces.begin() + middle, tree.faces.begin() + end,
                         [&](std::uint32_t f, std::uint32_t g) { return centroid(f) < centroid(g); });
        node.left = buildPatch(tree, mesh, begin, middle);
        node.right = buildPatch(tree, mesh, middle, end);
    }
    tree.nodes[index] = std::move(node);
    return index;
}

PatchTree buildPatchTree(const Mesh& mesh, std::vector<std::uint32_t> faces) {
    PatchTree tree;
    tree.faces = std::move(faces);
    if (!tree.faces.empty()) buildPatch(tree, mesh, 0, static_cast<std::uint32_t>(tree.faces.size()));
    return tree;
}

/// Signed solid angle of triangle abc seen from p (Van Oosterom and Strackee), in steradians.
double solidAngle(const glm::dvec3& p, const glm::dvec3& a0, const glm::dvec3& b0, const glm::dvec3& c0) {
    const glm::dvec3 a = a0 - p, b = b0 - p, c = c0 - p;
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double numerator = glm::dot(a, glm::cross(b, c));
    const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
    return 2.0 * std::atan2(numerator, denominator);
}

/// p outside the patch's box grown by a thousandth of its diagonal: far enough from everything in
/// the box for the cap below to be evaluated as accurately as the faces themselves.
bool wellOutside(const glm::dvec3& p, const PatchNode& node) {
    const glm::dvec3 margin(1e-3 * glm::length(node.hi - node.lo));
    return glm::any(glm::lessThan(p, node.lo - margin)) || glm::any(glm::greaterThan(p, node.hi + margin));
}

/// Sum of the solid angles of the subtree's faces seen from p. For p outside a patch's box the
/// patch is replaced by the fan from one boundary vertex over its boundary edges (Jacobson et al.,
/// "Robust inside-outside segmentation using generalized winding numbers", 2013, sec. 3.3): patch
/// minus fan is a closed surface inside the convex box, whose winding number at a point outside
/// the box is 0, so both have the same solid angle. A patch of k faces has about sqrt(k) boundary
/// edges, and the closed surface's root has none.
double patchSolidAngle(const glm::dvec3& p, const PatchTree& tree, std::uint32_t index, const Mesh& mesh) {
    const PatchNode& node = tree.nodes[index];
    const std::size_t faceCount = node.end - node.begin;
    if (wellOutside(p, node) && node.boundary.size() < faceCount) {
        double sum = 0.0;
        if (node.boundary.empty()) return sum;
        const glm::dvec3& apex = mesh.positions[node.boundary[0][0]];
        for (const Edge& e : node.boundary)
            sum += solidAngle(p, apex, mesh.positions[e[0]], mesh.positions[e[1]]);
        return sum;
    }
    if (node.left == 0) {
        double sum = 0.0;
        for (std::uint32_t i = node.begin; i < node.end; ++i) {
            const std::uint32_t f = tree.faces[i];
            sum += solidAngle(p, mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2));
        }
        return sum;
    }
    return patchSolidAngle(p, tree, node.left, mesh) + patchSolidAngle(p, tree, node.right, mesh);
}

/// Generalised winding number of the object's faces at p: the integer number of times a closed
/// surface wraps p, meaningful even when the body intersects itself; rounding moves it by far
/// less than the 0.5 threshold away from the surface.
double windingNumber(const glm::dvec3& p, const PatchTree& tree, const Mesh& mesh) {
    if (tree.faces.empty()) return 0.0;
    return patchSolidAngle(p, tree, 0, mesh) / (4.0 * std::numbers::pi);
}

/// Squared distance from p to the closed segment ab (a point when a == b).
double squaredDistanceToSegment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    const glm::dvec3 d = p - (a + t * ab);
    return glm::dot(d, d);
}

/// Squared distance from p to the closed triangle abc, by the Voronoi regions of its corners, edges
/// and face (Ericson, Real-Time Collision Detection, 5.1.5). A zero-area triangle has no face
/// region: its distance is that to its edges.
double squaredDistanceToTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                 const glm::dvec3& c) {
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return glm::dot(ap, ap);
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return glm::dot(bp, bp);
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return glm::dot(cp, cp);
    const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return squaredDistanceToSegment(p, a, b);
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return squaredDistanceToSegment(p, a, c);
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) return squaredDistanceToSegment(p, b, c);
    if (!(va + vb + vc > 0.0))
        return std::min({squaredDistanceToSegment(p, a, b), squaredDistanceToSegment(p, b, c),
                         squaredDistanceToSegment(p, c, a)});
    // Inside the face region: the distance to the plane, measured along the normal rather than
    // through the barycentric closest point, so a point on an axis-aligned face gets exactly 0.
    const glm::dvec3 n = glm::cross(ab, ac);
    const double h = glm::dot(ap, n);
    return h * h / glm::dot(n, n);
}

double squaredDistanceToBox(const glm::dvec3& p, const PatchNode& node) {
    const glm::dvec3 d = glm::max(glm::max(node.lo - p, p - node.hi), glm::dvec3(0.0));
    return glm::dot(d, d);
}

/// Branch and bound: lowers best2 to the squared distance from p to the subtree's faces, skipping
/// patches whose box is no closer than best2, and stopping once best2 <= stop2.
void nearestInPatch(const glm::dvec3& p, const PatchTree& tree, std::uint32_t index, const Mesh& mesh,
                    double stop2, double& best2) {
    const PatchNode& node = tree.nodes[index];
    if (best2 <= stop2 || squaredDistanceToBox(p, node) >= best2) return;
    if (node.left == 0) {
        for (std::uint32_t i = node.begin; i < node.end; ++i) {
            const std::uint32_t f = tree.faces[i];
            best2 = std::min(
                best2, squaredDistanceToTriangle(p, mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2)));
        }
        return;
    }
    std::uint32_t near = node.left, far = node.right;
    if (squaredDistanceToBox(p, tree.nodes[far]) < squaredDistanceToBox(p, tree.nodes[near]))
        std::swap(near, far);
    nearestInPatch(p, tree, near, mesh, stop2, best2);
    nearestInPatch(p, tree, far, mesh, stop2, best2);
}

/// Distance from p to the object's surface, or any value <= `beat` once it is clear the distance
/// cannot exceed `beat` (the caller only keeps distances above it).
double distanceToSurface(const glm::dvec3& p, const PatchTree& tree, const Mesh& mesh, double beat) {
    double best2 = std::numeric_limits<double>::infinity();
    if (!tree.faces.empty()) nearestInPatch(p, tree, 0, mesh, beat * beat, best2);
    return std::sqrt(best2);
}

} // namespace

std::vector<FacePair> exactIntersectingPairs(const std::vector<std::uint32_t>& faceIndices,
                                             const std::vector<std::uint32_t>& faceObject,
                                             const std::vector<glm::vec3>& positions,
                                             const PairRules& rules) {
    if (!rules.betweenObjects && !rules.selfCollisions) return {};
    const std::vector<SweepBox> sweep = sortedSweepBoxes(faceIndices, positions);
    constexpr std::size_t kBlock = 2048;
    const std::size_t blocks = (sweep.size() + kBlock - 1) / kBlock;
    std::vector<std::vector<FacePair>> perBlock(blocks);
    parallelBlocks(blocks, [&](std::size_t b) {
        perBlock[b] = sweepRange(sweep, b * kBlock, std::min(sweep.size(), (b + 1) * kBlock), faceIndices,
                                 faceObject, positions, rules);
    });
    std::vector<FacePair> pairs;
    for (const std::vector<FacePair>& block : perBlock) pairs.insert(pairs.end(), block.begin(), block.end());
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

Penetration deepestPenetration(const std::vector<std::uint32_t>& faceIndices,
                               const std::vector<std::uint32_t>& faceObject,
                               const std::vector<std::uint32_t>& nodeObject,
                               const std::vector<glm::dvec3>& positions,
                               const std::vector<bool>& objectClosed) {
    const Mesh mesh{faceIndices, positions};
    std::vector<std::vector<std::uint32_t>> facesOf(objectClosed.size());
    for (std::uint32_t f = 0; f < faceObject.size(); ++f)
        if (faceObject[f] < objectClosed.size()) facesOf[faceObject[f]].push_back(f);
    Penetration deepest;
    for (std::uint32_t b = 0; b < objectClosed.size(); ++b) {
        if (!objectClosed[b] || facesOf[b].empty()) continue;
        const PatchTree tree = buildPatchTree(mesh, std::move(facesOf[b]));
        const PatchNode& root = tree.nodes[0];
        for (std::uint32_t n = 0; n < nodeObject.size(); ++n) {
            const glm::dvec3& p = positions[n];
            // Outside the closed box of a closed surface the winding number is 0: skip the query.
            if (nodeObject[n] == b || squaredDistanceToBox(p, root) > 0.0) continue;
            if (std::abs(windingNumber(p, tree, mesh)) <= 0.5) continue;
            const double depth = distanceToSurface(p, tree, mesh, deepest.depth);
            if (depth > deepest.depth) deepest = {depth, n, b};
        }
    }
    return deepest;
}

} // namespace glcollide::cpu
