#version 430 core
// Surfaces and shadow-map depth, drawn straight from the engine's position buffer: one vec4 per
// node (xyz in metres, w the inverse mass, unused here), indexed by the engine's face buffer.
// Also the vertex stage of the shadow pass (u_viewProjection = the light's matrix).

layout(location = 0) in vec4 a_position;

uniform mat4 u_viewProjection;

out vec3 v_world;

void main() {
    v_world = a_position.xyz;
    gl_Position = u_viewProjection * vec4(a_position.xyz, 1.0);
}
