#pragma once
// A scene flattened into the global arrays the GPU holds: all bodies' nodes, faces and springs
// concatenated, plus per-node adjacency in CSR form. Built once on the CPU; the engine uploads it
// and the CPU twins run on it, so both sides see exactly the same data. Module `model` (no GL, no
// GMP): this file, features.hpp, octree_layout.hpp, face_box.hpp.

#include <glcollide/scene.hpp>

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace glcollide::model {

struct FlatSpring {
    std::uint32_t a = 0, b = 0; ///< global node indices
    double restLength = 0, stiffness = 0, damping = 0;
};

/// Compressed sparse rows: the neighbours of row i are items[offsets[i] .. offsets[i+1]).
struct Csr {
    std::vector<std::uint32_t> offsets; ///< rows + 1 entries
    std::vector<std::uint32_t> items;
};

struct ObjectRange {
    std::uint32_t firstNode = 0, nodeCount = 0, firstFace = 0, faceCount = 0, firstSpring = 0,
                  springCount = 0;
};

struct FlatModel {
    std::vector<glm::dvec3> positions;      ///< m
    std::vector<glm::dvec3> velocities;     ///< m/s (0 for pinned nodes)
    std::vector<double> masses;             ///< kg
    std::vector<double> inverseMasses;      ///< 1/kg; 0 for pinned nodes
    std::vector<std::uint32_t> faceIndices; ///< 3 per face, global
    std::vector<FlatSpring> springs;
    std::vector<ObjectRange> objects;
    Csr nodeSprings; ///< springs adjacent to each node, in increasing spring index (deterministic)
    Csr nodeFaces;   ///< faces adjacent to each node, in increasing face index

    [[nodiscard]] std::size_t nodeCount() const { return positions.size(); }
    [[nodiscard]] std::size_t faceCount() const { return faceIndices.size() / 3; }
};

/// Concatenates the bodies of `scene`. Pinned nodes get inverse mass 0 and velocity 0.
FlatModel flatten(const Scene& scene);

/// The object of each node (ObjectRange::firstNode … + nodeCount).
std::vector<std::uint32_t> nodeObjects(const FlatModel& model);

/// Builds the node→item adjacency of items that each list `perItem` node indices.
Csr buildAdjacency(std::size_t nodeCount, const std::vector<std::uint32_t>& itemNodes, std::size_t perItem);

/// Node→spring adjacency of a spring list (each spring appears in both of its nodes' rows).
Csr buildSpringAdjacency(std::size_t nodeCount, const std::vector<FlatSpring>& springs);

} // namespace glcollide::model
