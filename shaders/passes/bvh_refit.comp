#version 430 core
// glcollide-features: GLC_SWEPT
// BvhRefit: every node's box from the current positions, bottom-up (Karras 2012, section 4):
// invocation i writes leaf i's inflated face box, then climbs. At each parent the first of the
// two children to arrive stops (atomicAdd on the parent's visit counter returns 0); the second
// knows both child boxes are written, writes their union and climbs on. Memory ordering: the box
// buffer is coherent, and each invocation issues memoryBarrierBuffer() after writing a box and
// before the counter (its box is visible before the counter says so), and again after the
// counter before reading the sibling's box. The second arrival zeroes the counter for the next
// refit. min and max are exact: a refit gives the same boxes as a rebuild on the same positions.
// CPU twin: cpu::twinRefit.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl"
#include "common/face_nodes.glsl"
#include "common/collision.glsl"
#include "common/bvh.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_BVH_BOXES) coherent buffer BvhBoxesBuf { GpuBox g_boxes[]; };
layout(std430, binding = GLC_BIND_BVH_LINKS) readonly buffer BvhLinksBuf { uvec4 g_links[]; };
layout(std430, binding = GLC_BIND_BVH_VISITS) coherent buffer BvhVisitsBuf { uint g_visits[]; };
#include "common/face_bounds.glsl"

uniform uint u_faceCount;
uniform float u_halfThickness; // m: float(0.5 * thickness), as model::halfThicknessFloat

void main() {
    uint i = globalIndex();
    if (i >= u_faceCount) return;
    uint node = bvhLeafNode(i, u_faceCount);
    uvec3 f = faceNodes(g_links[node].x);
    vec3 lo, hi;
    faceBoxOfNodes(f, u_halfThickness, lo, hi);
    g_boxes[node].lo = vec4(lo, 0.0);
    g_boxes[node].hi = vec4(hi, 0.0);
    uint parent = g_links[node].z;
    while (parent != GLC_BVH_NONE) {
        memoryBarrierBuffer();
        if (atomicAdd(g_visits[parent], 1u) == 0u) return; // the sibling's invocation goes on
        memoryBarrierBuffer();
        uvec4 children = g_links[parent];
        g_boxes[parent].lo = min(g_boxes[children.x].lo, g_boxes[children.y].lo);
        g_boxes[parent].hi = max(g_boxes[children.x].hi, g_boxes[children.y].hi);
        g_visits[parent] = 0u;
        parent = children.z;
    }
}
