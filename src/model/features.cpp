#include "model/features.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <unordered_map>
#include <vector>

namespace glcollide::model {

std::vector<std::uint32_t> ownedFeatures(const std::vector<std::uint32_t>& faceIndices) {
    const std::size_t faces = faceIndices.size() / 3;
    std::unordered_map<std::uint32_t, std::uint32_t> nodeOwner;
    std::unordered_map<std::uint64_t, std::uint32_t> edgeOwner;
    nodeOwner.reserve(faces * 3);
    edgeOwner.reserve(faces * 3);
    // Visiting faces in increasing index, the first face to see a feature is its lowest face.
    for (std::uint32_t f = 0; f < faces; ++f)
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = faceEdge(faceIndices, f, k);
            nodeOwner.try_emplace(a, f);
            edgeOwner.try_emplace(edgeKey(a, b), f);
        }
    std::vector<std::uint32_t> owned(faces, 0u);
    for (std::uint32_t f = 0; f < faces; ++f)
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = faceEdge(faceIndices, f, k);
            if (nodeOwner.at(a) == f) owned[f] |= ownVertexBit(k);
            if (edgeOwner.at(edgeKey(a, b)) == f) owned[f] |= ownEdgeBit(k);
        }
    return owned;
}

std::vector<std::uint32_t> featureOwners(const std::vector<std::uint32_t>& faceIndices) {
    const auto faces = static_cast<std::uint32_t>(faceIndices.size() / 3);
    std::unordered_map<std::uint32_t, std::uint32_t> nodeOwner;
    std::unordered_map<std::uint64_t, std::uint32_t> edgeOwner;
    for (std::uint32_t f = 0; f < faces; ++f) // increasing index: the first face seen is the owner
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = faceEdge(faceIndices, f, k);
            nodeOwner.try_emplace(a, f);
            edgeOwner.try_emplace(edgeKey(a, b), f);
        }
    std::vector<std::uint32_t> owners(6 * static_cast<std::size_t>(faces));
    for (std::uint32_t f = 0; f < faces; ++f)
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = faceEdge(faceIndices, f, k);
            owners[6 * std::size_t{f} + static_cast<std::size_t>(k)] = nodeOwner.at(a);
            owners[6 * std::size_t{f} + 3 + static_cast<std::size_t>(k)] = edgeOwner.at(edgeKey(a, b));
        }
    return owners;
}

bool isClosedSurface(const std::vector<std::uint32_t>& faceIndices, std::uint32_t firstFace,
                     std::uint32_t faceCount) {
    if (faceCount == 0) return false;
    std::unordered_map<std::uint64_t, std::uint32_t> edgeFaces;
    edgeFaces.reserve(static_cast<std::size_t>(faceCount) * 3);
    for (std::uint32_t f = firstFace; f < firstFace + faceCount; ++f)
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = faceEdge(faceIndices, f, k);
            ++edgeFaces[edgeKey(a, b)];
        }
    return std::all_of(edgeFaces.begin(), edgeFaces.end(), [](const auto& e) { return e.second == 2; });
}

std::vector<std::uint32_t> nodeFaceTable(const std::vector<std::uint32_t>& faceIndices,
                                         std::size_t nodeCount) {
    std::vector<std::vector<std::uint32_t>> around(nodeCount);
    for (std::size_t f = 0; f < faceIndices.size() / 3; ++f)
        for (std::size_t k = 0; k < 3; ++k) {
            std::vector<std::uint32_t>& faces = around.at(faceIndices[3 * f + k]);
            if (faces.empty() || faces.back() != f)
                faces.push_back(static_cast<std::uint32_t>(f)); // faces in order
        }
    std::vector<std::uint32_t> table(nodeCount + 1);
    std::size_t next = nodeCount + 1;
    for (std::size_t n = 0; n < nodeCount; ++n) {
        table[n] = static_cast<std::uint32_t>(next);
        table.insert(table.end(), around[n].begin(), around[n].end());
        next += around[n].size();
    }
    table[nodeCount] = static_cast<std::uint32_t>(next);
    return table;
}

namespace {

constexpr std::uint32_t kNoFace = std::numeric_limits<std::uint32_t>::max();

// The topology orphanTable reads: each node's faces (nodeFaceTable) and every feature's owner.
class OrphanTopology {
  public:
    OrphanTopology(const std::vector<std::uint32_t>& faceIndices, std::size_t nodeCount)
        : m_faces(faceIndices), m_around(nodeFaceTable(faceIndices, nodeCount)),
          m_owners(featureOwners(faceIndices)) {}

    std::uint32_t corner(std::uint32_t f, std::uint32_t k) const { return m_faces[3 * std::size_t{f} + k]; }
    bool hasNode(std::uint32_t f, std::uint32_t n) const {
        return corner(f, 0) == n || corner(f, 1) == n || corner(f, 2) == n;
    }
    bool sharesNode(std::uint32_t f, std::uint32_t g) const {
        return hasNode(g, corner(f, 0)) || hasNode(g, corner(f, 1)) || hasNode(g, corner(f, 2));
    }
    std::uint32_t edgeOwner(std::uint32_t f, std::uint32_t k) const {
        return m_owners[6 * std::size_t{f} + 3 + k];
    }
    std::uint32_t nodeOwner(std::uint32_t n) const { return m_around[m_around[n]]; }

    /// Faces around node n, increasing.
    template <typename Visit> void forFacesAround(std::uint32_t n, Visit&& visit) const {
        for (std::uint32_t i = m_around[n]; i < m_around[n + 1]; ++i) visit(m_around[i]);
    }

    /// Faces sharing a node with face f (f included), increasing, each once.
    std::vector<std::uint32_t> facesTouching(std::uint32_t f) const {
        std::vector<std::uint32_t> out;
        for (std::uint32_t k = 0; k < 3; ++k)
            forFacesAround(corner(f, k), [&](std::uint32_t g) { out.push_back(g); });
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        return out;
    }

    /// The lowest face around node n that shares no node with face g (kNoFace: none).
    std::uint32_t lowestFaceApart(std::uint32_t n, std::uint32_t g) const {
        for (std::uint32_t i = m_around[n]; i < m_around[n + 1]; ++i)
            if (!sharesNode(m_around[i], g)) return m_around[i];
        return kNoFace;
    }

    /// The lowest (lower, higher) face pair, one face around each edge (node pairs), whose faces
    /// share no node ({kNoFace, kNoFace}: none).
    std::array<std::uint32_t, 2> lowestFacePairApart(std::array<std::uint32_t, 2> a,
                                                     std::array<std::uint32_t, 2> b) const {
        std::array<std::uint32_t, 2> best{kNoFace, kNoFace};
        forFacesAround(a[0], [&](std::uint32_t f) {
            if (!hasNode(f, a[1])) return;
            forFacesAround(b[0], [&](std::uint32_t g) {
                if (hasNode(g, b[1]) && !sharesNode(f, g))
                    best = std::min(best, {std::min(f, g), std::max(f, g)});
            });
        });
        return best;
    }

    /// Which edge (0..2) of face f joins nodes e[0] and e[1]; 3 when none does.
    std::uint32_t edgeIndex(std::uint32_t f, std::array<std::uint32_t, 2> e) const {
        for (std::uint32_t k = 0; k < 3; ++k) {
            const auto [p, q] = faceEdge(m_faces, f, static_cast<int>(k));
            if ((p == e[0] && q == e[1]) || (p == e[1] && q == e[0])) return k;
        }
        return 3;
    }

  private:
    const std::vector<std::uint32_t>& m_faces;
    std::vector<std::uint32_t> m_around, m_owners;
};

} // namespace

// Built from the features, not by testing face pairs: every orphan is found from its feature pair
// (a corner against each face its owner touches; an edge against each edge owned by a face its
// owner touches) and its one carrier computed as FeaturePairs' rule states it. The CPU twin
// (cpu::ccdFeaturePairs) applies that rule to each candidate pair instead, and the unit tests
// compare the two over every face pair of small meshes.
std::vector<std::uint32_t> orphanTable(const std::vector<std::uint32_t>& faceIndices, std::size_t nodeCount) {
    const auto faceCount = static_cast<std::uint32_t>(faceIndices.size() / 3);
    const OrphanTopology topo(faceIndices, nodeCount);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> marks; // ((lower << 32) | higher, bit)
    const auto mark = [&](std::uint32_t f, std::uint32_t g, std::uint32_t bit) {
        marks.emplace_back((std::uint64_t{std::min(f, g)} << 32) | std::max(f, g), bit);
    };
    // Vertex-face orphans: corner p of A against G, where p's owner touches G.
    std::vector<std::uint8_t> nodeSeen(nodeCount, 0u);
    for (std::uint32_t f = 0; f < faceCount; ++f)
        for (std::uint32_t k = 0; k < 3; ++k) {
            const std::uint32_t p = topo.corner(f, k);
            if (nodeSeen.at(p) != 0u) continue;
            nodeSeen[p] = 1u;
            for (const std::uint32_t g : topo.facesTouching(topo.nodeOwner(p))) {
                const std::uint32_t a = topo.lowestFaceApart(p, g);
                if (a == kNoFace) continue;
                const std::uint32_t corner = topo.corner(a, 0) == p ? 0 : topo.corner(a, 1) == p ? 1 : 2;
                mark(a, g, 1u << ((a < g ? kOrphanLowerCorner : kOrphanHigherCorner) + corner));
            }
        }
    // Edge-edge orphans: edge a (owned by fa) against every edge owned by a face that touches fa
    // (a symmetric relation: each unordered pair once, from its lower (face, edge)). Edges sharing
    // a node have no faces apart.
    for (std::uint32_t fa = 0; fa < faceCount; ++fa) {
        const std::vector<std::uint32_t> touching = topo.facesTouching(fa);
        for (std::uint32_t ka = 0; ka < 3; ++ka) {
            if (topo.edgeOwner(fa, ka) != fa) continue;
            const auto ea = faceEdge(faceIndices, fa, static_cast<int>(ka));
            for (const std::uint32_t fb : touching)
                for (std::uint32_t kb = 0; kb < 3; ++kb) {
                    if (topo.edgeOwner(fb, kb) != fb || fb < fa || (fb == fa && kb <= ka)) continue;
                    const auto eb = faceEdge(faceIndices, fb, static_cast<int>(kb));
                    if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) continue;
                    const auto carrier = topo.lowestFacePairApart(ea, eb);
                    if (carrier[0] == kNoFace) continue;
                    // The carrier's lower face holds one of the two edges, its higher face the other.
                    const bool lowerHoldsA = topo.edgeIndex(carrier[0], ea) < 3;
                    const std::uint32_t e = topo.edgeIndex(carrier[0], lowerHoldsA ? ea : eb);
                    const std::uint32_t g = topo.edgeIndex(carrier[1], lowerHoldsA ? eb : ea);
                    mark(carrier[0], carrier[1], 1u << (kOrphanEdgePair + 3 * e + g));
                }
        }
    }
    std::sort(marks.begin(), marks.end());
    std::vector<std::uint32_t> table(std::size_t{faceCount} + 1);
    std::uint32_t face = 0;
    for (std::size_t i = 0; i < marks.size();) {
        const std::uint64_t key = marks[i].first;
        std::uint32_t bits = 0;
        for (; i < marks.size() && marks[i].first == key; ++i) bits |= marks[i].second;
        const auto lower = static_cast<std::uint32_t>(key >> 32);
        for (; face <= lower; ++face) table[face] = static_cast<std::uint32_t>(table.size());
        table.push_back(static_cast<std::uint32_t>(key));
        table.push_back(bits);
    }
    for (; face <= faceCount; ++face) table[face] = static_cast<std::uint32_t>(table.size());
    return table;
}

} // namespace glcollide::model
