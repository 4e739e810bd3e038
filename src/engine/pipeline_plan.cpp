#include "engine/pipeline_plan.hpp"

#include <glcollide/error.hpp>

namespace glcollide::engine {

std::vector<std::string> PipelinePlan::passes() const {
    std::vector<std::string> p;
    if (nodeForce) p.emplace_back("NodeForce");
    if (springUpdate) p.emplace_back("SpringUpdate");
    if (nodeUpdate) p.emplace_back("NodeUpdate");
    return p;
}

std::vector<std::string> PipelinePlan::buffers() const {
    std::vector<std::string> b;
    if (!nodeUpdate) return b;
    b = {"positions", "velocities", "faces"};
    if (nodeForce || springUpdate) b.emplace_back("forces");
    if (springUpdate) {
        b.emplace_back("springs");
        b.emplace_back("nodeSpringOffsets");
        b.emplace_back("nodeSpringList");
    }
    if (nodeForce && nodeForceParams.wind) {
        b.emplace_back("nodeFaceOffsets");
        b.emplace_back("nodeFaceList");
    }
    return b;
}

PipelinePlan planPipeline(const Scene& scene) {
    const EffectSet& fx = scene.effects;
    for (Effect e : {Effect::Collisions, Effect::SelfCollisions})
        if (fx.has(e))
            throw Error(scene.sourcePath.string() + ": effect '" + std::string(effectName(e)) +
                        "' is not implemented in this version of glcollide (the collision "
                        "pipeline is planned); remove it from /effects");
    PipelinePlan plan;
    NodeForceParams& nf = plan.nodeForceParams;
    nf.gravity = fx.has(Effect::Gravity);
    nf.damping = fx.has(Effect::Damping);
    nf.wind = fx.has(Effect::Wind);
    nf.gravityAcceleration = scene.gravity;
    nf.dampingCoefficient = scene.damping;
    nf.windVelocity = scene.wind.velocity;
    nf.windDrag = scene.wind.drag;

    std::size_t nodes = 0;
    for (const Body& b : scene.bodies) nodes += b.positions.size();
    plan.nodeUpdate = nodes > 0;
    plan.nodeForce = plan.nodeUpdate && (nf.gravity || nf.damping || nf.wind);
    plan.springUpdate = plan.nodeUpdate && fx.has(Effect::Springs);
    plan.springUpdateParams.accumulate = plan.nodeForce;

    NodeUpdateParams& nu = plan.nodeUpdateParams;
    nu.forces = plan.nodeForce || plan.springUpdate;
    nu.ground = fx.has(Effect::Ground);
    nu.groundHeight = scene.ground.height;
    nu.restitution = scene.ground.restitution;
    nu.friction = scene.ground.friction;
    return plan;
}

} // namespace glcollide::engine
