#pragma once
// The contact responses as types (issue 23, item 6; as the broad phases are): each class states
// what its response needs from the detection, what it adds to the pipeline plan and the substep's
// stages it runs. responseModel() is the factory, the one place that maps
// CollisionSettings::response to a class: adding a response is its class and one entry there
// (and its name in scene/scene_json.cpp's table). GL-free: the plan is composed without a context.

#include <glcollide/scene.hpp>

#include <optional>
#include <vector>

namespace glcollide::engine {

struct PipelinePlan;
enum class Stage : std::uint8_t;

class ResponseModel {
  public:
    virtual ~ResponseModel() = default;
    [[nodiscard]] virtual ContactResponse kind() const = 0;
    /// The detection it needs; nullopt when either serves.
    [[nodiscard]] virtual std::optional<Detection> requiredDetection() const { return std::nullopt; }
    /// Its parts of the plan, after the integrator and the detection are planned.
    virtual void plan(const Scene& scene, PipelinePlan& plan) const = 0;
    /// The substep's stages, in order (PipelinePlan::stages() with collisions).
    [[nodiscard]] virtual std::vector<Stage> stages(const PipelinePlan& plan) const = 0;
    /// Whether its contact forces enter an implicit step explicitly (then they keep the explicit
    /// substep limit of a contact spring, and the engine warns below it).
    [[nodiscard]] virtual bool explicitUnderImplicitEuler() const { return false; }
};

/// The factory: the response `kind` (stateless; lives as long as the program).
const ResponseModel& responseModel(ContactResponse kind);

} // namespace glcollide::engine
