// The faces that intersect at x0 (tangled_marks.comp, GLC_BIND_TANGLED: one uint per node, then
// per face), for the responses' recovery from intersecting input (decision 0024): an edge-edge
// contact between such faces would keep the edges on the sides they have now — the wrong ones —
// and hold the bodies together, so it is left out and the vertex-face contacts push them apart.
// u_tangledFaces: the index of face 0's mark (the node count), or 0xFFFFFFFF when no marks are
// bound (the block is then never read).
#ifndef GLC_TANGLED_GLSL
#define GLC_TANGLED_GLSL
layout(std430, binding = GLC_BIND_TANGLED) readonly buffer TangledBuf { uint g_tangled[]; };
uniform uint u_tangledFaces;
bool faceTangled(uint face) {
    return u_tangledFaces != 0xFFFFFFFFu && g_tangled[u_tangledFaces + face] != 0u;
}
#endif
