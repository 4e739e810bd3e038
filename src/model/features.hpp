#pragma once
// Feature ownership and edges of the flattened faces. A node is owned by the lowest-indexed face
// containing it, an edge (unordered node pair) by the lowest-indexed face containing it; the owner
// alone generates the feature's vertex-face and edge-edge contacts, so a shared feature counts once.
// The owned-feature bits are GLC_OWN_* of shaders/common/layout.glsl (through core/gpu_layout.hpp,
// its GL-free C++ view): defined there once, for the shaders, the engine and the CPU twins alike.

#include "core/gpu_layout.hpp"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace glcollide::model {

/// Owned bit of corner k (0..2) of a face: GLC_OWN_VERTEX0 << k.
constexpr std::uint32_t ownVertexBit(int k) {
    return GLC_OWN_VERTEX0 << k;
}
/// Owned bit of edge k (0..2) of a face, the edge from corner k to corner (k + 1) % 3:
/// GLC_OWN_EDGE01 << k.
constexpr std::uint32_t ownEdgeBit(int k) {
    return GLC_OWN_EDGE01 << k;
}
static_assert(ownVertexBit(1) == GLC_OWN_VERTEX1 && ownVertexBit(2) == GLC_OWN_VERTEX2 &&
                  ownEdgeBit(1) == GLC_OWN_EDGE12 && ownEdgeBit(2) == GLC_OWN_EDGE20,
              "the shaders shift GLC_OWN_VERTEX0 and GLC_OWN_EDGE01 by the corner or edge number");

/// Edge k (0..2) of face f: its corners k and (k + 1) % 3, in the face's winding order.
inline std::array<std::uint32_t, 2> faceEdge(const std::vector<std::uint32_t>& faceIndices,
                                             std::uint32_t face, int k) {
    const std::size_t first = 3 * static_cast<std::size_t>(face);
    return {faceIndices[first + static_cast<std::size_t>(k)],
            faceIndices[first + static_cast<std::size_t>((k + 1) % 3)]};
}

/// One key per undirected edge: (min << 32) | max of its two nodes.
inline std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    return (static_cast<std::uint64_t>(a) << 32) | b;
}

/// Owned-feature bits (GLC_OWN_*) of every face: a node is owned by the lowest-indexed face
/// containing it, an edge (unordered node pair) by the lowest-indexed face containing it.
std::vector<std::uint32_t> ownedFeatures(const std::vector<std::uint32_t>& faceIndices);

/// Owner face of every feature, 6 per face: [6f + k] the owner of corner k
/// (0..2) of face f, [6f + 3 + k] the owner of edge k; the same owners as ownedFeatures.
std::vector<std::uint32_t> featureOwners(const std::vector<std::uint32_t>& faceIndices);

/// Each node's faces (for orphanTable and the CPU twin's orphan rule): words [0, nodeCount]
/// are offsets counted from the table's start, node n's faces in increasing order (each once) at
/// [table[n], table[n + 1]). Throws std::out_of_range for a node index >= nodeCount.
std::vector<std::uint32_t> nodeFaceTable(const std::vector<std::uint32_t>& faceIndices,
                                         std::size_t nodeCount);

/// Continuous detection's orphan feature pairs (decision 0018, addendum "Orphans"), precomputed
/// from the topology for FeaturePairs (GLC_BIND_FEATURE_ORPHANS). An orphan is a feature pair whose
/// owner faces share a node (ownership's candidate does not exist); exactly one face pair carries
/// it: for a corner p of face A against face G (A does not own p, p's owner shares a node with G),
/// A is the lowest face around p sharing no node with G; for an edge pair, the carrier is the lowest
/// face pair (one face around each edge) whose faces share no node. Layout: words [0, faceCount]
/// are offsets counted from the table's start; face L's entries, at [table[L], table[L + 1]), are
/// word pairs (H, bits) for the faces H > L of the pairs (L, H) that carry orphans, H increasing.
/// bits: 1 << k, corner k of L against H; 1 << (3 + k), corner k of H against L;
/// 1 << (6 + 3e + g), edge e of L against edge g of H (edge e: corner e to corner (e + 1) % 3).
/// Throws std::out_of_range for a node index >= nodeCount.
std::vector<std::uint32_t> orphanTable(const std::vector<std::uint32_t>& faceIndices, std::size_t nodeCount);

/// Bit positions of orphanTable's entries (GLC_ORPHAN_* of shaders/common/layout.glsl).
constexpr std::uint32_t kOrphanLowerCorner = 0, kOrphanHigherCorner = GLC_ORPHAN_HIGHER_CORNERS,
                        kOrphanEdgePair = GLC_ORPHAN_EDGE_PAIRS;

/// 1 when every edge of faces [firstFace, firstFace + faceCount) has exactly two of those faces;
/// 0 otherwise, and for an object without faces (it bounds no volume).
bool isClosedSurface(const std::vector<std::uint32_t>& faceIndices, std::uint32_t firstFace,
                     std::uint32_t faceCount);

} // namespace glcollide::model
