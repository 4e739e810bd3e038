#version 430 core
// TriTriQuery, robust precision, first pass — answers a batch of independent triangle-triangle
// queries (glcollide query tritri, tests, benchmarks, the robust self-check). One invocation per
// pair: reads 18 floats (a0 a1 a2 b0 b1 b2, xyz each) and writes 1 when glcTriTriFiltered of
// common/tri_tri_robust.glsl certifies that the closed triangles intersect, 0 when it certifies
// they do not; a pair the filters cannot decide is appended to the undecided list (count in
// stats[1]), which tri_tri_query_exact.comp finishes exactly. CPU references:
// cpu::exactTrianglesIntersect (the oracle), shader::robustTrianglesIntersect (this code as C++).
#include "common/layout.glsl"
#include "common/tri_tri_robust.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_QUERY_TRIANGLES) readonly buffer QueryTrianglesBuf { float g_queryTriangles[]; };
layout(std430, binding = GLC_BIND_QUERY_RESULTS) writeonly buffer QueryResultsBuf { uint g_queryResults[]; };
// stats[0]: predicates evaluated exactly (the exact pass), stats[1]: undecided pairs, stats[2]:
// pairs the exact pass could not finish.
layout(std430, binding = GLC_BIND_QUERY_STATS) buffer QueryStatsBuf { uint g_queryStats[]; };
layout(std430, binding = GLC_BIND_UNDECIDED) writeonly buffer UndecidedBuf { uint g_undecided[]; };

uniform uint u_pairCount;

vec3 corner(uint base, uint k) {
    uint o = base + 3u * k;
    return vec3(g_queryTriangles[o], g_queryTriangles[o + 1u], g_queryTriangles[o + 2u]);
}

void main() {
    uint i = globalIndex();
    if (i >= u_pairCount) return;
    uint base = 18u * i;
    int answer = glcTriTriFiltered(corner(base, 0u), corner(base, 1u), corner(base, 2u),
                                   corner(base, 3u), corner(base, 4u), corner(base, 5u));
    if (answer == GLC_UNDECIDED) {
        g_undecided[atomicAdd(g_queryStats[1], 1u)] = i; // capacity: one per pair
        return;
    }
    g_queryResults[i] = uint(answer);
}
