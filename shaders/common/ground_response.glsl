// The ground's velocity response, written once: an approaching velocity is reflected with the
// restitution e and its tangential part reduced by Coulomb friction μ, the normal impulse (1 + e)|vn|
// bounding the tangential change. NodeUpdate and FrameStep apply it where a node meets the ground
// (advance_node.glsl); GroundImpact applies it to the velocity a node hit the ground with within the
// substep (decision 0024, "Restitution at any step"). Twins: cpu::nodeUpdate, cpu::groundImpact.
#ifndef GLC_GROUND_RESPONSE_GLSL
#define GLC_GROUND_RESPONSE_GLSL

void groundResponse(inout vec3 v, float e, float mu) {
    if (!(v.y < 0.0)) return;
    float normalSpeed = -v.y;
    v.y = e * normalSpeed;
    float tangentialSpeed = length(v.xz);
    if (tangentialSpeed > 0.0) {
        float scale = max(0.0, 1.0 - mu * (1.0 + e) * normalSpeed / tangentialSpeed);
        v.xz *= scale;
    }
}

#endif
