// The contact term of the implicit solve (docs/integration.md, "Contacts in the implicit solve"):
// the records of implicit_contact_find.comp and the node → contact incidence list that
// implicit_contact_scan/scatter/sort.comp build from them, read by implicit_setup.comp and
// implicit_cg_direction.comp (compiled with GLC_IMPLICIT_CONTACTS). An incidence entry is
// 4·slot + corner: the record's slot (the vertex-face list's slot i, or u_edgeEdgeBase + the
// edge-edge list's slot) and which of its four nodes the row belongs to.
// Twin: cpu::implicitVelocityUpdate with an ImplicitContactSet.
#ifndef GLC_IMPLICIT_CONTACT_GLSL
#define GLC_IMPLICIT_CONTACT_GLSL

uniform float u_contactStiffness; // N/m: k of every contact (ContactParams::stiffness)

uint incidenceSlot(uint entry) {
    return entry >> 2u;
}

uint incidenceCorner(uint entry) {
    return entry & 3u;
}

// Whether corner k of record c has a row of its own: an active contact (force > 0), a node that
// moves (inverse mass > 0; a pinned node keeps Δv = 0) and a weight that is not 0 (a vertex-face
// contact at an edge or a corner of the face leaves the other corners out). Counting and
// scattering use this one rule, so the counts and the entries agree.
bool hasRow(GpuImplicitContact c, uint k, float inverseMass) {
    return c.normalForce.w > 0.0 && inverseMass > 0.0 && c.weights[k] != 0.0;
}

#endif
