#version 430 core
// TriTriQueryExact — the exact half of a robust TriTriQuery batch: one invocation per pair the
// filtered pass left undecided (the list at GLC_BIND_UNDECIDED, its length in stats[1]), decided by
// glcTriTriExact of common/tri_tri_robust.glsl. The host reads the count back and dispatches that
// many invocations (passes/tri_tri_query_pass.cpp); a pair it could not finish is counted in
// stats[2], and the host throws instead of answering.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_QUERY_TRIANGLES) readonly buffer QueryTrianglesBuf { float g_queryTriangles[]; };
layout(std430, binding = GLC_BIND_QUERY_RESULTS) writeonly buffer QueryResultsBuf { uint g_queryResults[]; };
layout(std430, binding = GLC_BIND_QUERY_STATS) buffer QueryStatsBuf { uint g_queryStats[]; };
layout(std430, binding = GLC_BIND_UNDECIDED) readonly buffer UndecidedBuf { uint g_undecided[]; };

#include "common/tri_tri_robust.glsl"

vec3 corner(uint base, uint k) {
    uint o = base + 3u * k;
    return vec3(g_queryTriangles[o], g_queryTriangles[o + 1u], g_queryTriangles[o + 2u]);
}

void main() {
    uint slot = globalIndex();
    if (slot >= g_queryStats[1]) return;
    uint i = g_undecided[slot];
    uint base = 18u * i;
    bool hit = glcTriTriExact(corner(base, 0u), corner(base, 1u), corner(base, 2u), corner(base, 3u),
                              corner(base, 4u), corner(base, 5u));
    g_queryResults[i] = hit ? 1u : 0u;
    if (glcExactEvaluations != 0u) atomicAdd(g_queryStats[0], glcExactEvaluations);
    if (glcExactFailed) atomicAdd(g_queryStats[2], 1u); // no answer: the host throws
}
