#version 430 core
// Untangle, first kernel (decision 0024, "Deep intersections"; pass: src/passes/untangle.hpp) —
// one invocation per entry of GLC_LIST_INTERSECTIONS (face pairs whose triangles intersect at x0,
// TriTri's output; indirect dispatch from its count). The pair's intersection segment ends at two
// piercings, an edge of one triangle through the other (first triangle's edges 01, 12, 20 through
// the second, then the second's through the first; the first two found). At each, the edge is
// pushed relative to the face along R: the face's unit normal when its object is closed and not the
// edge's (normals point outwards, so the push brings the edge's inner end out; within one closed
// surface neither side of a self-intersection is known to be wrong), else the normal's sign that moves
// the piercing towards the segment's other end (a push δ·n moves it by −δ·e∥/(n·e) in the face's
// plane), which shortens the intersection contour (intersection contour minimisation). The unit
// relative push is split like a constraint projection: node i of (edge 0, edge 1, face 0, 1, 2)
// gets a_i·w_i/W·R, a = (1 − s, s, −b0, −b1, −b2), W = Σ a_j²·w_j, each part clamped to length 1
// and summed per node in fixed point (integer atomics: the sums do not depend on the order).
// A pair with fewer than two piercings (coplanar, touching) pushes nothing and is counted.
// Decisions here are float heuristics: they choose a direction, never whether a pair intersects
// (TriTri's exact answer) or whether a step is safe. Twin: cpu::untangleStep.
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_INTERSECTIONS) readonly buffer IntersectionsBuf { uvec2 g_intersections[]; };
layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_OBJECTS) readonly buffer ObjectsBuf { GpuObject g_objects[]; };
layout(std430, binding = GLC_BIND_UNTANGLE_PUSH) buffer UntanglePushBuf { ivec4 g_push[]; };
layout(std430, binding = GLC_BIND_UNTANGLE_COUNTS) buffer UntangleCountsBuf { uint g_untangleCounts[]; };

uniform float u_pushScale; // fixed-point units per unit of push

struct Piercing {
    bool edgeOfFirst; // the edge is the first face's
    uvec2 edge;       // its nodes
    float s;          // along the edge
    vec3 barycentric; // in the other face
    vec3 point;
};

// Edge (p0, p1) through triangle (t0, t1, t2): strictly across its plane, inside the closed triangle.
bool pierce(vec3 p0, vec3 p1, vec3 t0, vec3 t1, vec3 t2, inout Piercing out_) {
    vec3 n = cross(t1 - t0, t2 - t0);
    float d0 = dot(n, p0 - t0), d1 = dot(n, p1 - t0);
    if (!((d0 > 0.0 && d1 < 0.0) || (d0 < 0.0 && d1 > 0.0))) return false;
    float s = d0 / (d0 - d1);
    vec3 p = p0 + s * (p1 - p0);
    float nn = dot(n, n);
    vec3 b = vec3(dot(n, cross(t1 - p, t2 - p)), dot(n, cross(t2 - p, t0 - p)), dot(n, cross(t0 - p, t1 - p))) / nn;
    if (b.x < 0.0 || b.y < 0.0 || b.z < 0.0) return false;
    out_.s = s;
    out_.barycentric = b;
    out_.point = p;
    return true;
}

void addPart(uint node, vec3 part) {
    float l = length(part);
    if (l > 1.0) part *= 1.0 / l;
    ivec3 q = ivec3(round(part * u_pushScale));
    if (q.x != 0) atomicAdd(g_push[node].x, q.x);
    if (q.y != 0) atomicAdd(g_push[node].y, q.y);
    if (q.z != 0) atomicAdd(g_push[node].z, q.z);
}

void main() {
    uint i = globalIndex();
    if (i >= storedCount(GLC_LIST_INTERSECTIONS)) return;
    uvec2 pair = g_intersections[i];
    uvec3 fa = faceNodes(pair.x), fb = faceNodes(pair.y);
    vec3 a[3] = vec3[3](g_positions[fa.x].xyz, g_positions[fa.y].xyz, g_positions[fa.z].xyz);
    vec3 b[3] = vec3[3](g_positions[fb.x].xyz, g_positions[fb.y].xyz, g_positions[fb.z].xyz);
    Piercing ends[2];
    uint found = 0u;
    for (uint side = 0u; side < 2u && found < 2u; ++side) { // the first face's edges, then the second's
        bool first = side == 0u;
        for (uint e = 0u; e < 3u && found < 2u; ++e) {
            uint e1 = (e + 1u) % 3u;
            Piercing p;
            p.edgeOfFirst = first;
            bool hit = first ? pierce(a[e], a[e1], b[0], b[1], b[2], p) : pierce(b[e], b[e1], a[0], a[1], a[2], p);
            if (hit) {
                uvec3 owner = first ? fa : fb;
                p.edge = uvec2(owner[e], owner[e1]);
                ends[found++] = p;
            }
        }
    }
    if (found < 2u) {
        atomicAdd(g_untangleCounts[1], 1u);
        return;
    }
    for (uint k = 0u; k < 2u; ++k) {
        Piercing p = ends[k];
        vec3 q = ends[1u - k].point;
        uint faceId = p.edgeOfFirst ? pair.y : pair.x;
        uvec3 face = p.edgeOfFirst ? fb : fa;
        vec3 f0 = g_positions[face.x].xyz, f1 = g_positions[face.y].xyz, f2 = g_positions[face.z].xyz;
        vec3 n = normalize(cross(f1 - f0, f2 - f0));
        vec3 push;
        uint faceObject = g_faceInfo[faceId].object, edgeObject = g_faceInfo[p.edgeOfFirst ? pair.x : pair.y].object;
        if (faceObject != edgeObject && g_objects[faceObject].closed != 0u) {
            push = n;
        } else {
            vec3 e = g_positions[p.edge.y].xyz - g_positions[p.edge.x].xyz;
            float sigma = dot(q - p.point, e) * dot(n, e);
            push = sigma > 0.0 ? -n : sigma < 0.0 ? n : vec3(0.0);
        }
        uint node[5] = uint[5](p.edge.x, p.edge.y, face.x, face.y, face.z);
        float weight[5] = float[5](1.0 - p.s, p.s, -p.barycentric.x, -p.barycentric.y, -p.barycentric.z);
        float w = 0.0;
        for (uint j = 0u; j < 5u; ++j) w += weight[j] * weight[j] * g_positions[node[j]].w;
        if (!(w > 0.0)) continue; // all five pinned
        for (uint j = 0u; j < 5u; ++j) addPart(node[j], (weight[j] * g_positions[node[j]].w / w) * push);
    }
}
