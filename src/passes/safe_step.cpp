#include "passes/safe_step.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <string>
#include <vector>

namespace glcollide::passes {

namespace {
constexpr std::uint32_t kNoImpact = 0x7F800000u; // bits of +inf: above every time in [0, 1]
} // namespace

SafeStepPass::SafeStepPass(const SafeStepSettings& settings, std::uint32_t objectCount, bool ground,
                           double groundHeight)
    : m_settings(settings), m_objectCount(objectCount), m_ground(ground),
      m_objectToi(gl::makeBuffer("objectToi", std::vector<std::uint32_t>(objectCount, kNoImpact))),
      m_program("safe_step") {
    if (!(settings.fraction > 0.0f && settings.fraction < 1.0f))
        throw Error("SafeStep: fraction must be in (0, 1), got " + std::to_string(settings.fraction));
    if (settings.maxRounds < settings.cutRounds)
        throw Error("SafeStep: maxRounds must be at least cutRounds");
    m_program.set("u_ground", ground ? 1u : 0u);
    m_program.set("u_groundHeight", static_cast<float>(groundHeight));
}

void SafeStepPass::cut(const DeviceBuffers& b, const CollisionDetection& collision, float fraction,
                       bool everyNode) const {
    round(b, SafeStepInputs{&collision.nodeToi(), &collision.objects(), &collision.counters()}, fraction,
          everyNode);
}

void SafeStepPass::round(const DeviceBuffers& b, const SafeStepInputs& in, float fraction,
                         bool everyNode) const {
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, kName, "predictedPositions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    if (!in.nodeToi || !in.objects || !in.counters) throw Error(std::string(kName) + ": inputs missing");
    bindRequired(*in.nodeToi, GLC_BIND_NODE_TOI, kName, "nodeToi");
    bindRequired(*in.counters, GLC_BIND_COLLISION_COUNTERS, kName, "collisionCounters");
    bindRequired(*in.objects, GLC_BIND_OBJECTS, kName, "objects");
    m_objectToi.bindStorage(GLC_BIND_OBJECT_TOI);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // after the last round's reads of the times
    m_objectToi.fill32(kNoImpact);
    m_program.use();
    m_program.set("u_nodeCount", b.nodeCount);
    m_program.set("u_objectCount", m_objectCount);
    m_program.set("u_fraction", fraction);
    m_program.set("u_everyNode", everyNode ? 1u : 0u);
    for (const std::uint32_t reduce : {1u, 0u}) { // the objects' earliest times, then the cut
        m_program.set("u_reduce", reduce);
        m_program.dispatch1D(b.nodeCount, GLC_WORKGROUP_SIZE);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    }
}

void SafeStepPass::setSubstep(double h) const {
    m_program.set("u_h", static_cast<float>(h));
}

SafeStepCounts SafeStepPass::dispatch(const DeviceBuffers& b, CollisionDetection& collision, double h,
                                      std::uint32_t mayTouch) const {
    setSubstep(h);
    SafeStepCounts counts;
    // Round r cuts the steps of the objects of every pair that may touch (and, in the first
    // round, of every object whose step crosses the ground), then checks again. The cut rounds
    // move an object to a fraction of its time of impact; the later rounds freeze it.
    while (mayTouch > 0 || (m_ground && counts.rounds == 0)) {
        if (counts.rounds == m_settings.maxRounds) {
            cut(b, collision, 0.0f, true); // the last resort: nothing moves, so nothing can cross
            counts.frozeAll = true;
            break;
        }
        const float fraction = counts.rounds < m_settings.cutRounds ? m_settings.fraction : 0.0f;
        cut(b, collision, fraction, false);
        if (mayTouch == 0 && counts.rounds == 0) {
            // Only the ground was to check: nothing crossed it, nothing was cut, x1 is safe.
            counts.groundCrossings = collision.readStat(GLC_STAT_SAFE_STEP_GROUND);
            if (counts.groundCrossings == 0) break;
        }
        ++counts.rounds;
        mayTouch = collision.recheckCcd(b);
    }
    if (counts.rounds > 0) {
        counts.cuts = collision.readStat(GLC_STAT_SAFE_STEP_CUTS);
        counts.groundCrossings = collision.lists().stat(GLC_STAT_SAFE_STEP_GROUND);
    }
    return counts;
}

void SafeStepPass::commit(const DeviceBuffers& b) {
    // x1 is safe: it becomes the positions (vec4 with the inverse mass, as NodePredict wrote it).
    gl::copyBufferData(b.predictedPositions, b.positions, std::size_t{b.nodeCount} * 4 * sizeof(float));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

} // namespace glcollide::passes
