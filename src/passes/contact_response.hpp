#pragma once
// ContactResponse: penalty forces for the feature pairs of the Representative-Triangle expansion
// (FeaturePairs: GLC_LIST_VERTEX_FACE and GLC_LIST_EDGE_EDGE; docs/collisions.md), summed per node
// in fixed point into DeviceBuffers::contactForces, which NodeUpdate adds and clears. Two kernels,
// each dispatched indirectly over its list (shaders/passes/contact_vertex_face.comp,
// contact_edge_edge.comp): no count is read back to the host.

#include "core/contact_params.hpp"
#include "gl/program.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/device_buffers.hpp"
#include "passes/pass_id.hpp"

namespace glcollide::passes {

/// The collision buffers the response reads (owned by the collision detection).
struct ContactInputs {
    /// The vertex-face and edge-edge lists (declared), their counts and the counter block, whose
    /// contactCount the response adds to.
    const AppendLists* lists = nullptr;
    const gl::Buffer* faceInfo = nullptr; ///< GpuFaceInfo per face
    const gl::Buffer* objects = nullptr;  ///< GpuObject per object
    /// uint per node, then per face: 1 for the faces that intersect at x0 (the safe step's marks,
    /// CollisionDetection::tangled()); edge-edge contacts between them are left out. nullptr: none.
    const gl::Buffer* tangled = nullptr;
};

/// Checks and binds what the contact kernels read of `inputs` (the face info, the objects, the lists
/// and their counters); throws glcollide::Error naming `pass` when something is missing.
void bindContactInputs(const ContactInputs& inputs, const char* pass);

/// Binds `inputs.tangled` for tangled.glsl, or tells the program there are no marks.
void bindTangled(const gl::ComputeProgram& program, const ContactInputs& inputs, std::uint32_t nodeCount);

class ContactResponsePass {
  public:
    static constexpr PassId kId = PassId::ContactResponse;
    static constexpr const char* kName = passName(kId);
    /// `config.predictedForces` picks the program variant that reads the force buffer.
    explicit ContactResponsePass(const ContactParams& config = {});
    void dispatch(const DeviceBuffers& buffers, const ContactInputs& inputs,
                  const ContactParams& params) const;

  private:
    ContactParams m_config;
    gl::ComputeProgram m_vertexFace, m_edgeEdge;
};

} // namespace glcollide::passes
