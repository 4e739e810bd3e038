#version 430 core
// ImplicitCgUpdate — iteration u_iteration of the implicit solver's conjugate gradients, second
// width (skipped once ImplicitCgDirection declared the solve over): alpha = rz / p·q from the
// previous pass's partial sums (the same bits in every group), then per node
//   v += alpha·p   (the velocity accumulates Δv directly),  r −= alpha·q,  z = P⁻¹·r,
// and per-group partial sums of r·z and r·r for the next ImplicitCgDirection.
// Every node is updated by the light layout; heavy groups only write a zero partial (the partial
// arrays have one entry per group of the shared layout). Twin: cpu::implicitVelocityUpdate.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/row_gather.glsl"
#include "common/implicit_solver.glsl"
#include "common/implicit_pq.glsl"

layout(std430, binding = GLC_BIND_NODE_VELOCITIES) buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
layout(std430, binding = GLC_BIND_SOLVER_RESIDUAL) buffer ResidualBuf { vec4 g_residual[]; };
layout(std430, binding = GLC_BIND_SOLVER_PRECONDITIONED) writeonly buffer PreconditionedBuf { vec4 g_preconditioned[]; };
layout(std430, binding = GLC_BIND_SOLVER_DIRECTION_OUT) readonly buffer DirectionOutBuf { vec4 g_direction[]; };
layout(std430, binding = GLC_BIND_SOLVER_PRODUCT) readonly buffer ProductBuf { vec4 g_product[]; };
layout(std430, binding = GLC_BIND_SOLVER_BLOCK_INVERSE) readonly buffer BlockInverseBuf { float g_blockInverse[]; };

uniform uint u_iteration;

void main() {
    if (groupIsPadding()) return; // whole groups only: the rest meet at barriers
    if (g_state.doneAt != GLC_SOLVER_RUNNING) return; // set by the previous pass: uniform
    float pq = sumPartialsPq();
    // p·q > 0 for A positive definite and p ≠ 0; anything else (rounding to 0 near rest) is no step.
    float alpha = pq > 0.0 ? g_state.rz[u_iteration & 1u] / pq : 0.0;
    uint i = groupIndex() * GLC_WORKGROUP_SIZE + gl_LocalInvocationID.x;
    vec2 partial = vec2(0.0);
    if (!groupIsHeavy() && i < u_nodeCount) {
        g_velocities[i].xyz += alpha * g_direction[i].xyz;
        vec3 r = g_residual[i].xyz - alpha * g_product[i].xyz;
        vec4 inverseA = vec4(g_blockInverse[6u * i], g_blockInverse[6u * i + 1u], g_blockInverse[6u * i + 2u],
                             g_blockInverse[6u * i + 3u]);
        vec2 inverseB = vec2(g_blockInverse[6u * i + 4u], g_blockInverse[6u * i + 5u]);
        vec3 z = symMul(inverseA, inverseB, r);
        g_residual[i] = vec4(r, 0.0);
        g_preconditioned[i] = vec4(z, 0.0);
        partial = vec2(dot(r, z), dot(r, r));
    }
    vec2 groupPartial = groupSum(vec4(partial, 0.0, 0.0)).xy;
    if (gl_LocalInvocationID.x == 0u) g_partialsR[groupIndex()] = groupPartial;
}
