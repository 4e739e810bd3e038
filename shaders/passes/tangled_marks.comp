#version 430 core
// TangledMarks — the intersection-free response's recovery from intersecting input (decision
// 0024): one invocation per entry of GLC_LIST_INTERSECTIONS (the face pairs whose closed
// triangles intersect at x0, TriTri's output; indirect dispatch from its count) marks both faces
// and their six nodes in GLC_BIND_TANGLED (nodes first, then faces). The safe step's CCD then
// leaves out the feature pairs between marked faces (feature_ccd.comp): a pair that already
// intersects would otherwise be "touching at t = 0" forever and freeze its objects, while the
// response pushes it apart. Writes only 1s (atomicOr): the marks do not depend on the order.
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_INTERSECTIONS) readonly buffer IntersectionsBuf { uvec2 g_intersections[]; };
layout(std430, binding = GLC_BIND_TANGLED) buffer TangledBuf { uint g_tangled[]; };

uniform uint u_nodeCount; // faces' marks start after the nodes'

void main() {
    uint i = globalIndex();
    if (i >= storedCount(GLC_LIST_INTERSECTIONS)) return;
    uvec2 pair = g_intersections[i];
    uvec3 a = faceNodes(pair.x), b = faceNodes(pair.y);
    for (uint k = 0u; k < 3u; ++k) {
        atomicOr(g_tangled[a[k]], 1u);
        atomicOr(g_tangled[b[k]], 1u);
    }
    atomicOr(g_tangled[u_nodeCount + pair.x], 1u);
    atomicOr(g_tangled[u_nodeCount + pair.y], 1u);
}
