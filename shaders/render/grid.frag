#version 430 core
// Ground grid: a light floor with anti-aliased minor and major lines (widths from the screen-space
// derivatives of the grid coordinate), receiving the key light's shadows, fading into the
// background towards the edge of its square.

in vec3 v_world;
out vec4 o_colour;

uniform vec3 u_centre;
uniform float u_halfSize;  // m
uniform float u_spacing;   // m between minor lines; major lines every 5
uniform vec3 u_background;
uniform mat4 u_shadowMatrix;
uniform sampler2DShadow u_shadowMap;
uniform float u_shadowTexel;

// 1 on a line one pixel wide (times `width`), 0 away from it.
float lineCoverage(vec2 coord, float width) {
    vec2 w = max(fwidth(coord), vec2(1e-6));
    vec2 d = abs(fract(coord - 0.5) - 0.5) / (w * width);
    // Lines closer together than a few pixels fade out instead of turning into moire.
    float dense = 1.0 - smoothstep(0.25, 0.5, max(w.x, w.y));
    return (1.0 - min(min(d.x, d.y), 1.0)) * dense;
}

float keyVisibility(vec3 world) {
    vec4 s = u_shadowMatrix * vec4(world, 1.0);
    if (any(lessThan(s.xyz, vec3(0.0))) || any(greaterThan(s.xyz, vec3(1.0)))) return 1.0;
    float lit = 0.0;
    for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx)
            lit += texture(u_shadowMap, vec3(s.xy + vec2(dx, dy) * u_shadowTexel, s.z));
    return lit / 25.0;
}

void main() {
    vec2 coord = (v_world.xz - u_centre.xz) / u_spacing;
    float minor = lineCoverage(coord, 1.0);
    float major = lineCoverage(coord / 5.0, 1.6);
    vec3 colour = vec3(0.93);
    colour = mix(colour, vec3(0.78), minor);
    colour = mix(colour, vec3(0.58), major);
    colour *= 0.62 + 0.38 * keyVisibility(v_world);
    float r = length(v_world.xz - u_centre.xz) / u_halfSize;
    float fade = 1.0 - smoothstep(0.45, 1.0, r);
    o_colour = vec4(mix(u_background, colour, fade), 1.0);
}
