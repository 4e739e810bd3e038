#version 430 core
// RadialHostCheck — whether the host moved nodes since the last substep (decision 0025, "The
// premise"): radial culling relies on a start that is intersection-free, which the engine knows
// only for the states its own substeps made. After a substep's commit the positions equal the
// predicted end positions; a frame's first substep starts with this check, before NodePredict
// overwrites them. One invocation per node; any difference (bits, so NaN or -0 count too) sets
// the flag. Only 1 is ever written, so the order does not matter.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_predicted[]; };
layout(std430, binding = GLC_BIND_RADIAL_MOVED) buffer RadialMovedBuf { uint g_moved; };

uniform uint u_nodeCount;

void main() {
    uint i = globalIndex();
    if (i >= u_nodeCount) return;
    if (any(notEqual(floatBitsToUint(g_positions[i].xyz), floatBitsToUint(g_predicted[i].xyz)))) g_moved = 1u;
}
