// The point of a face the Morton order sorts by: the centre of its vertices' box. Include after
// face_nodes.glsl and NodePositionsBuf (g_positions). Its rounding only changes the order of the
// leaves, never which pairs the BVH finds: the traversal tests the exact face boxes.
vec3 faceCentroid(uint face) {
    uvec3 n = faceNodes(face);
    vec3 a = g_positions[n.x].xyz, b = g_positions[n.y].xyz, c = g_positions[n.z].xyz;
    return 0.5 * (min(min(a, b), c) + max(max(a, b), c));
}
