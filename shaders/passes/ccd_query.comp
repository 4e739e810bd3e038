#version 430 core
// glcollide-features: GLC_CCD_EDGE_EDGE
// CcdQuery — answers a batch of independent continuous-collision queries (glcollide query ccd,
// tests, the CCD benchmark). One invocation per query: reads 25 floats (4 points xyz at t = 0, the
// same 4 at t = 1, then the minimum separation) and runs the conservative float CCD of
// common/ccd.glsl: glcVertexFaceCcd, or glcEdgeEdgeCcd when GLC_CCD_EDGE_EDGE is defined (one
// variant per kind, so the kind is a constant the compiler folds). Writes 3 uints: bit 0 "may
// collide", bit 1 "capped" (the budget ran out); the time of impact's bits; the boxes evaluated.
// CPU twin: the same functions compiled as C++ (cpu/ccd_library.hpp). Host: passes/ccd_query_pass.cpp.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_CCD_QUERIES) readonly buffer CcdQueriesBuf { float g_ccdQueries[]; };
layout(std430, binding = GLC_BIND_CCD_RESULTS) writeonly buffer CcdResultsBuf { uint g_ccdResults[]; };

uniform uint u_queryCount;
uniform uint u_budget; // boxes per query, >= 1 (the host keeps it within the device's loop limit)

#include "common/ccd.glsl"

vec3 queryPoint(uint base, uint k) {
    uint o = base + 3u * k;
    return vec3(g_ccdQueries[o], g_ccdQueries[o + 1u], g_ccdQueries[o + 2u]);
}

void main() {
    uint i = globalIndex();
    if (i >= u_queryCount) return;
    uint base = 25u * i;
    vec3 q0 = queryPoint(base, 0u), q1 = queryPoint(base, 1u), q2 = queryPoint(base, 2u), q3 = queryPoint(base, 3u);
    vec3 q4 = queryPoint(base, 4u), q5 = queryPoint(base, 5u), q6 = queryPoint(base, 6u), q7 = queryPoint(base, 7u);
    float minSeparation = g_ccdQueries[base + 24u];
    int budget = int(u_budget);
#ifdef GLC_CCD_EDGE_EDGE
    bool mayCollide = glcEdgeEdgeCcd(q0, q1, q2, q3, q4, q5, q6, q7, minSeparation, budget);
#else
    bool mayCollide = glcVertexFaceCcd(q0, q1, q2, q3, q4, q5, q6, q7, minSeparation, budget);
#endif
    g_ccdResults[3u * i] = (mayCollide ? 1u : 0u) | (glcCcdCapped ? 2u : 0u);
    g_ccdResults[3u * i + 1u] = floatBitsToUint(glcCcdToi);
    g_ccdResults[3u * i + 2u] = uint(glcCcdBoxes);
}
