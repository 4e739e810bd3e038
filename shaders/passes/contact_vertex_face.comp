#version 430 core
// glcollide-features: GLC_PREDICTED_FORCES
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
// Contacts within the thickness only (common/contact_pair.glsl).
const bool kContactCrossings = false;
#include "common/contact_pair.glsl"

layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_OBJECTS) readonly buffer ObjectsBuf { GpuObject g_objects[]; };
layout(std430, binding = GLC_BIND_VERTEX_FACE_PAIRS) readonly buffer VertexFacePairsBuf { uvec2 g_vertexFace[]; };

// Vertex `p` against face (a, b, c) of `faceObject` with ownership bits `faceOwned`
// (common/contact_pair.glsl). Returns 1 when a force was applied.
uint vertexFace(uint p, uvec3 face, uint faceOwned, GpuObject faceObject) {
    ContactPair c = vertexFaceContact(p, face, faceOwned, faceObject);
    return c.found ? respond(c.nodes, c.weights, c.normal, c.depth) : 0u;
}

void main() {
    uint i = globalIndex();
    if (i >= storedCount(GLC_LIST_VERTEX_FACE)) return;
    uvec2 item = g_vertexFace[i]; // (node, face)
    GpuFaceInfo info = g_faceInfo[item.y];
    if (vertexFace(item.x, faceNodes(item.y), info.owned, g_objects[info.object]) != 0u)
        atomicAdd(g_counters.stats[GLC_STAT_CONTACTS], 1u);
}
