#include "model/flat_model.hpp"

#include <algorithm>

#include <glcollide/error.hpp>

namespace glcollide::model {

std::vector<std::uint32_t> nodeObjects(const FlatModel& model) {
    std::vector<std::uint32_t> objectOf(model.nodeCount(), 0);
    for (std::uint32_t o = 0; o < model.objects.size(); ++o) {
        const ObjectRange& r = model.objects[o];
        std::fill_n(objectOf.begin() + r.firstNode, r.nodeCount, o);
    }
    return objectOf;
}

Csr buildAdjacency(std::size_t nodeCount, const std::vector<std::uint32_t>& itemNodes, std::size_t perItem) {
    Csr csr;
    csr.offsets.assign(nodeCount + 1, 0);
    for (std::uint32_t n : itemNodes) ++csr.offsets[n + 1];
    for (std::size_t i = 0; i < nodeCount; ++i) csr.offsets[i + 1] += csr.offsets[i];
    csr.items.resize(itemNodes.size());
    std::vector<std::uint32_t> cursor(csr.offsets.begin(), csr.offsets.end() - 1);
    // Items are visited in increasing index, so each row comes out sorted: a fixed gather order
    // makes the GPU sums reproducible bit for bit.
    for (std::size_t k = 0; k < itemNodes.size(); ++k)
        csr.items[cursor[itemNodes[k]]++] = static_cast<std::uint32_t>(k / perItem);
    return csr;
}

Csr buildSpringAdjacency(std::size_t nodeCount, const std::vector<FlatSpring>& springs) {
    std::vector<std::uint32_t> ends;
    ends.reserve(springs.size() * 2);
    for (const FlatSpring& s : springs) {
        ends.push_back(s.a);
        ends.push_back(s.b);
    }
    return buildAdjacency(nodeCount, ends, 2);
}

FlatModel flatten(const Scene& scene) {
    FlatModel m;
    for (const Body& body : scene.bodies) {
        ObjectRange range;
        range.firstNode = static_cast<std::uint32_t>(m.positions.size());
        range.nodeCount = static_cast<std::uint32_t>(body.positions.size());
        range.firstFace = static_cast<std::uint32_t>(m.faceCount());
        range.faceCount = static_cast<std::uint32_t>(body.faces.size());
        range.firstSpring = static_cast<std::uint32_t>(m.springs.size());
        range.springCount = static_cast<std::uint32_t>(body.springs.size());
        const std::uint32_t base = range.firstNode;
        for (std::size_t i = 0; i < body.positions.size(); ++i) {
            const bool pinned = !body.pinned.empty() && body.pinned[i] != 0;
            m.positions.push_back(body.positions[i]);
            m.velocities.push_back(pinned ? glm::dvec3(0.0) : body.velocities[i]);
            m.masses.push_back(body.masses[i]);
            m.inverseMasses.push_back(pinned ? 0.0 : 1.0 / body.masses[i]);
        }
        for (const auto& f : body.faces)
            for (std::uint32_t v : f) m.faceIndices.push_back(base + v);
        for (const Spring& s : body.springs)
            m.springs.push_back({base + s.a, base + s.b, s.restLength, s.stiffness, s.damping});
        m.objects.push_back(range);
    }
    if (m.positions.size() > 0xffffffffu / 2) throw Error("scene has too many nodes for 32-bit indices");
    m.nodeSprings = buildSpringAdjacency(m.nodeCount(), m.springs);
    m.nodeFaces = buildAdjacency(m.nodeCount(), m.faceIndices, 3);
    return m;
}

} // namespace glcollide::model
