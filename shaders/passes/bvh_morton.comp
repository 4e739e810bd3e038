#version 430 core
// BvhBuild, step 2: the 30-bit Morton code of each face's centroid as the sort key (10 bits per
// axis, x in the highest bit of each triple), the face index as its value. The grid is a cube
// over the centroid bounds: every axis is scaled by the largest extent, so a thin axis (a folded
// cloth's layers) does not get as many top-level splits as the wide ones. Scaling each axis to
// its own extent made the tree split layers that overlap near the root: 2.9x the traversal's node
// visits on a 3-layer folded cloth of 1M faces (CPU twin, decision 0017). Equal codes
// keep their index order (the sort is stable) and the hierarchy breaks their ties by index
// (Karras 2012). CPU twin: cpu::mortonCode.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl"
#include "common/face_nodes.glsl"
#include "common/bvh.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_BVH_BOUNDS) readonly buffer BvhBoundsBuf { uvec4 g_bounds[2]; };
layout(std430, binding = GLC_BIND_SORT_KEYS_OUT) writeonly buffer SortKeysOutBuf { uint g_keys[]; };
layout(std430, binding = GLC_BIND_SORT_VALUES_OUT) writeonly buffer SortValuesOutBuf { uint g_values[]; };

#include "common/bvh_centroid.glsl"

uniform uint u_faceCount;

// The 10 low bits of v spread to every third bit (bit k -> bit 3k).
uint spreadBits(uint v) {
    v &= 0x3ffu;
    v = (v | (v << 16u)) & 0x030000ffu;
    v = (v | (v << 8u)) & 0x0300f00fu;
    v = (v | (v << 4u)) & 0x030c30c3u;
    v = (v | (v << 2u)) & 0x09249249u;
    return v;
}

void main() {
    uint f = globalIndex();
    if (f >= u_faceCount) return;
    vec3 lo = vec3(orderedFloat(g_bounds[0].x), orderedFloat(g_bounds[0].y), orderedFloat(g_bounds[0].z));
    vec3 hi = vec3(orderedFloat(g_bounds[1].x), orderedFloat(g_bounds[1].y), orderedFloat(g_bounds[1].z));
    vec3 extent = hi - lo;
    float largest = max(max(extent.x, extent.y), extent.z);
    float scale = largest > 0.0 ? 1024.0 / largest : 0.0;
    // clamp: a centroid rounded past the bounds, or a non-finite one, still gets a valid code.
    uvec3 q = uvec3(clamp((faceCentroid(f) - lo) * scale, vec3(0.0), vec3(1023.0)));
    g_keys[f] = (spreadBits(q.x) << 2u) | (spreadBits(q.y) << 1u) | spreadBits(q.z);
    g_values[f] = f;
}
