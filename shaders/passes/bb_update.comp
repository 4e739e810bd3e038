#version 430 core
// glcollide-features: GLC_SWEPT
// BBUpdate — refit the leaf boxes of the AABB-octree to the current node positions (seeds/002,
// Alg. 1 "BBUpdate Compute Shader"). Each leaf box is the union of the current vertices of the
// faces assigned to it (src/model/octree_layout.cpp), inflated by half the contact thickness; a box without
// faces is empty (lo = +inf > hi = -inf). One work group per box: its threads stride over the
// box's faces and a shared-memory min/max tree reduces them. min and max are exact, so the result
// does not depend on thread order (no float atomics). CPU twin: cpu::twinLeafBoxes.
#include "common/layout.glsl"

layout(local_size_x = GLC_BB_UPDATE_GROUP) in;

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_BOXES) writeonly buffer BoxesBuf { GpuBox g_boxes[]; };
layout(std430, binding = GLC_BIND_FACES) readonly buffer FacesBuf { uint g_faceIndices[]; };
layout(std430, binding = GLC_BIND_BOX_FACE_LIST) readonly buffer BoxFaceListBuf { uint g_boxFaceList[]; };
layout(std430, binding = GLC_BIND_BOX_FACE_OFFSETS) readonly buffer BoxFaceOffsetsBuf { uint g_boxFaceOffsets[]; };
#include "common/face_bounds.glsl"

uniform uint u_boxCount;
uniform float u_halfThickness; // m: float(0.5 * thickness), as model::halfThicknessFloat

shared vec3 s_lo[GLC_BB_UPDATE_GROUP];
shared vec3 s_hi[GLC_BB_UPDATE_GROUP];

void main() {
    // One group per box; more than 65535 boxes spill into y (ComputeProgram::dispatch1D).
    uint box = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
    if (box >= u_boxCount) return; // uniform in the group: no barrier is skipped by part of it
    uint t = gl_LocalInvocationID.x;
    vec3 lo = vec3(uintBitsToFloat(0x7f800000u)); // +inf
    vec3 hi = -lo;
    uint end = g_boxFaceOffsets[box + 1u];
    for (uint k = g_boxFaceOffsets[box] + t; k < end; k += uint(GLC_BB_UPDATE_GROUP)) {
        uint face = g_boxFaceList[k];
        for (uint c = 0u; c < 3u; ++c) addNodeBounds(g_faceIndices[3u * face + c], lo, hi);
    }
    s_lo[t] = lo;
    s_hi[t] = hi;
    for (uint stride = uint(GLC_BB_UPDATE_GROUP / 2); stride > 0u; stride >>= 1u) {
        memoryBarrierShared();
        barrier();
        if (t < stride) {
            s_lo[t] = min(s_lo[t], s_lo[t + stride]);
            s_hi[t] = max(s_hi[t], s_hi[t + stride]);
        }
    }
    if (t == 0u) {
        // inf - h = inf: an empty box stays empty.
        g_boxes[box].lo = vec4(s_lo[0] - vec3(u_halfThickness), 0.0);
        g_boxes[box].hi = vec4(s_hi[0] + vec3(u_halfThickness), 0.0);
    }
}
