#version 430 core
// RadialClassify — radial view-based culling's triangle classification (issue 24, docs/culling.md,
// "Classification"): one invocation per face. A face is *positive* when glcRadialPositive proves
// phi(t) = n(t) . (p0(t) - q(t)) > 0 over the whole substep for its observer q, every point moving
// linearly from x0 (the positions) to x1 (the predicted positions). The proof is a certified float
// bound that holds whatever the compiler does (shaders/common/radial_sign.glsl); not proven means
// "may collide", never "negative". Output: bit f % 32 of word f / 32 of GLC_BIND_RADIAL_POSITIVE,
// set by atomicOr (the host clears the mask first): the result does not depend on the order.
// A face without an observer (GLC_RADIAL_NO_OBSERVER) is never positive.
#include "common/layout.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/radial_sign.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_start[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_end[]; };
layout(std430, binding = GLC_BIND_RADIAL_OBSERVERS) readonly buffer RadialObserversBuf { vec4 g_observers[]; };
layout(std430, binding = GLC_BIND_RADIAL_FACE_OBSERVER) readonly buffer RadialFaceObserverBuf { uint g_faceObserver[]; };
layout(std430, binding = GLC_BIND_RADIAL_POSITIVE) buffer RadialPositiveBuf { uint g_positive[]; };

uniform uint u_faceCount;

void main() {
    uint face = globalIndex();
    if (face >= u_faceCount) return;
    uint observer = g_faceObserver[face];
    if (observer == GLC_RADIAL_NO_OBSERVER) return;
    uvec3 n = faceNodes(face);
    if (glcRadialPositive(g_start[n.x].xyz, g_start[n.y].xyz, g_start[n.z].xyz, g_observers[2u * observer].xyz,
                          g_end[n.x].xyz, g_end[n.y].xyz, g_end[n.z].xyz, g_observers[2u * observer + 1u].xyz))
        atomicOr(g_positive[face / 32u], 1u << (face % 32u));
}
