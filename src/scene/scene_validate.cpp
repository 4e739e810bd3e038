// validateScene: the invariants documented on Scene and Body.
#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <cmath>
#include <string>

namespace glcollide {
namespace {

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string prefix(const Scene& scene) {
    return scene.sourcePath.empty() ? std::string("scene '" + scene.name + "'") : scene.sourcePath.string();
}

} // namespace

void validateScene(const Scene& scene) {
    const std::string where = prefix(scene);
    const auto fail = [&](const std::string& what) { throw Error(where + ": " + what); };

    if (!(scene.time.dt > 0.0) || !std::isfinite(scene.time.dt))
        fail("time.dt must be a positive finite number of seconds, got " + std::to_string(scene.time.dt));
    if (scene.time.substeps < 0)
        fail("time.substeps must be >= 0 (0 = auto), got " + std::to_string(scene.time.substeps));
    if (scene.time.frames <= 0) fail("time.frames must be > 0, got " + std::to_string(scene.time.frames));
    if (!finite(scene.gravity)) fail("gravity is not finite");
    if (!(scene.damping >= 0.0) || !std::isfinite(scene.damping)) fail("damping must be finite and >= 0");
    if (!finite(scene.wind.velocity)) fail("wind.velocity is not finite");
    if (!(scene.wind.drag >= 0.0) || !std::isfinite(scene.wind.drag))
        fail("wind.drag must be finite and >= 0");
    if (!std::isfinite(scene.ground.height)) fail("ground.height is not finite");
    if (!(scene.ground.restitution >= 0.0 && scene.ground.restitution <= 1.0))
        fail("ground.restitution must be in [0, 1], got " + std::to_string(scene.ground.restitution));
    if (!(scene.ground.friction >= 0.0) || !std::isfinite(scene.ground.friction))
        fail("ground.friction must be finite and >= 0");
    const CollisionSettings& col = scene.collision;
    if (col.octreeDepth < 1 || col.octreeDepth > 3)
        fail("collision.octree_depth must be 1, 2 or 3, got " + std::to_string(col.octreeDepth));
    if (!(col.thickness > 0.0) || !std::isfinite(col.thickness))
        fail("collision.thickness must be finite and > 0, got " + std::to_string(col.thickness));
    if (!(col.stiffness > 0.0) || !std::isfinite(col.stiffness))
        fail("collision.stiffness must be finite and > 0, got " + std::to_string(col.stiffness));
    if (!(col.damping >= 0.0) || !std::isfinite(col.damping))
        fail("collision.damping must be finite and >= 0");
    if (!(col.friction >= 0.0) || !std::isfinite(col.friction))
        fail("collision.friction must be finite and >= 0");
    if (!(col.restitution >= 0.0 && col.restitution <= 1.0))
        fail("collision.restitution must be in [0, 1], got " + std::to_string(col.restitution));
    if (col.restitutionIterations < 1 || col.restitutionIterations > 64)
        fail("collision.restitution_iterations must be 1 … 64, got " +
             std::to_string(col.restitutionIterations));
    if (col.restitution > 0.0 && col.response != ContactResponse::IntersectionFree)
        fail("collision.restitution needs collision.response intersection_free");
    if (!(col.relaxationTime > 0.0) || !std::isfinite(col.relaxationTime))
        fail("collision.relaxation_time must be finite and > 0");
    if (col.initialCapacity < 1) fail("collision.initial_capacity must be >= 1");
    if (col.response == ContactResponse::IntersectionFree && col.detection != Detection::Continuous)
        fail("collision.response intersection_free needs collision.detection continuous");
    if (col.responseIterations < 0 || col.responseIterations > 64)
        fail("collision.response_iterations must be 1 … 64 (or 0: automatic), got " +
             std::to_string(col.responseIterations));
    const int newtonSteps = scene.time.solver.newtonSteps;
    if (newtonSteps < 0 || newtonSteps > 4)
        fail("time.solver.newton_steps must be 1 … 4 (or 0: automatic), got " + std::to_string(newtonSteps));
    const double newtonTolerance = scene.time.solver.newtonTolerance;
    if (!(newtonTolerance >= 0.0 && newtonTolerance <= 1.0))
        fail("time.solver.newton_tolerance must be in [0, 1], got " + std::to_string(newtonTolerance));
    const double contactMargin = scene.time.solver.contactMargin;
    if (!(contactMargin >= 0.0 && contactMargin <= 4.0))
        fail("time.solver.contact_margin must be in [0, 4], got " + std::to_string(contactMargin));
    if (newtonSteps > 1 &&
        (scene.time.integrator != Integrator::ImplicitEuler ||
         col.response != ContactResponse::IntersectionFree ||
         (!scene.effects.has(Effect::Collisions) && !scene.effects.has(Effect::SelfCollisions))))
        fail(
            "time.solver.newton_steps above 1 needs implicit_euler and collision.response intersection_free");

    for (std::size_t bi = 0; bi < scene.bodies.size(); ++bi) {
        const Body& b = scene.bodies[bi];
        const std::string body = "body " + std::to_string(bi) + " '" + b.name + "'";
        const auto bfail = [&](const std::string& what) { fail(body + ": " + what); };
        const std::size_t n = b.positions.size();
        if (n == 0) bfail("has no nodes");
        if (b.velocities.size() != n || b.masses.size() != n || b.pinned.size() != n)
            bfail("per-node vectors differ in length (positions " + std::to_string(n) + ", velocities " +
                  std::to_string(b.velocities.size()) + ", masses " + std::to_string(b.masses.size()) +
                  ", pinned " + std::to_string(b.pinned.size()) + ")");
        for (std::size_t v = 0; v < n; ++v) {
            const std::string node = "node " + std::to_string(v) + ": ";
            if (!finite(b.positions[v])) bfail(node + "position is not finite");
            if (!finite(b.velocities[v])) bfail(node + "velocity is not finite");
            if (!(b.masses[v] > 0.0) || !std::isfinite(b.masses[v]))
                bfail(node + "mass must be positive and finite, got " + std::to_string(b.masses[v]));
            if (b.pinned[v] > 1) bfail(node + "pinned must be 0 or 1");
        }
        for (std::size_t f = 0; f < b.faces.size(); ++f)
            for (std::uint32_t i : b.faces[f]) {
                if (i >= n)
                    bfail("face " + std::to_string(f) + ": index " + std::to_string(i) + " out of range");
            }
        for (std::size_t f = 0; f < b.faces.size(); ++f) {
            const auto& t = b.faces[f];
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
                bfail("face " + std::to_string(f) + ": repeated index");
        }
        for (std::size_t t = 0; t < b.tets.size(); ++t)
            for (std::uint32_t i : b.tets[t])
                if (i >= n)
                    bfail("tet " + std::to_string(t) + ": index " + std::to_string(i) + " out of range");
        for (std::size_t s = 0; s < b.springs.size(); ++s) {
            const Spring& sp = b.springs[s];
            const std::string spring = "spring " + std::to_string(s) + ": ";
            if (sp.a >= n || sp.b >= n)
                bfail(spring + "end index out of range (" + std::to_string(sp.a) + ", " +
                      std::to_string(sp.b) + ")");
            if (sp.a == sp.b) bfail(spring + "both ends are node " + std::to_string(sp.a));
            if (!(sp.restLength > 0.0) || !std::isfinite(sp.restLength))
                bfail(spring + "rest length must be positive and finite, got " +
                      std::to_string(sp.restLength) + " (coincident nodes " + std::to_string(sp.a) + " and " +
                      std::to_string(sp.b) + "?)");
            if (!(sp.stiffness > 0.0) || !std::isfinite(sp.stiffness))
                bfail(spring + "stiffness must be positive and finite, got " + std::to_string(sp.stiffness));
            if (!(sp.damping >= 0.0) || !std::isfinite(sp.damping))
                bfail(spring + "damping must be finite and >= 0, got " + std::to_string(sp.damping));
        }
    }
}

} // namespace glcollide
