#pragma once
// Composes the pass list and the buffer set from a scene's effects, without touching GL, so
// "simulate only what the scene calls for" is decided in one place and testable on its own.

#include "core/dynamics_params.hpp"

#include <glcollide/scene.hpp>

#include <string>
#include <vector>

namespace glcollide::engine {

struct PipelinePlan {
    bool nodeForce = false;
    bool springUpdate = false;
    bool nodeUpdate = false;
    NodeForceParams nodeForceParams;
    SpringUpdateParams springUpdateParams;
    NodeUpdateParams nodeUpdateParams; ///< h is filled in once substeps are known

    [[nodiscard]] std::vector<std::string> passes() const;
    /// Buffer labels the passes need, in DeviceBuffers declaration order.
    [[nodiscard]] std::vector<std::string> buffers() const;
};

/// Throws Error for effects this version cannot simulate (collisions, self_collisions).
PipelinePlan planPipeline(const Scene& scene);

} // namespace glcollide::engine
