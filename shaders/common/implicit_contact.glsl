// The contact term of the implicit solve (docs/integration.md, "Contacts in the implicit solve"):
// the records of implicit_contact_find.comp and the node → contact incidence list that
// implicit_contact_scan/scatter/sort.comp build from them, read by implicit_setup.comp and
// implicit_cg_direction.comp (compiled with GLC_IMPLICIT_CONTACTS). Only the feature pairs that are
// contacts get a record (an atomic append: record r); each record keeps the list slot of its pair
// (the vertex-face list's slot i, or u_edgeEdgeBase + the edge-edge list's slot), which names it
// for the sort. An incidence entry is 4·r + corner: the record and which of its four nodes the
// row belongs to.
// Words of GLC_BIND_IMPLICIT_CONTACTS: row offsets [0, nodes], the record count (u_contactCount),
// then 4 entries, 1 list slot and 12 record words per record of the capacity.
// Twin: cpu::implicitVelocityUpdate with an ImplicitContactSet.
#ifndef GLC_IMPLICIT_CONTACT_GLSL
#define GLC_IMPLICIT_CONTACT_GLSL

layout(std430, binding = GLC_BIND_IMPLICIT_CONTACTS) buffer ImplicitContactsBuf { uint g_contactData[]; };

uniform float u_contactStiffness; // N/m: k of every contact (ContactParams::stiffness)
uniform uint u_contactCount;      // word of the record count: nodes + 1
uniform uint u_contactEntries;    // word of the first incidence entry: nodes + 2
uniform uint u_contactSlots;      // word of the first record's list slot: entries + 4 · capacity
uniform uint u_contactRecords;    // word of the first record: slots + capacity

// Node i's row is entries [contactRowBegin(i), contactRowEnd(i)).
uint contactRowBegin(uint node) {
    return g_contactData[node];
}

uint contactRowEnd(uint node) {
    return g_contactData[node + 1u];
}

void setContactRowOffset(uint node, uint offset) {
    g_contactData[node] = offset;
}

uint contactEntry(uint e) {
    return g_contactData[u_contactEntries + e];
}

void setContactEntry(uint e, uint entry) {
    g_contactData[u_contactEntries + e] = entry;
}

GpuImplicitContact contactRecord(uint r) {
    uint w = u_contactRecords + 12u * r;
    GpuImplicitContact c;
    c.nodes = uvec4(g_contactData[w], g_contactData[w + 1u], g_contactData[w + 2u], g_contactData[w + 3u]);
    c.weights = uintBitsToFloat(uvec4(g_contactData[w + 4u], g_contactData[w + 5u], g_contactData[w + 6u],
                                      g_contactData[w + 7u]));
    c.normalForce = uintBitsToFloat(uvec4(g_contactData[w + 8u], g_contactData[w + 9u], g_contactData[w + 10u],
                                          g_contactData[w + 11u]));
    return c;
}

void storeContactRecord(uint r, GpuImplicitContact c) {
    uint w = u_contactRecords + 12u * r;
    uvec4 weights = floatBitsToUint(c.weights), normalForce = floatBitsToUint(c.normalForce);
    for (uint k = 0u; k < 4u; ++k) {
        g_contactData[w + k] = c.nodes[k];
        g_contactData[w + 4u + k] = weights[k];
        g_contactData[w + 8u + k] = normalForce[k];
    }
}

// The list slot of record r's feature pair.
uint recordSlot(uint r) {
    return g_contactData[u_contactSlots + r];
}

void setRecordSlot(uint r, uint slot) {
    g_contactData[u_contactSlots + r] = slot;
}

uint incidenceRecord(uint entry) {
    return entry >> 2u;
}

uint incidenceCorner(uint entry) {
    return entry & 3u;
}

// Whether corner k of record c has a row of its own: a node that moves (inverse mass > 0; a pinned
// node keeps Δv = 0) and a weight that is not 0 (a vertex-face contact at an edge or a corner of
// the face leaves the other corners out). Every record is a contact (force > 0) or an approaching
// pair within the margin (force 0, stiffness k). Counting and scattering use this one rule, so the
// counts and the entries agree.
bool hasRow(GpuImplicitContact c, uint k, float inverseMass) {
    return c.normalForce.w >= 0.0 && inverseMass > 0.0 && c.weights[k] != 0.0;
}

#endif
