#version 430 core
// Surfaces and shadow-map depth, drawn straight from the engine's position buffer: one vec4 per
// node (xyz in metres, w the inverse mass, unused here), indexed by the engine's face buffer.
// Also the vertex stage of the shadow pass (u_viewProjection = the light's matrix).
//
// Smooth shading's vertex normal, gathered here from the node's faces (the renderer's node -> face
// incidence, built once): the sum of their unnormalised normals (cross products, so each face
// counts by its area), read from the engine's own buffers bound as storage — nothing is copied
// and no float atomics are needed. Faces wind counter-clockwise seen from outside (front).

layout(location = 0) in vec4 a_position;

layout(std430, binding = 1) readonly buffer PositionsBuf { vec4 g_positions[]; };
layout(std430, binding = 2) readonly buffer FacesBuf { uint g_faces[]; };
layout(std430, binding = 3) readonly buffer NodeFaceOffsetsBuf { uint g_nodeFaceOffsets[]; };
layout(std430, binding = 4) readonly buffer NodeFaceListBuf { uint g_nodeFaceList[]; };

uniform mat4 u_viewProjection;
uniform uint u_smooth; // 1: gather the vertex normal (the shadow pass and flat shading skip it)

out vec3 v_world;
out vec3 v_normal;
out float v_crease; // 1 at a vertex on a crease (a box's edge): its faces are shaded flat

// A vertex is on a crease when one of its faces turns more than 25 degrees away from its normal
// (a box's edge: 45 degrees; a 320-face sphere's vertex: under 10).
const float kCreaseCosine = 0.906; // cos 25 degrees

vec3 faceNormal(uint f) {
    vec3 a = g_positions[g_faces[3u * f]].xyz, b = g_positions[g_faces[3u * f + 1u]].xyz,
         c = g_positions[g_faces[3u * f + 2u]].xyz;
    return cross(b - a, c - a);
}

void main() {
    v_world = a_position.xyz;
    v_normal = vec3(0.0);
    v_crease = 0.0;
    if (u_smooth != 0u) {
        uint node = uint(gl_VertexID), first = g_nodeFaceOffsets[node], end = g_nodeFaceOffsets[node + 1u];
        for (uint k = first; k < end; ++k) v_normal += faceNormal(g_nodeFaceList[k]);
        float len = length(v_normal);
        for (uint k = first; k < end && len > 0.0; ++k) {
            vec3 n = faceNormal(g_nodeFaceList[k]);
            float l = length(n);
            if (l > 0.0 && dot(n, v_normal) < kCreaseCosine * l * len) v_crease = 1.0;
        }
    }
    gl_Position = u_viewProjection * vec4(a_position.xyz, 1.0);
}
