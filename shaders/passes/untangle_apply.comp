#version 430 core
// Untangle, second kernel (decision 0024, "Deep intersections"; pass: src/passes/untangle.hpp) —
// one invocation per node: a node with pushes (untangle_pairs.comp) moves its step x1 by
// u_step·D/max(1, |D|), D the sum of its pushes: along their sum, at most u_step. The velocity is
// not changed. Counts the nodes moved. Twin: cpu::untangleStep.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) buffer PredictedPositionsBuf { vec4 g_predicted[]; };
layout(std430, binding = GLC_BIND_UNTANGLE_PUSH) readonly buffer UntanglePushBuf { ivec4 g_push[]; };
layout(std430, binding = GLC_BIND_UNTANGLE_COUNTS) buffer UntangleCountsBuf { uint g_untangleCounts[]; };

uniform uint u_nodeCount;
uniform float u_pushScale; // fixed-point units per unit of push
uniform float u_step;      // m

void main() {
    uint i = globalIndex();
    if (i >= u_nodeCount) return;
    ivec4 q = g_push[i];
    if (q.xyz == ivec3(0)) return;
    vec3 d = vec3(q.xyz) / u_pushScale;
    g_predicted[i].xyz += u_step * d / max(1.0, length(d));
    atomicAdd(g_untangleCounts[0], 1u);
}
