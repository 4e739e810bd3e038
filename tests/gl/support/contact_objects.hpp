#pragma once
// The objects a contact pass reads (GpuObject: a node range and whether the surface is closed) and
// the twin's node → object map, for the GL tests that build faces and objects by hand. The node
// ranges matter: contact_pair.glsl's keepsOutside keeps only another object's vertex outside a
// closed object's face (decision 0024, "Thin parts of closed objects").

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace glcollide::test {

/// The object of each node: that of the faces it belongs to (objects share no node); a node on no
/// face takes the object of the node before it (0 for the first), so ranges stay consecutive.
inline std::vector<std::uint32_t> nodeObjectsOfFaces(const std::vector<std::uint32_t>& faces,
                                                     const std::vector<std::uint32_t>& faceObject,
                                                     std::size_t nodeCount) {
    constexpr std::uint32_t kNone = ~0u;
    std::vector<std::uint32_t> objectOf(nodeCount, kNone);
    for (std::size_t f = 0; f < faceObject.size(); ++f)
        for (std::size_t k = 0; k < 3; ++k) objectOf[faces[3 * f + k]] = faceObject[f];
    for (std::size_t n = 0; n < nodeCount; ++n)
        if (objectOf[n] == kNone) objectOf[n] = n == 0 ? 0u : objectOf[n - 1];
    return objectOf;
}

/// One GpuObject per entry of `objectClosed` (only firstNode, nodeCount and closed are set: what
/// the contact passes read) with its node range, as the engine lays objects out. Random soups
/// interleave their objects' nodes: an open object whose nodes are not consecutive gets the empty
/// range (read only by the coplanar side rule, for a vertex exactly in a face's plane, which such
/// soups do not reach). Throws when a closed object's nodes are not consecutive.
inline std::vector<gpu::GpuObject> gpuObjects(const std::vector<std::uint32_t>& nodeObject,
                                              const std::vector<std::uint8_t>& objectClosed) {
    std::vector<gpu::GpuObject> objects(objectClosed.size(), gpu::GpuObject{});
    std::vector<bool> scattered(objects.size(), false);
    for (std::size_t o = 0; o < objects.size(); ++o) objects[o].closed = objectClosed[o];
    for (std::uint32_t n = 0; n < nodeObject.size(); ++n) {
        gpu::GpuObject& o = objects.at(nodeObject[n]);
        if (o.nodeCount == 0) o.firstNode = n;
        if (o.firstNode + o.nodeCount != n) {
            if (o.closed != 0)
                throw Error("gpuObjects: the nodes of object " + std::to_string(nodeObject[n]) +
                            " are not consecutive (node " + std::to_string(n) + ")");
            scattered[nodeObject[n]] = true;
        }
        ++o.nodeCount;
    }
    for (std::size_t o = 0; o < objects.size(); ++o)
        if (scattered[o]) objects[o].firstNode = objects[o].nodeCount = 0;
    return objects;
}

} // namespace glcollide::test
