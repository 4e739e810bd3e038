#version 430 core
// Two-sided shading of the engine's surfaces, smooth (the vertex normals of surface.vert,
// interpolated; faces touching a crease stay flat) or flat (the face normal from the screen-space derivatives of the world position,
// exact for a planar triangle). The front side (faces wind counter-clockwise seen from outside)
// shows the object's colour, the back side (a cloth's underside, a body's inside) a paler one;
// the normal is turned to the side that is seen. Faces the narrow phase reported as intersecting
// are drawn in the highlight colour. gl_PrimitiveID is the global face index (one draw of all
// faces).

in vec3 v_world;
in vec3 v_normal;
in float v_crease;
out vec4 o_colour;

// Per face: bits 0-30 object index, bit 31 set when the face intersects another face.
layout(std430, binding = 0) readonly buffer FaceStyleBuf {
    uint g_faceStyle[];
};

#define PALETTE_SIZE 10
#define HIGHLIGHT_BIT 0x80000000u

uniform vec3 u_palette[PALETTE_SIZE];
uniform vec3 u_highlight;
uniform vec3 u_backTint;  // the back side's colour is the front's mixed halfway towards this
uniform uint u_smooth;    // 1: interpolated vertex normals; 0: flat
uniform vec3 u_eye;
uniform vec3 u_keyDir;  // unit vector towards the key light (casts the shadows)
uniform vec3 u_fillDir; // unit vector towards the fill light
uniform mat4 u_shadowMatrix; // world -> shadow map texture coordinates and depth, all in [0, 1]
uniform sampler2DShadow u_shadowMap;
uniform float u_shadowTexel;  // 1 / shadow map size
uniform float u_normalOffset; // m: shadow lookups start this far off the surface (no acne)

float keyVisibility(vec3 world, vec3 n) {
    vec4 s = u_shadowMatrix * vec4(world + n * u_normalOffset, 1.0);
    if (any(lessThan(s.xyz, vec3(0.0))) || any(greaterThan(s.xyz, vec3(1.0)))) return 1.0;
    float lit = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            lit += texture(u_shadowMap, vec3(s.xy + vec2(dx, dy) * u_shadowTexel, s.z));
    return lit / 9.0;
}

void main() {
    vec3 flat_ = normalize(cross(dFdx(v_world), dFdy(v_world)));
    vec3 v = normalize(u_eye - v_world);
    if (dot(flat_, v) < 0.0) flat_ = -flat_;
    vec3 n = flat_;
    // A face with a vertex on a crease (a box's edge) stays flat, so sharp bodies stay sharp and
    // curved cloth is smooth.
    if (u_smooth != 0u && v_crease == 0.0 && dot(v_normal, v_normal) > 0.0) {
        n = normalize(v_normal);
        if (!gl_FrontFacing) n = -n; // the seen side's normal
    }

    uint style = g_faceStyle[gl_PrimitiveID];
    bool hit = (style & HIGHLIGHT_BIT) != 0u;
    vec3 base = hit ? u_highlight : u_palette[(style & ~HIGHLIGHT_BIT) % uint(PALETTE_SIZE)];
    if (!hit && !gl_FrontFacing) base = mix(base, u_backTint, 0.5);

    float key = max(dot(n, u_keyDir), 0.0) * keyVisibility(v_world, n);
    float fill = max(dot(n, u_fillDir), 0.0);
    float sky = 0.5 + 0.5 * n.y;
    float spec = pow(max(dot(n, normalize(u_keyDir + v)), 0.0), 48.0) * (key > 0.0 ? 1.0 : 0.0);
    vec3 colour = base * (0.20 + 0.14 * sky + 0.62 * key + 0.16 * fill) + vec3(0.10 * spec);
    // Intersecting faces stay saturated in shadow and on the dark side.
    if (hit) colour = mix(colour, u_highlight, 0.55);
    o_colour = vec4(min(colour, vec3(1.0)), 1.0);
}
