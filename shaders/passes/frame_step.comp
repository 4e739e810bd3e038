#version 430 core
// glcollide-features: GLC_GRAVITY GLC_DAMPING GLC_WIND GLC_SPRINGS GLC_GROUND GLC_CHECK_FINITE
// FrameStep — every symplectic Euler substep of a frame in one dispatch of one work group, for
// small scenes without collisions, where a substep's passes cost more to launch than to run
// (docs/integration.md, "Fewer dispatches"). Each substep is the SpringUpdate phase (springs and
// external force of every node into g_forces), then the NodeUpdate phase (advance every node);
// the group's invocations take every GLC_FRAME_STEP_GROUP-th node and meet at a barrier between
// phases. The buffers are coherent and each phase ends with memoryBarrierBuffer(), so a phase sees
// the whole previous phase. Only for scenes whose rows have at most GLC_HEAVY_ROW springs.
// Same arithmetic as SpringUpdate + NodeUpdate (shared includes); twins: cpu::nodeForce,
// cpu::springUpdate, cpu::nodeUpdate.
#include "common/layout.glsl"

layout(local_size_x = GLC_FRAME_STEP_GROUP) in;

layout(std430, binding = GLC_BIND_NODE_POSITIONS) coherent buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) coherent buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
layout(std430, binding = GLC_BIND_NODE_FORCES) coherent buffer NodeForcesBuf { vec4 g_forces[]; };
#ifdef GLC_SPRINGS
layout(std430, binding = GLC_BIND_SPRINGS) readonly buffer SpringsBuf { GpuSpring g_springs[]; };
layout(std430, binding = GLC_BIND_NODE_SPRING_OFFSETS) readonly buffer NodeSpringOffsetsBuf { uint g_nodeSpringOffsets[]; };
layout(std430, binding = GLC_BIND_NODE_SPRING_LIST) readonly buffer NodeSpringListBuf { uint g_nodeSpringList[]; };
#include "common/spring_force.glsl"
#endif
#ifdef GLC_CHECK_FINITE
layout(std430, binding = GLC_BIND_HEALTH) buffer HealthBuf { GpuHealth g_health; };
#endif
#include "common/external_force.glsl"
#include "common/advance_node.glsl"

uniform uint u_nodeCount;
uniform uint u_firstSubstep; // index within the frame of this dispatch's first substep
uniform uint u_substeps;     // substeps of this dispatch

void main() {
    uint lane = gl_LocalInvocationID.x;
    for (uint substep = u_firstSubstep; substep < u_firstSubstep + u_substeps; ++substep) {
        for (uint i = lane; i < u_nodeCount; i += GLC_FRAME_STEP_GROUP) {
            vec3 f = externalForce(i);
#ifdef GLC_SPRINGS
            f += springForce(i, g_nodeSpringOffsets[i], g_nodeSpringOffsets[i + 1u], 1u);
#endif
            g_forces[i] = vec4(f, 0.0);
        }
        memoryBarrierBuffer();
        barrier();
        for (uint i = lane; i < u_nodeCount; i += GLC_FRAME_STEP_GROUP) advanceNode(i, g_forces[i].xyz, substep);
        memoryBarrierBuffer();
        barrier();
    }
}
