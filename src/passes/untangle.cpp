#include "passes/untangle.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <array>
#include <string>
#include <vector>

namespace glcollide::passes {

UntanglePass::UntanglePass(std::uint32_t nodeCount, double step)
    : m_push(gl::makeBuffer("untanglePush", std::vector<std::int32_t>(4 * std::size_t{nodeCount}, 0))),
      m_counts(gl::makeBuffer("untangleCounts", std::vector<std::uint32_t>(2, 0u))),
      m_pairs("untangle_pairs"), m_apply("untangle_apply") {
    if (!(step > 0.0)) throw Error("Untangle: step must be > 0, got " + std::to_string(step));
    m_pairs.set("u_pushScale", kPushScale);
    m_apply.set("u_pushScale", kPushScale);
    m_apply.set("u_step", static_cast<float>(step));
    m_apply.set("u_nodeCount", nodeCount);
}

UntangleCounts UntanglePass::dispatch(const DeviceBuffers& b, const CollisionDetection& collision) const {
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, kName, "predictedPositions");
    bindRequired(b.faces, GLC_BIND_FACES, kName, "faces");
    collision.faceInfo().bindStorage(GLC_BIND_FACE_INFO);
    collision.objects().bindStorage(GLC_BIND_OBJECTS);
    collision.intersections().bindStorage(GLC_BIND_INTERSECTIONS);
    collision.counters().bindStorage(GLC_BIND_COLLISION_COUNTERS);
    m_push.bindStorage(GLC_BIND_UNTANGLE_PUSH);
    m_counts.bindStorage(GLC_BIND_UNTANGLE_COUNTS);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // after the last run's reads
    m_push.fill32(0u);
    m_counts.fill32(0u);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    collision.lists().dispatchOver(m_pairs, GLC_LIST_INTERSECTIONS, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_apply.use();
    m_apply.dispatch1D(b.nodeCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    std::array<std::uint32_t, 2> counts{};
    m_counts.download(0, sizeof(counts), counts.data());
    return {counts[0], counts[1]};
}

} // namespace glcollide::passes
