// Deterministic energy sums shared by EnergyGuard (energy_guard.comp) and the Newton steps' line
// search (newton_line_search.comp): fixed-order trees for the float terms, exact 128-bit fixed
// point for the contacts' terms (their lists' order changes from run to run), and the terms both
// sum — a spring's elastic energy and a feature pair's penalty ½·k·depth² with their magnitude
// scales (EnergyGuardPass::resolutionFactor says how the scales bound the rounding).
// Include after local_size, index.glsl, contact_pair.glsl (so after g_positions and
// previousPosition), lists.glsl, face_nodes.glsl and the blocks g_springs, g_faceInfo, g_objects,
// g_vertexFace and g_edgeEdge.
#ifndef GLC_ENERGY_SUM_GLSL
#define GLC_ENERGY_SUM_GLSL

uniform float u_stiffness; // N/m: the contacts' penalty stiffness

shared vec4 s_sum[GLC_WORKGROUP_SIZE];
shared uvec4 s_exact[2 * GLC_WORKGROUP_SIZE];

// Exact unsigned 128-bit arithmetic in four 32-bit words (least significant first): addition is
// associative, so the sum of the contact terms does not depend on their order in the lists.
uvec4 add128(uvec4 a, uvec4 b) {
    uvec4 carry;
    uvec4 sum = uaddCarry(a, b, carry);
    uint c1;
    sum.y = uaddCarry(sum.y, carry.x, c1);
    carry.y += c1;
    sum.z = uaddCarry(sum.z, carry.y, c1);
    carry.z += c1;
    sum.w = sum.w + carry.z; // beyond 2⁶⁴ J: never reached
    return sum;
}

// A non-negative float as 128-bit fixed point in units of 2⁻⁶⁴: exact down to 2⁻⁶⁴ (the bits below
// are dropped: the same for every run), 0 for NaN, infinity, subnormals and negatives (none occur:
// the terms are energies and magnitudes).
uvec4 toFixed128(float value) {
    uint bits = floatBitsToUint(value);
    uint biased = (bits >> 23u) & 0xFFu;
    if ((bits >> 31u) != 0u || biased == 0u || biased == 0xFFu) return uvec4(0u);
    uint mantissa = (bits & 0x7FFFFFu) | 0x800000u; // value = mantissa · 2^(biased − 150)
    int shift = int(biased) - 150 + 64;              // bit position of the mantissa's lowest bit
    if (shift <= -24) return uvec4(0u);
    if (shift < 0) return uvec4(mantissa >> uint(-shift), 0u, 0u, 0u);
    if (shift > 104) return uvec4(0xFFFFFFFFu); // saturate: above 2⁶⁴ J
    uint word = uint(shift) / 32u, bit = uint(shift) % 32u;
    uint low = mantissa << bit, high = bit == 0u ? 0u : mantissa >> (32u - bit);
    uvec4 r = uvec4(0u);
    r[word] = low;
    if (word < 3u) r[word + 1u] = high;
    return r;
}

// The 128-bit fixed-point sum as a float (J): the same rounding for the same sum.
float fromFixed128(uvec4 v) {
    return ldexp(float(v.w), 32) + float(v.z) + ldexp(float(v.y), -32) + ldexp(float(v.x), -64);
}

// Exact fixed-order tree sum of two 128-bit values per invocation; invocation 0 gets the totals.
void groupExactTotal(inout uvec4 a, inout uvec4 b) {
    uint i = gl_LocalInvocationID.x;
    s_exact[2u * i] = a;
    s_exact[2u * i + 1u] = b;
    barrier();
    for (uint half_ = GLC_WORKGROUP_SIZE / 2u; half_ > 0u; half_ /= 2u) {
        if (i < half_) {
            s_exact[2u * i] = add128(s_exact[2u * i], s_exact[2u * (i + half_)]);
            s_exact[2u * i + 1u] = add128(s_exact[2u * i + 1u], s_exact[2u * (i + half_) + 1u]);
        }
        barrier();
    }
    a = s_exact[0];
    b = s_exact[1];
    barrier();
}

// Fixed-order tree sum of one vec4 per invocation; every invocation gets the group's total.
vec4 groupTotal(vec4 v) {
    uint i = gl_LocalInvocationID.x;
    s_sum[i] = v;
    barrier();
    for (uint half_ = GLC_WORKGROUP_SIZE / 2u; half_ > 0u; half_ /= 2u) {
        if (i < half_) s_sum[i] += s_sum[i + half_];
        barrier();
    }
    vec4 total = s_sum[0];
    barrier();
    return total;
}

// (½·k·(|xa − xb| − L)², its magnitude scale) of spring s.
vec2 springEnergy(GpuSpring spring) {
    float len = length(g_positions[spring.nodeA].xyz - g_positions[spring.nodeB].xyz);
    float stretch = len - spring.restLength;
    float e = 0.5 * spring.stiffness * stretch * stretch;
    // The rounding of len − L is relative to len + L, not to the stretch: the energy's error is
    // about k·|len − L|·(len + L)·ε.
    return vec2(e, e + spring.stiffness * abs(stretch) * (len + spring.restLength));
}

// (½·k·depth², its magnitude scale) of one contact.
vec2 contactEnergy(ContactPair c) {
    if (!c.found) return vec2(0.0);
    float e = 0.5 * u_stiffness * c.depth * c.depth;
    // The depth is a difference of coordinates: its rounding is relative to their size.
    float size = length(g_positions[c.nodes.x].xyz) + u_thickness;
    return vec2(e, e + u_stiffness * c.depth * size);
}

vec2 vertexFaceEnergy(uint k) {
    uvec2 item = g_vertexFace[k]; // (node, face)
    GpuFaceInfo info = g_faceInfo[item.y];
    return contactEnergy(vertexFaceContact(item.x, faceNodes(item.y), info.owned, g_objects[info.object]));
}

vec2 edgeEdgeEnergy(uint k) {
    uvec2 item = g_edgeEdge[k]; // (3*fa+e, 3*fb+g)
    uvec3 a = faceNodes(item.x / 3u), b = faceNodes(item.y / 3u);
    uint e = item.x % 3u, g = item.y % 3u;
    return contactEnergy(edgeEdgeContact(a[e], a[(e + 1u) % 3u], b[g], b[(g + 1u) % 3u]));
}

// The feature pairs' penalty energy and magnitude over the entries first, first + stride, … of
// both lists, summed exactly (the lists' order varies between runs).
void addContactEnergies(uint first, uint stride, inout uvec4 energy, inout uvec4 magnitude) {
    uint vertexFace = storedCount(GLC_LIST_VERTEX_FACE), edgeEdge = storedCount(GLC_LIST_EDGE_EDGE);
    for (uint k = first; k < vertexFace + edgeEdge; k += stride) {
        vec2 t = k < vertexFace ? vertexFaceEnergy(k) : edgeEdgeEnergy(k - vertexFace);
        energy = add128(energy, toFixed128(t.x));
        magnitude = add128(magnitude, toFixed128(t.y));
    }
}

#endif
