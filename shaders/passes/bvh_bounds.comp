#version 430 core
// BvhBuild, step 1: the bounds of the face centroids, which the Morton codes quantise. Each work
// group reduces its faces' centroids in shared memory, then one invocation folds the group's
// box into g_bounds with atomicMin/atomicMax on order-preserving uints (bvh.glsl): min and max
// are exact, so the bounds do not depend on the order of the groups. The host sets g_bounds to
// the empty box before the dispatch.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl"
#include "common/face_nodes.glsl"
#include "common/bvh.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_BVH_BOUNDS) buffer BvhBoundsBuf { uvec4 g_bounds[2]; };

#include "common/bvh_centroid.glsl"

uniform uint u_faceCount;

shared vec3 s_lo[GLC_WORKGROUP_SIZE];
shared vec3 s_hi[GLC_WORKGROUP_SIZE];

void main() {
    uint f = globalIndex();
    uint t = gl_LocalInvocationID.x;
    vec3 inf = vec3(uintBitsToFloat(0x7f800000u));
    vec3 c = f < u_faceCount ? faceCentroid(f) : inf;
    s_lo[t] = f < u_faceCount ? c : inf;
    s_hi[t] = f < u_faceCount ? c : -inf;
    for (uint stride = uint(GLC_WORKGROUP_SIZE / 2); stride > 0u; stride >>= 1u) {
        memoryBarrierShared();
        barrier();
        if (t < stride) {
            s_lo[t] = min(s_lo[t], s_lo[t + stride]);
            s_hi[t] = max(s_hi[t], s_hi[t + stride]);
        }
    }
    if (t == 0u && s_lo[0].x <= s_hi[0].x) {
        atomicMin(g_bounds[0].x, orderedBits(s_lo[0].x));
        atomicMin(g_bounds[0].y, orderedBits(s_lo[0].y));
        atomicMin(g_bounds[0].z, orderedBits(s_lo[0].z));
        atomicMax(g_bounds[1].x, orderedBits(s_hi[0].x));
        atomicMax(g_bounds[1].y, orderedBits(s_hi[0].y));
        atomicMax(g_bounds[1].z, orderedBits(s_hi[0].z));
    }
}
