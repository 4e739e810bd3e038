#include "passes/broad_phase/leaf_boxes.hpp"

#include "core/gpu_layout.hpp"

#include <epoxy/gl.h>

namespace glcollide::passes {

LeafBoxes::LeafBoxes(const BroadPhaseContext& c)
    : m_boxCount(c.layout.boxCount), m_boxes("boxes", std::size_t{c.layout.boxCount} * sizeof(gpu::GpuBox)),
      m_boxFaceOffsets(gl::makeBuffer("boxFaceOffsets", c.layout.boxFaces.offsets)),
      m_boxFaceList(gl::makeBuffer("boxFaceList", c.layout.boxFaces.items)),
      m_refit("bb_update", faceBoxDefines(c)) {
    m_refit.set("u_boxCount", m_boxCount);
    m_refit.set("u_halfThickness", c.halfThickness);
}

Stage LeafBoxes::refitStage() const {
    return {PassId::BBUpdate, {}, [this] {
                m_refit.use();
                m_refit.dispatch1D(m_boxCount * GLC_BB_UPDATE_GROUP,
                                   GLC_BB_UPDATE_GROUP); // one group per box
                glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
            }};
}

void LeafBoxes::bind() const {
    m_boxes.bindStorage(GLC_BIND_BOXES);
    m_boxFaceOffsets.bindStorage(GLC_BIND_BOX_FACE_OFFSETS);
    m_boxFaceList.bindStorage(GLC_BIND_BOX_FACE_LIST);
}

} // namespace glcollide::passes
