#version 430 core
// Flat, two-sided shading of the engine's surfaces: the face normal comes from the screen-space
// derivatives of the world position (exact for a planar triangle), turned towards the viewer.
// The face's object picks its colour; faces the narrow phase reported as intersecting are drawn
// in the highlight colour. gl_PrimitiveID is the global face index (one draw of all faces).

in vec3 v_world;
out vec4 o_colour;

// Per face: bits 0-30 object index, bit 31 set when the face intersects another face.
layout(std430, binding = 0) readonly buffer FaceStyleBuf {
    uint g_faceStyle[];
};

#define PALETTE_SIZE 10
#define HIGHLIGHT_BIT 0x80000000u

uniform vec3 u_palette[PALETTE_SIZE];
uniform vec3 u_highlight;
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
    vec3 n = normalize(cross(dFdx(v_world), dFdy(v_world)));
    vec3 v = normalize(u_eye - v_world);
    if (dot(n, v) < 0.0) n = -n;

    uint style = g_faceStyle[gl_PrimitiveID];
    bool hit = (style & HIGHLIGHT_BIT) != 0u;
    vec3 base = hit ? u_highlight : u_palette[(style & ~HIGHLIGHT_BIT) % uint(PALETTE_SIZE)];

    float key = max(dot(n, u_keyDir), 0.0) * keyVisibility(v_world, n);
    float fill = max(dot(n, u_fillDir), 0.0);
    float sky = 0.5 + 0.5 * n.y;
    float spec = pow(max(dot(n, normalize(u_keyDir + v)), 0.0), 48.0) * (key > 0.0 ? 1.0 : 0.0);
    vec3 colour = base * (0.20 + 0.14 * sky + 0.62 * key + 0.16 * fill) + vec3(0.10 * spec);
    // Intersecting faces stay saturated in shadow and on the dark side.
    if (hit) colour = mix(colour, u_highlight, 0.55);
    o_colour = vec4(min(colour, vec3(1.0)), 1.0);
}
