#pragma once
// CPU twins of the FeaturePairs expansion (shaders/passes/feature_pairs.comp: Representative
// Triangles, docs/design/decisions/0018-representative-triangles.md) and of the ContactResponse
// pass (shaders/passes/contact_vertex_face.comp, contact_edge_edge.comp) in double precision: the
// same contact rules, case by case, on the same inputs. Forces are not quantised (the GPU's
// fixed-point sums differ from these by at most 0.5/forceScale per contribution).

#include "core/contact_params.hpp"
#include "core/gpu_layout.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace glcollide::cpu {

struct ContactInput {
    const std::vector<glm::dvec3>* positions = nullptr;      ///< m, per node
    const std::vector<glm::dvec3>* velocities = nullptr;     ///< m/s, per node
    const std::vector<std::uint32_t>* faceIndices = nullptr; ///< 3 per face
    const std::vector<std::uint32_t>* faceOwned = nullptr;   ///< GLC_OWN_* bits per face
    const std::vector<std::uint8_t>* faceClosed = nullptr;   ///< 1 when the face's object is closed
    /// 1/kg per node, 0 for pinned nodes (the GPU's positions .w); nullptr: 1 for every node.
    const std::vector<double>* inverseMasses = nullptr;
    /// N per node: the forces at the start of the substep (ContactParams::predictedForces); nullptr: none.
    const std::vector<glm::dvec3>* predictedForces = nullptr;
    /// The object of each node and of each face: only a vertex of another object is kept outside a
    /// closed object's face; the object's own vertex keeps the side it had (contact_pair.glsl's
    /// keepsOutside). Required when faceClosed marks a face (std::invalid_argument otherwise).
    const std::vector<std::uint32_t>* nodeObject = nullptr;
    const std::vector<std::uint32_t>* faceObject = nullptr;
};

struct ContactResult {
    std::vector<glm::dvec3> forces;           ///< N, per node
    std::uint32_t contacts = 0;               ///< vertex-face and edge-edge contacts that produced a force
    std::vector<std::uint32_t> contributions; ///< per node: contacts that added to its force
    std::vector<std::uint32_t> approaching;   ///< per node: active contacts, v_n < v_t, or with the
                                              ///< penalty and friction the pushing ones (the GPU's .w counts)
};

using IndexPair = std::array<std::uint32_t, 2>;

/// The feature pairs of a list of face pairs, each sorted.
struct FeaturePairList {
    std::vector<IndexPair> vertexFace; ///< (node, face): a vertex owned by one face against the other
    std::vector<IndexPair> edgeEdge; ///< (3*fa+e, 3*fb+g): owned edges of fa and fb; edge e: corner e to e+1
};

/// The Representative-Triangle expansion of `candidates` (face pairs (fa, fb)): every vertex that
/// fa owns (GLC_OWN_VERTEX* of faceOwned) against fb and every vertex fb owns against fa; every
/// edge fa owns against every edge fb owns, as (3*fa+e, 3*fb+g).
FeaturePairList featurePairs(const std::vector<std::uint32_t>& faceIndices,
                             const std::vector<std::uint32_t>& faceOwned,
                             const std::vector<IndexPair>& candidates);

/// Continuous detection's expansion (feature_pairs.comp with GLC_CCD_COMPLETE): featurePairs plus
/// the orphans, each once. For each candidate (fa, fb): every corner p of one face not owned by it
/// whose owner face (model::featureOwners) shares a node with the other face G, when that face is
/// the lowest face around p sharing no node with G; every edge pair (e of fa, g of fb) whose owner
/// faces share a node, when (min(fa, fb), max(fa, fb)) is the lowest such face pair around the two
/// edges whose faces share no node.
FeaturePairList ccdFeaturePairs(const std::vector<std::uint32_t>& faceIndices,
                                const std::vector<std::uint32_t>& faceOwned,
                                const std::vector<std::uint32_t>& featureOwners,
                                const std::vector<IndexPair>& candidates);

/// One contact (shaders/common/contact_pair.glsl): four nodes with signed weights (side A: +,
/// summing to 1; side B: −, summing to −1), the unit normal from B to A and the depth inside the
/// thickness.
struct ContactGeometry {
    std::array<std::uint32_t, 4> nodes{};
    std::array<double, 4> weights{};
    glm::dvec3 normal{0.0};
    double depth = 0.0;
};

/// Whether a vertex or edge that went through a face or edge within the substep (its side at the
/// start, x − substep·v, is the other one) is a contact at any depth or only within the thickness
/// (contact_pair.glsl's kContactCrossings). The implicit solve's Newton steps take any depth: they
/// linearise at a predicted end x1 = x0 + h·v1 that may have gone through by more than the
/// thickness, and a pair that is no contact there would get no force at all (decision 0024,
/// "Crossings in the Newton steps"). The responses and the energy guard, whose positions never
/// went through, keep the thickness.
enum class Crossings { WithinThickness, AtAnyDepth };

/// The contacts among the feature pairs, in list order (vertex-face, then edge-edge): the rules of
/// the response and of the implicit solve's contact term (implicit_contact_find.comp).
std::vector<ContactGeometry> contactGeometries(const ContactParams& params, const ContactInput& in,
                                               const FeaturePairList& pairs,
                                               Crossings crossings = Crossings::WithinThickness);

/// How far, relative to a feature's size, a float evaluation of contact_pair.glsl may move the
/// boundaries of the closest-feature regions (an edge's end, a face's edge or corner) that decide
/// which feature pair counts a contact: 2⁻¹⁴. Where it comes from: the region tests compare dot
/// products of coordinate differences, each rounded by a few units of u = 2⁻²⁴ of the coordinates'
/// size |x|, so a boundary moves by about 4u·|x| — 2⁻¹⁴ of a feature up to 2⁸ times smaller than
/// its distance from the origin (a 1 cm face 2.5 m away). For edge pairs it is the relative error of
/// each dot product of closestSegmentParams (ambiguousContactEnergy).
inline constexpr double kFloatRegionSlack = 1.0 / 16384.0;

/// The energy ½·k·depth² of the feature pairs whose contact a float evaluation may count where this
/// double one does not, or not count where it does: a vertex-face pair whose status changes with
/// the face scaled about its centroid by 1 ± `relativeSlack` (each adds the largest energy of the
/// three evaluations); an edge pair whose closest-point parameters, with every dot product off by
/// `relativeSlack` of itself, may fall on either side of its edges' ends, or whose edges may be
/// parallel in float (each adds ½·k·(h − the segments' distance)²). The contact energy is not
/// continuous across those boundaries (a vertex near an edge can be counted by a vertex-face and an
/// edge-edge pair on one side and by one of them on the other: decision 0024, "Known failures"), so
/// a GPU sum of the same state may differ from the CPU's by up to this (Engine::energy).
double ambiguousContactEnergy(const ContactParams& params, const ContactInput& in,
                              const FeaturePairList& pairs, double relativeSlack = kFloatRegionSlack);

/// Contact forces of the feature pairs (the response's two kernels, count pass then force pass).
ContactResult contactForces(const ContactParams& params, const ContactInput& in,
                            const FeaturePairList& pairs);
/// Contact forces of the candidate face pairs: contactForces of their featurePairs.
ContactResult contactForces(const ContactParams& params, const ContactInput& in,
                            const std::vector<IndexPair>& candidates);

/// Barycentric weights of the point of triangle abc closest to p (Ericson §5.1.5).
glm::dvec3 closestOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                             const glm::dvec3& c);
/// Parameters (s, t) of the closest points of segments p0p1 and q0q1 (Ericson §5.1.9).
std::array<double, 2> closestSegmentParams(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& q0,
                                           const glm::dvec3& q1);

} // namespace glcollide::cpu
