#version 430 core
// Benchmark reference: the paper's masked TriTri, fused (common/paper_fused_tri_tri.glsl): a pair
// whose leaf boxes' mask entry (passes/box_mask.comp) is 0 returns at once (seeds/002 Alg. 3 line
// 9). Run by src/benchkit/paper_fused_tri_tri.cpp, never by the engine.
#include "common/layout.glsl"
#include "common/paper_fused_tri_tri.glsl"

layout(std430, binding = GLC_BIND_BOX_MASK) readonly buffer BoxMaskBuf { uint g_boxMask[]; };
uniform uint u_boxCount;

void main() {
    uint f, g;
    if (!paperPair(f, g)) return;
    if (g_boxMask[g_faceInfo[f].box * u_boxCount + g_faceInfo[g].box] == 0u) return;
    paperTestPair(f, g);
}
