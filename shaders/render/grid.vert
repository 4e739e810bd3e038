#version 430 core
// The ground grid: one square in the plane y = u_centre.y, made from gl_VertexID (a 4-vertex
// triangle strip, no vertex buffer).

uniform mat4 u_viewProjection;
uniform vec3 u_centre;
uniform float u_halfSize; // m

out vec3 v_world;

void main() {
    vec2 corner = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
    v_world = u_centre + vec3(corner.x, 0.0, corner.y) * u_halfSize;
    gl_Position = u_viewProjection * vec4(v_world, 1.0);
}
