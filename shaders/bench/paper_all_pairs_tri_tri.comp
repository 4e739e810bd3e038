#version 430 core
// Benchmark reference: the paper's all-pairs TriTri, fused (common/paper_fused_tri_tri.glsl);
// run by src/benchkit/paper_fused_tri_tri.cpp, never by the engine.
#include "common/layout.glsl"
#include "common/paper_fused_tri_tri.glsl"

void main() {
    uint f, g;
    if (paperPair(f, g)) paperTestPair(f, g);
}
