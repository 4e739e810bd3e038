// Which feature pairs are contacts, and their geometry: the one definition that the penalty /
// Bridson response (contact_vertex_face.comp, contact_edge_edge.comp) and the implicit solve's
// contact term (implicit_contact_find.comp) share. A contact is four nodes with signed weights a
// (side A: +, summing to 1; side B: −, summing to −1), a unit normal u from B to A and a depth
// (how far inside the thickness h it is). Include after contact_geometry.glsl; the includer
// declares g_positions (vec4: xyz, w inverse mass), vec3 previousPosition(uint node) (the node at
// the start of the substep: the side it must be kept on), uniform float u_thickness and const bool
// kContactCrossings: whether a vertex or edge that went through a face or edge within the substep
// is a contact at any depth (the implicit solve's Newton steps and their line search, which
// linearise at a predicted end that may have gone through), or only within the thickness.
// Twin: src/cpu/contact_twin.cpp (contactGeometry).
#ifndef GLC_CONTACT_PAIR_GLSL
#define GLC_CONTACT_PAIR_GLSL

struct ContactPair {
    bool found;
    uvec4 nodes;
    vec4 weights;
    vec3 normal;
    float depth;
};

ContactPair noContact() {
    return ContactPair(false, uvec4(0u), vec4(0.0), vec3(0.0), 0.0);
}

// Whether vertex p's contact with the face (nodes `face`, ownership bits `owned`) at barycentric
// weights `w` (exact zeros from closestOnTriangle's vertex and edge regions) counts here: the
// interior always; the edge opposite vertex k (w[k] = 0) if the face owns it; vertex k (w[k] = 1)
// if the face owns it and p < that node — the same vertex-vertex contact is also found from the
// other side (that node against p's face), and counts once.
bool ownsClosestFeature(uint p, uvec3 face, vec3 w, uint owned) {
    uint zeros = uint(w.x == 0.0) + uint(w.y == 0.0) + uint(w.z == 0.0);
    if (zeros == 0u) return true;
    for (uint k = 0u; k < 3u; ++k) {
        if (zeros == 2u && w[k] == 1.0) return (owned & (GLC_OWN_VERTEX0 << k)) != 0u && p < face[k];
        if (zeros == 1u && w[k] == 0.0) return (owned & (GLC_OWN_EDGE01 << ((k + 1u) % 3u))) != 0u;
    }
    return true; // not reached: two zeros make the third weight 1
}

// Whether vertex p was strictly on the face's `side` (closed objects: the outside, +1) at the start
// of the substep (previousPosition), so that being now deeper than the thickness behind the face's
// plane, over the face, means it went through the face within the substep.
bool crossedFacePlane(uint p, uvec3 face, float side) {
    vec3 pa = previousPosition(face.x);
    float sPrev = dot(cross(previousPosition(face.y) - pa, previousPosition(face.z) - pa), previousPosition(p) - pa);
    return side != 0.0 && side * sPrev > 0.0;
}

// Whether vertex p is kept on the outside of a face of object `faceObject`: when that object is
// closed (outward normals) and p belongs to another object — p behind the face is inside that
// body. A vertex of the same closed object within the thickness behind its own face is not inside
// it: the body is thinner than the thickness there (a soft solid squashed flat, the two sides of a
// crushed fold; the state is intersection-free), and pushing it out would push it through the face,
// which the CCD forbids: the pair would stay deeper than the thickness for good (decision 0024,
// "Thin parts of closed objects"). It keeps the side it had, as on open surfaces.
bool keepsOutside(uint p, GpuObject faceObject) {
    return faceObject.closed != 0u && (p < faceObject.firstNode || p - faceObject.firstNode >= faceObject.nodeCount);
}

// A vertex exactly in the plane of another object's face, then and now (coplanar or coincident
// input: two sheets laid in one plane), has no side to keep; left without a contact such sheets
// never came apart. The side is then chosen the same way for every such pair: the object whose
// nodes come first (the scene's order) goes to the positive side of the face's normal turned towards
// GLC_COPLANAR_DIRECTION, the other object to the negative side, so the two sheets part (decision
// 0024, "Coplanar input"). 0 (no contact, as before) within one object, or for a normal
// perpendicular to that direction.
const vec3 GLC_COPLANAR_DIRECTION = vec3(0.5772, 0.5774, 0.5776);
float coplanarSide(uint p, vec3 n, GpuObject faceObject) {
    float lower = p < faceObject.firstNode ? 1.0 : (p - faceObject.firstNode >= faceObject.nodeCount ? -1.0 : 0.0);
    return lower * sign(dot(n, GLC_COPLANAR_DIRECTION));
}

// Vertex `p` against face (a, b, c) of object `faceObject` with ownership bits `faceOwned`
// (contact_vertex_face.comp). The vertex's side of the face: another object's vertex against a
// closed object (keepsOutside), the outside (outward normals); otherwise (cloth, which has no
// inside, or the body's own vertex), the side it was on at the start of the substep
// (previousPosition) — so a vertex that got through the sheet within the substep is pushed back,
// not on through. Near an edge or a corner of a closed object the distance decides, whatever the
// side: every edge there has a face on its other side, whose interior takes a vertex that went
// through; only an open surface's rim needs the side there.
ContactPair vertexFaceContact(uint p, uvec3 face, uint faceOwned, GpuObject faceObject) {
    bool closed = faceObject.closed != 0u;
    vec3 x = g_positions[p].xyz;
    vec3 xa = g_positions[face.x].xyz, xb = g_positions[face.y].xyz, xc = g_positions[face.z].xyz;
    vec3 n = cross(xb - xa, xc - xa);
    float area2 = length(n);
    if (!(area2 > 0.0)) return noContact(); // zero-area face: its edges still take part in edge-edge
    n /= area2;
    vec3 w = closestOnTriangle(x, xa, xb, xc);
    if (!ownsClosestFeature(p, face, w, faceOwned)) return noContact();
    vec3 diff = x - (w.x * xa + w.y * xb + w.z * xc);
    float d = length(diff);
    float s = dot(n, x - xa);
    float side = 1.0;
    if (!keepsOutside(p, faceObject)) {
        vec3 pa = previousPosition(face.x);
        float sPrev = dot(cross(previousPosition(face.y) - pa, previousPosition(face.z) - pa),
                          previousPosition(p) - pa);
        side = sPrev > 0.0 ? 1.0 : (sPrev < 0.0 ? -1.0 : sign(s));
        if (side == 0.0) side = coplanarSide(p, n, faceObject);
    }
    // Signed distance on the vertex's side (< 0: on the wrong side); 0 when it was and is in the
    // face's plane (no side to keep: only the distance rule below acts).
    float sideDistance = side * s;
    bool inside = w.x > 0.0 && w.y > 0.0 && w.z > 0.0;
    ContactPair c = ContactPair(true, uvec4(p, face), vec4(1.0, -w), vec3(0.0), 0.0);
    if (kContactCrossings && inside && !(sideDistance > -u_thickness) && crossedFacePlane(p, face, side)) {
        c.normal = side * n; // went through the face, deeper than the thickness: back to its side
        c.depth = u_thickness - sideDistance;
    } else if (side != 0.0 && (inside || d == 0.0) && sideDistance < u_thickness && sideDistance > -u_thickness) {
        c.normal = side * n;
        c.depth = u_thickness - sideDistance;
    } else if (d < u_thickness && d > 0.0 && (side != 0.0 || !inside)) {
        // (Inside the face with no side the vertex is in its plane: d is the rounding of the closest
        // point, and diff / d a direction of rounding noise; no contact.)
        if (closed || sideDistance >= 0.0) {
            c.normal = diff / d;
            c.depth = u_thickness - d;
        } else { // near an edge or corner of an open face, but across its plane: back across
            c.normal = side * n;
            c.depth = u_thickness - sideDistance;
        }
    } else {
        return noContact();
    }
    return c;
}

// Edges p0p1 and q0q1 (contact_edge_edge.comp): closer than the thickness with both closest points
// inside their edges (an endpoint is a vertex: the vertex-face contacts have it). Edges that
// crossed within the substep (their closest-point offset points the other way than at its start)
// are pushed back, depth h + d (decision 0019); with kContactCrossings at any distance d.
ContactPair edgeEdgeContact(uint p0, uint p1, uint q0, uint q1) {
    vec3 x0 = g_positions[p0].xyz, x1 = g_positions[p1].xyz;
    vec3 y0 = g_positions[q0].xyz, y1 = g_positions[q1].xyz;
    vec2 st = closestSegmentParams(x0, x1, y0, y1);
    if (!(st.x > 0.0 && st.x < 1.0 && st.y > 0.0 && st.y < 1.0)) return noContact();
    vec3 diff = mix(x0, x1, st.x) - mix(y0, y1, st.y);
    float d = length(diff);
    vec3 diffPrev = mix(previousPosition(p0), previousPosition(p1), st.x) -
                    mix(previousPosition(q0), previousPosition(q1), st.y);
    bool crossed = dot(diffPrev, diff) < 0.0;
    if (!(d < u_thickness) && !(kContactCrossings && crossed)) return noContact();
    ContactPair c = ContactPair(true, uvec4(p0, p1, q0, q1), vec4(1.0 - st.x, st.x, st.y - 1.0, -st.y),
                                vec3(0.0), 0.0);
    if (d > 0.0 && dot(diffPrev, diff) >= 0.0) {
        c.normal = diff / d;
        c.depth = u_thickness - d;
    } else if (d > 0.0) { // crossed: back to the side of the start of the substep
        c.normal = -diff / d;
        c.depth = u_thickness + d;
    } else { // touching now (no direction): the direction they had
        float dPrev = length(diffPrev);
        if (!(dPrev > 0.0)) return noContact();
        c.normal = diffPrev / dPrev;
        c.depth = u_thickness;
    }
    return c;
}

#endif
