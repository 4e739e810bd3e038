#pragma once
// The face-box inflation both sides use: the GPU passes pass it as the uniform u_halfThickness
// (bb_update.comp and the face-pair kernels: octree_expand, all_face_pairs, masked_face_pairs), the CPU twin
// (cpu/collision_twin.hpp) inflates its boxes by it, so the float boxes agree bit for bit.

namespace glcollide::model {

/// Half the contact thickness as the GPU gets it (uniform u_halfThickness): float(0.5 * h), h in m.
inline float halfThicknessFloat(double thickness) {
    return static_cast<float>(0.5 * thickness);
}

} // namespace glcollide::model
