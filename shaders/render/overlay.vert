#version 430 core
// Overlays drawn over the surfaces in one colour each (the viewer's toggles): the wireframe (the
// engine's faces again, as lines), pinned nodes (the position buffer as points; a node with
// inverse mass w > 0 is moved outside the clip volume, so only pinned ones, w = 0, are seen) and a
// segment between two points given as uniforms (u_mode 2: gl_VertexID 0 and 1, no vertex buffer).

layout(location = 0) in vec4 a_position;

uniform mat4 u_viewProjection;
uniform uint u_mode; // 0: the engine's positions; 1: only pinned nodes; 2: the segment u_a - u_b
uniform vec3 u_a;
uniform vec3 u_b;
uniform float u_pointSize; // pixels

void main() {
    gl_PointSize = u_pointSize;
    if (u_mode == 2u) {
        gl_Position = u_viewProjection * vec4(gl_VertexID == 0 ? u_a : u_b, 1.0);
        return;
    }
    gl_Position = u_viewProjection * vec4(a_position.xyz, 1.0);
    if (u_mode == 1u && a_position.w > 0.0) gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // clipped away
}
