#pragma once
// One run of the radial culling pass over a substep x0 -> x1 of a face soup, for the GL tests that
// drive passes::RadialCullingPass directly: the buffers it reads, bound as the engine binds them,
// and the statistics read back into `lists`.

#include "passes/collision/append_lists.hpp"
#include "passes/radial_culling.hpp"
#include "support/collision_buffers.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace glcollide::test {

inline void runRadialCulling(const passes::RadialCullingPass& pass, passes::AppendLists& lists,
                             const std::vector<glm::vec3>& x0, const std::vector<glm::vec3>& x1,
                             const std::vector<std::uint32_t>& faceIndices) {
    passes::DeviceBuffers b = collisionBuffers(x0, faceIndices);
    b.predictedPositions = gl::makeBuffer("predictedPositions", positionsWithUnitW(x1));
    lists.bind();
    b.positions.bindStorage(GLC_BIND_NODE_POSITIONS);
    b.predictedPositions.bindStorage(GLC_BIND_PREDICTED_POSITIONS);
    b.faces.bindStorage(GLC_BIND_FACES);
    pass.run(lists);
    lists.readCounters();
}

} // namespace glcollide::test
