#version 430 core
// glcollide-features: GLC_SWEPT
// Masked broad phase, step 2 (the paper's scheme, seeds/002 Alg. 3 line 9): one invocation per
// face pair f < g over the upper triangle of the faces x faces grid, in 2D tiles the host walks; a
// pair whose leaf boxes' mask entry (box_mask.comp) is 0 returns at once, the rest are appended to
// the candidate list as (f, g) when valid with overlapping face boxes. Still O(faces^2)
// invocations: the paper's experiment, kept comparable. CPU twin: cpu::twinCandidates.
#include "common/layout.glsl"
#include "common/collision.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_FACE_PAIR_TILE, local_size_y = GLC_FACE_PAIR_TILE) in;

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_FACE_PAIRS) writeonly buffer FacePairsBuf { uvec2 g_facePairs[]; };
layout(std430, binding = GLC_BIND_BOX_MASK) readonly buffer BoxMaskBuf { uint g_boxMask[]; };

#include "common/face_pair_candidate.glsl"

uniform uint u_faceCount;
uniform uint u_boxCount;
uniform uint u_tileOriginX; // first face g (x) of this dispatch
uniform uint u_tileOriginY; // first face f (y) of this dispatch

void main() {
    uint g = u_tileOriginX + gl_GlobalInvocationID.x;
    uint f = u_tileOriginY + gl_GlobalInvocationID.y;
    if (f >= u_faceCount || g >= u_faceCount || g <= f) return;
    if (g_boxMask[g_faceInfo[f].box * u_boxCount + g_faceInfo[g].box] == 0u) return;
    if (isCandidatePair(f, g)) GLC_APPEND(GLC_LIST_CANDIDATES, g_facePairs, uvec2(f, g))
}
