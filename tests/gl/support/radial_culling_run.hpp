#pragma once
// One run of the radial culling pass over a substep x0 -> x1 of a face soup, for the GL tests that
// drive passes::RadialCullingPass directly: the buffers it reads, bound as the engine binds them,
// and the statistics read back into `lists`; and what the tests compare it with (the twins'
// closed surfaces, the exact oracle along the motion).

#include "cpu/collision_twin.hpp"
#include "model/flat_model.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/radial_culling.hpp"
#include "support/collision_buffers.hpp"

#include <gtest/gtest.h>

#include <glm/vec3.hpp>

#include <algorithm>
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

/// What one run of the culling pass gave, read back.
struct CullingRun {
    std::vector<std::uint8_t> free; ///< per real face, from the GPU
    std::uint32_t freeCount = 0;
    std::vector<passes::RadialWinding> winding; ///< per observer
    std::uint32_t violatedStat = 0;
    std::vector<passes::RadialObserver> observers, ghostNodes;
};

/// One run of the culling pass over x0 -> x1 with the engine's configuration for `model`.
inline CullingRun runCulling(const model::FlatModel& model, const passes::RadialCullingConfig& config,
                             const std::vector<glm::vec3>& x0, const std::vector<glm::vec3>& x1) {
    passes::RadialCullingPass pass(config);
    passes::AppendLists lists(0);
    runRadialCulling(pass, lists, x0, x1, model.faceIndices);
    CullingRun r;
    const std::vector<std::uint32_t> mask = pass.readFreeMask();
    for (std::size_t f = 0; f < model.faceCount(); ++f) {
        r.free.push_back(static_cast<std::uint8_t>(mask[f / 32] >> (f % 32) & 1u));
        r.freeCount += r.free.back();
    }
    EXPECT_EQ(lists.stat(GLC_STAT_RADIAL_FREE), r.freeCount);
    r.winding = pass.readWinding();
    r.violatedStat = lists.stat(GLC_STAT_RADIAL_VIOLATED);
    r.observers = pass.readObservers();
    r.ghostNodes = pass.readGhostNodes();
    return r;
}

/// Real positions followed by the GPU's ghost nodes at one end of the substep.
inline std::vector<glm::vec3> withGhosts(std::vector<glm::vec3> x,
                                         const std::vector<passes::RadialObserver>& ghosts, bool end) {
    for (const passes::RadialObserver& g : ghosts) x.push_back(end ? g.end : g.start);
    return x;
}

/// The observed closed surfaces for the twins: the real faces, then the ghost faces; each face's
/// observer; the real nodes followed by the GPU's ghost nodes at both ends of the substep.
struct ClosedByGhosts {
    std::vector<std::uint32_t> faces, observers;
    std::vector<glm::vec3> x0, x1;
};
inline ClosedByGhosts closedByGhosts(const model::FlatModel& model, const passes::RadialCullingConfig& config,
                                     const CullingRun& run, const std::vector<glm::vec3>& x0,
                                     const std::vector<glm::vec3>& x1) {
    ClosedByGhosts c{model.faceIndices, config.faceObserver, withGhosts(x0, run.ghostNodes, false),
                     withGhosts(x1, run.ghostNodes, true)};
    c.faces.insert(c.faces.end(), config.ghosts.faces.begin(), config.ghosts.faces.end());
    c.observers.insert(c.observers.end(), config.ghosts.faceObserver.begin(),
                       config.ghosts.faceObserver.end());
    return c;
}

/// No face the GPU calls free intersects another face of `model` at t = k/8, k = 1..8, of the
/// linear motion x0 -> x1 (exact oracle) — with `faceObserver`, another face of its own observer's
/// surface (the theorem's scope: clusters say nothing about each other); returns the most pairs so
/// intersecting at one of those times.
inline std::size_t expectFreeFacesIntersectNothing(const model::FlatModel& model,
                                                   const std::vector<glm::vec3>& x0,
                                                   const std::vector<glm::vec3>& x1,
                                                   const std::vector<std::uint8_t>& free,
                                                   const std::vector<std::uint32_t>& faceObserver = {}) {
    const std::vector<std::uint32_t> faceObject(model.faceCount(), 0u);
    std::size_t intersecting = 0, k = 0;
    for (const auto& pairs : cpu::twinIntersectionsAlongMotion(model.faceIndices, faceObject, x0, x1,
                                                               cpu::PairRules{false, true}, 8)) {
        ++k;
        std::size_t counted = 0;
        for (const cpu::FacePair& p : pairs) {
            if (!faceObserver.empty() && faceObserver[p[0]] != faceObserver[p[1]]) continue;
            ++counted;
            EXPECT_FALSE(free[p[0]] || free[p[1]])
                << "faces " << p[0] << " and " << p[1] << " intersect at t = " << k << "/8, one of them free";
        }
        intersecting = std::max(intersecting, counted);
    }
    return intersecting;
}

} // namespace glcollide::test
