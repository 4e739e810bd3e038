#version 430 core
// RadialWinding — radial view-based culling's observer check (decision 0025, "The winding
// number"; docs/culling.md, "Observer check"): the theorem needs each observed closed surface (real
// and ghost faces) to wind exactly once around its observer at the start of the substep (a segment
// observer: around its first end; no face touches the segment in a substep that frees a face, so
// every point of it is wound around as often, decision 0025 "Segment observers"). One
// invocation per classified face: the ray from the observer at x0 along GLC_RADIAL_RAY crosses the
// face (as the classification orients it) leaving through its front (+1), its back (-1) or not at
// all, by certified signs (glcRadialRayCrossing, common/radial_sign.glsl); the crossings of a
// surface sum to its winding number (integer atomics: the sum does not depend on the order). A
// crossing that cannot be proven (the ray through an edge or a vertex, the observer on a face's
// plane) marks the surface undecided. RadialFree frees nothing of a surface whose count is not 1
// or that is undecided. This replaces checking that the surface is embedded (a real face crossing a
// ghost face need not change the winding number, and then the theorem still holds: such a face is
// never free). CPU twin: cpu::radialWindingNumbers.
#include "common/layout.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/radial_sign.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_start[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_end[]; }; // unused here
layout(std430, binding = GLC_BIND_RADIAL_OBSERVERS) readonly buffer RadialObserversBuf { vec4 g_observers[]; };
layout(std430, binding = GLC_BIND_RADIAL_FACE_OBSERVER) readonly buffer RadialFaceObserverBuf { uint g_faceObserver[]; };
layout(std430, binding = GLC_BIND_RADIAL_WINDING) buffer RadialWindingBuf { uint g_winding[]; };

#include "common/radial_ghost.glsl"

uniform uint u_faceCount; // classified faces: real, then ghost

void main() {
    uint face = globalIndex();
    if (face >= u_faceCount) return;
    uint observer = g_faceObserver[face];
    if (observer == GLC_RADIAL_NO_OBSERVER) return;
    uvec3 n = glcRadialFaceNodes(face);
    vec3 p0 = glcRadialStart(n.x), p1 = glcRadialStart(n.y), p2 = glcRadialStart(n.z);
    if (g_observers[2u * observer].w < 0.0) { // an inward surface, turned round as RadialClassify does
        vec3 t = p1;
        p1 = p2;
        p2 = t;
    }
    int crossing = glcRadialRayCrossing(p0, p1, p2, g_observers[2u * observer].xyz, GLC_RADIAL_RAY);
    if (crossing == GLC_RADIAL_RAY_UNDECIDED)
        atomicOr(g_winding[2u * observer + 1u], 1u);
    else if (crossing != 0)
        atomicAdd(g_winding[2u * observer], crossing > 0 ? 1u : 0xffffffffu); // two's complement sum
}
