#version 430 core
// Octree broad phase, step 1 of BBCollision (seeds/002, Alg. 2, Fig. 7): one invocation per
// leaf-box pair (i <= j) over the upper triangle of the boxes x boxes grid, in 2D tiles the host
// walks (u_tileOriginX/Y). A pair whose objects may collide (i == j only with self-collisions) and
// whose boxes overlap is appended to the box-pair list. Next: octree_expand.comp.
// CPU twin: cpu::twinCandidates (the broad phase's output, brute force over all pairs).
#include "common/layout.glsl"
#include "common/collision.glsl"
#include "common/lists.glsl"

layout(local_size_x = GLC_BOX_PAIR_TILE, local_size_y = GLC_BOX_PAIR_TILE) in;

layout(std430, binding = GLC_BIND_BOXES) readonly buffer BoxesBuf { GpuBox g_boxes[]; };
layout(std430, binding = GLC_BIND_BOX_PAIRS) writeonly buffer BoxPairsBuf { uvec2 g_boxPairs[]; };

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
    if (mayCollide && boxesOverlap(g_boxes[i].lo.xyz, g_boxes[i].hi.xyz, g_boxes[j].lo.xyz, g_boxes[j].hi.xyz))
        GLC_APPEND(GLC_LIST_BOX_PAIRS, g_boxPairs, uvec2(i, j))
}
