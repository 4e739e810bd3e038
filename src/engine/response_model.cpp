#include "engine/response_model.hpp"

#include "engine/pipeline_plan.hpp"

namespace glcollide::engine {

namespace {

/// Forces or impulses on the feature pairs, then NodeUpdate (PipelinePlan::forceResponseStages).
class PenaltyResponse final : public ResponseModel {
  public:
    [[nodiscard]] ContactResponse kind() const override { return ContactResponse::Penalty; }
    void plan(const Scene&, PipelinePlan&) const override {} // contactParams: a force response
    [[nodiscard]] std::vector<Stage> stages(const PipelinePlan& plan) const override {
        return plan.forceResponseStages();
    }
    [[nodiscard]] bool explicitUnderImplicitEuler() const override { return true; }
};

/// Bridson et al. 2002: the same stages, a velocity-level response (decision 0019).
class BridsonResponse final : public ResponseModel {
  public:
    [[nodiscard]] ContactResponse kind() const override { return ContactResponse::Bridson; }
    void plan(const Scene&, PipelinePlan&) const override {} // contactParams: velocity-level
    [[nodiscard]] std::vector<Stage> stages(const PipelinePlan& plan) const override {
        return plan.forceResponseStages();
    }
};

/// Decision 0024: contacts in the solve, a checked and cut step, the energy guard, the commit.
class IntersectionFreeResponse final : public ResponseModel {
  public:
    [[nodiscard]] ContactResponse kind() const override { return ContactResponse::IntersectionFree; }
    [[nodiscard]] std::optional<Detection> requiredDetection() const override {
        return Detection::Continuous;
    }
    void plan(const Scene& scene, PipelinePlan& plan) const override { planSafeStep(scene, plan); }
    [[nodiscard]] std::vector<Stage> stages(const PipelinePlan& plan) const override {
        // Without continuous detection (refused by the scene validation) there is no step to check.
        return plan.safeStep ? plan.safeStepStages() : plan.forceResponseStages();
    }
};

} // namespace

const ResponseModel& responseModel(ContactResponse kind) {
    static const PenaltyResponse penalty;
    static const BridsonResponse bridson;
    static const IntersectionFreeResponse intersectionFree;
    switch (kind) {
    case ContactResponse::Penalty:
        return penalty;
    case ContactResponse::Bridson:
        return bridson;
    case ContactResponse::IntersectionFree:
        return intersectionFree;
    }
    return penalty; // not reached: every enumerator is above
}

} // namespace glcollide::engine
