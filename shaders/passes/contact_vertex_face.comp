#version 430 core
// ContactResponse, vertex-face — one invocation per entry (node p, face) of GLC_LIST_VERTEX_FACE
// (indirect dispatch from its count; the pairs come from FeaturePairs, feature_pairs.comp): within
// the thickness h, p is pushed away from its closest point on the face. A vertex whose projection
// lies inside the face and that is at most h on the wrong side of it is pushed back along the
// normal, so a shallow penetration is undone, not deepened: the wrong side of a closed object's
// face is below it (outward normals); of an open surface's face, the side the vertex was not on
// at the start of the substep (decision 0019).
// A vertex near an edge or a vertex of the other mesh is near every face around that feature:
// the contact counts only for the face that owns the closest feature (GLC_OWN_* bits), and a
// vertex-vertex contact only from its lower node, so a vertex meeting a vertex of valence 6 gets
// one contact, not twelve (the stiffness the substep rule assumes; six gave the soak scene's
// energy gain, docs/collisions.md). Force law and fixed-point sums: common/contact_force.glsl.
// Twin: cpu::contactForces.
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/contact_geometry.glsl"
#include "common/contact_force.glsl"

layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_OBJECTS) readonly buffer ObjectsBuf { GpuObject g_objects[]; };
layout(std430, binding = GLC_BIND_VERTEX_FACE_PAIRS) readonly buffer VertexFacePairsBuf { uvec2 g_vertexFace[]; };

// Whether vertex p's contact with the face (nodes `face`, ownership bits `owned`) at barycentric
// weights `w` (exact zeros from closestOnTriangle's vertex and edge regions) counts here: the
// interior always; the edge opposite vertex k (w[k] = 0) if the face owns it; vertex k (w[k] = 1)
// if the face owns it and p < that node — the same vertex-vertex contact is also found from the
// other side (that node against p's face), and counts once.
bool ownsClosestFeature(uint p, uvec3 face, vec3 w, uint owned) {
    uint zeros = uint(w.x == 0.0) + uint(w.y == 0.0) + uint(w.z == 0.0);
    if (zeros == 0u) return true;
    for (uint k = 0u; k < 3u; ++k) {
        if (zeros == 2u && w[k] == 1.0) return (owned & (GLC_OWN_VERTEX0 << k)) != 0u && p < face[k];
        if (zeros == 1u && w[k] == 0.0) return (owned & (GLC_OWN_EDGE01 << ((k + 1u) % 3u))) != 0u;
    }
    return true; // not reached: two zeros make the third weight 1
}

// Vertex `p` against face (a, b, c) with ownership bits `faceOwned`. Returns 1 when a force was applied.
// The vertex's side of the face: closed objects, the outside (outward normals); open surfaces
// (cloth, which has no inside), the side it was on at the start of the substep, from the previous
// positions x − dt·v (contact_force.glsl) — so a vertex that got through the sheet within the
// substep is pushed back, not on through. With dt = 0 the side is the current one.
uint vertexFace(uint p, uvec3 face, uint faceOwned, bool closed) {
    vec3 x = g_positions[p].xyz;
    vec3 xa = g_positions[face.x].xyz, xb = g_positions[face.y].xyz, xc = g_positions[face.z].xyz;
    vec3 n = cross(xb - xa, xc - xa);
    float area2 = length(n);
    if (!(area2 > 0.0)) return 0u; // zero-area face: its edges still take part in edge-edge
    n /= area2;
    vec3 w = closestOnTriangle(x, xa, xb, xc);
    if (!ownsClosestFeature(p, face, w, faceOwned)) return 0u;
    vec3 diff = x - (w.x * xa + w.y * xb + w.z * xc);
    float d = length(diff);
    float s = dot(n, x - xa);
    float side = 1.0;
    if (!closed) {
        vec3 pa = previousPosition(face.x);
        float sPrev = dot(cross(previousPosition(face.y) - pa, previousPosition(face.z) - pa),
                          previousPosition(p) - pa);
        side = sPrev > 0.0 ? 1.0 : (sPrev < 0.0 ? -1.0 : sign(s));
    }
    // Signed distance on the vertex's side (< 0: on the wrong side); 0 when it was and is in the
    // face's plane (no side to keep: only the distance rule below acts).
    float sideDistance = side * s;
    bool inside = w.x > 0.0 && w.y > 0.0 && w.z > 0.0;
    vec3 u;
    float depth;
    if (side != 0.0 && inside && sideDistance < u_thickness && sideDistance > -u_thickness) {
        u = side * n;
        depth = u_thickness - sideDistance;
    } else if (d < u_thickness && d > 0.0) {
        if (closed || sideDistance >= 0.0) {
            u = diff / d;
            depth = u_thickness - d;
        } else { // near an edge or corner of an open face, but across its plane: back across
            u = side * n;
            depth = u_thickness - sideDistance;
        }
    } else {
        return 0u;
    }
    return respond(uvec4(p, face), vec4(1.0, -w), u, depth);
}

void main() {
    uint i = globalIndex();
    if (i >= storedCount(GLC_LIST_VERTEX_FACE)) return;
    uvec2 item = g_vertexFace[i]; // (node, face)
    GpuFaceInfo info = g_faceInfo[item.y];
    bool closed = g_objects[info.object].closed != 0u;
    if (vertexFace(item.x, faceNodes(item.y), info.owned, closed) != 0u) atomicAdd(g_counters.stats[GLC_STAT_CONTACTS], 1u);
}
