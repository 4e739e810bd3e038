#pragma once
// The broad-phase factory: the one place that maps CollisionSettings::broadPhase to a class.
// Adding a broad phase = its class + one entry in each function here.

#include "passes/broad_phase/broad_phase.hpp"

#include <memory>

namespace glcollide::passes {

/// The passes a kind's stages are timed under (GL-free: the pipeline plan uses it).
std::vector<PassId> broadPhasePasses(glcollide::BroadPhase kind);

/// Builds the kind `context.settings.broadPhase` (compiles its programs, uploads its tables).
/// Throws glcollide::Error on settings the kind cannot serve.
std::unique_ptr<BroadPhase> createBroadPhase(const BroadPhaseContext& context);

} // namespace glcollide::passes
