#version 430 core
// Masked broad phase, step 1 (the paper's scheme, seeds/002 Alg. 2): one invocation per leaf-box
// pair (i <= j) over the upper triangle of the boxes x boxes grid, in 2D tiles the host walks.
// Writes mask[i * boxes + j] = mask[j * boxes + i] = 1 where the boxes' objects may collide and
// the boxes overlap, else 0. Next: masked_face_pairs.comp (and the benchmark's fused reference,
// shaders/bench/paper_masked_tri_tri.comp).
#include "common/layout.glsl"
#include "common/collision.glsl"

layout(local_size_x = GLC_BOX_PAIR_TILE, local_size_y = GLC_BOX_PAIR_TILE) in;

layout(std430, binding = GLC_BIND_BOXES) readonly buffer BoxesBuf { GpuBox g_boxes[]; };
layout(std430, binding = GLC_BIND_BOX_MASK) writeonly buffer BoxMaskBuf { uint g_boxMask[]; };

uniform uint u_pairRules;      // GLC_RULE_* bits
uniform uint u_boxCount;       // objects * boxesPerObject
uniform uint u_boxesPerObject; // 8^depth; object of box b = b / u_boxesPerObject
uniform uint u_tileOriginX;    // first box j (x) of this dispatch
uniform uint u_tileOriginY;    // first box i (y) of this dispatch

void main() {
    uint j = u_tileOriginX + gl_GlobalInvocationID.x;
    uint i = u_tileOriginY + gl_GlobalInvocationID.y;
    if (i >= u_boxCount || j >= u_boxCount || j < i) return;
    bool mayCollide = objectsMayCollide(i / u_boxesPerObject, j / u_boxesPerObject, u_pairRules) &&
                      (i != j || (u_pairRules & GLC_RULE_SELF) != 0u);
    bool hit = mayCollide && boxesOverlap(g_boxes[i].lo.xyz, g_boxes[i].hi.xyz, g_boxes[j].lo.xyz, g_boxes[j].hi.xyz);
    g_boxMask[i * u_boxCount + j] = hit ? 1u : 0u;
    g_boxMask[j * u_boxCount + i] = hit ? 1u : 0u;
}
