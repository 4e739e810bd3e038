#pragma once
// The mass-spring half of the paper's pipeline: NodeForce, SpringUpdate, NodeUpdate. Each pass
// owns its program, compiled with the defines its configuration needs; dispatch() binds its
// buffers, sets its uniforms, dispatches one invocation per node and issues the storage barrier
// the next pass needs.

#include "core/dynamics_params.hpp"
#include "gl/program.hpp"
#include "model/flat_model.hpp"
#include "passes/device_buffers.hpp"
#include "passes/pass_id.hpp"

namespace glcollide::passes {

/// The define list of common/external_force.glsl for these terms.
std::vector<std::string> externalForceDefines(const NodeForceParams& terms);
/// Binds external_force.glsl's buffers and sets its uniforms on `program`.
void bindExternalForce(const gl::ComputeProgram& program, const DeviceBuffers& buffers,
                       const NodeForceParams& params, const NodeForceParams& compiled, const char* pass);

class NodeForcePass {
  public:
    static constexpr PassId kId = PassId::NodeForce;
    static constexpr const char* kName = passName(kId);
    explicit NodeForcePass(const NodeForceParams& config);
    void dispatch(const DeviceBuffers& buffers, const NodeForceParams& params) const;

  private:
    NodeForceParams m_config;
    gl::ComputeProgram m_program;
};

class SpringUpdatePass {
  public:
    static constexpr PassId kId = PassId::SpringUpdate;
    static constexpr const char* kName = passName(kId);
    explicit SpringUpdatePass(const SpringUpdateParams& config);
    void dispatch(const DeviceBuffers& buffers, const SpringUpdateParams& params) const;

  private:
    SpringUpdateParams m_config;
    gl::ComputeProgram m_program;
};

class NodeUpdatePass {
  public:
    static constexpr PassId kId = PassId::NodeUpdate;
    static constexpr const char* kName = passName(kId);
    explicit NodeUpdatePass(const NodeUpdateParams& config);
    /// `substep`: index within the frame, recorded with a non-finite node when checkFinite is on.
    void dispatch(const DeviceBuffers& buffers, const NodeUpdateParams& params,
                  std::uint32_t substep = 0) const;

  private:
    NodeUpdateParams m_config;
    gl::ComputeProgram m_program;
};

/// Continuous detection's first half of NodeUpdate (node_update.comp with GLC_PREDICT): the
/// velocity step with the forces (none under implicit Euler, whose solve already set v) and the
/// predicted end positions into buffers.predictedPositions. NodeUpdate then runs without forces.
/// The intersection-free response's NodePredict also adds the contact forces and applies the
/// ground (config.contacts, config.ground): x1 is the whole step, which SafeStep commits.
class NodePredictPass {
  public:
    static constexpr PassId kId = PassId::NodePredict;
    static constexpr const char* kName = passName(kId);
    explicit NodePredictPass(const NodeUpdateParams& config);
    void dispatch(const DeviceBuffers& buffers, const NodeUpdateParams& params,
                  std::uint32_t substep = 0) const;

  private:
    NodeUpdateParams m_config;
    gl::ComputeProgram m_program;
};

/// The intersection-free response's ContactApply (node_update.comp with GLC_PREDICT and
/// GLC_CONTACTS, no forces): one response iteration's contact forces into v, x1 = x0 + h·v again,
/// the ground. NodePredict's program with another identity (its own timer section).
class ContactApplyPass {
  public:
    static constexpr PassId kId = PassId::ContactApply;
    static constexpr const char* kName = passName(kId);
    explicit ContactApplyPass(const NodeUpdateParams& config) : m_predict(config) {}
    void dispatch(const DeviceBuffers& buffers, const NodeUpdateParams& params,
                  std::uint32_t substep = 0) const {
        m_predict.dispatch(buffers, params, substep);
    }

  private:
    NodePredictPass m_predict;
};

/// Every substep of a frame in one dispatch (shaders/passes/frame_step.comp): for small scenes
/// without collisions and without heavy rows.
/// Substeps one FrameStep dispatch may run (at most kFrameStepSubstepsPerDispatch) so that none of
/// its invocations loops more than 2^15 times in all: llvmpipe ends an invocation's loops silently
/// after 65,535 iterations in total (gallivm's loop limiter, as in octree_expand.comp), which cut
/// a frame of 4,096 nodes short beyond ~800 substeps. Counted per invocation (every
/// GLC_FRAME_STEP_GROUP-th node) with one more iteration per loop than it runs: the substep loop,
/// per node the two node loops, its springs (`nodeSprings`, null without springs) and its faces
/// (`nodeFaces`, null without wind).
std::uint32_t frameStepSubstepsPerDispatch(std::uint32_t nodeCount, const model::Csr* nodeSprings,
                                           const model::Csr* nodeFaces);

class FrameStepPass {
  public:
    static constexpr PassId kId = PassId::FrameStep;
    static constexpr const char* kName = passName(kId);
    explicit FrameStepPass(const FrameStepParams& config);
    void dispatch(const DeviceBuffers& buffers, const FrameStepParams& params) const;

  private:
    FrameStepParams m_config;
    gl::ComputeProgram m_program;
};

} // namespace glcollide::passes
