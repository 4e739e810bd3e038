#version 430 core
// CcdFilter — the Ccd stage's first kernel when radial culling is on (docs/ccd.md, "In the
// engine"; decision 0025): one invocation per entry of GLC_LIST_VERTEX_FACE (u_edgeEdge = 0) or
// GLC_LIST_EDGE_EDGE (u_edgeEdge = 1); the pairs common/ccd_pair_selection.glsl leaves to test
// are appended (their index) to GLC_LIST_CCD_VERTEX_FACE_TESTS / _EDGE_EDGE_TESTS, over which
// feature_ccd.comp then runs. A subset of the feature list, so it never overflows on its own.
// The order of the entries does not matter: the CCD's results are minima.
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/contact_geometry.glsl"
#include "common/radial_cull.glsl"
#include "common/ccd_pair_selection.glsl"

layout(std430, binding = GLC_BIND_CCD_VERTEX_FACE_TESTS) writeonly buffer CcdVertexFaceTestsBuf { uint g_vertexFaceTests[]; };
layout(std430, binding = GLC_BIND_CCD_EDGE_EDGE_TESTS) writeonly buffer CcdEdgeEdgeTestsBuf { uint g_edgeEdgeTests[]; };

void main() {
    uint i = globalIndex();
    if (i >= storedCount(u_edgeEdge == 0u ? GLC_LIST_VERTEX_FACE : GLC_LIST_EDGE_EDGE)) return;
    if (selectCcdPair(i).action != GLC_CCD_TEST) return;
    if (u_edgeEdge == 0u) GLC_APPEND(GLC_LIST_CCD_VERTEX_FACE_TESTS, g_vertexFaceTests, i)
    else GLC_APPEND(GLC_LIST_CCD_EDGE_EDGE_TESTS, g_edgeEdgeTests, i)
}
