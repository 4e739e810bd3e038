// The engine's answers do not depend on the units a scene is drawn in. The same scene with every
// length times 2^k (a mask in units of 2^-12 m, or of 4,096 m), with every mass, stiffness and
// damping times 2^j, or with every time times 2^t (and so velocities, accelerations, stiffnesses and
// dampings in those units) is the same physical system; every float operation the engine does on it
// is then the original one times a power of two, which is exact as long as nothing overflows or
// underflows. So the positions must come out bit for bit the original ones times 2^k (or equal),
// frame after frame, with the same counts (contacts, CCD, safe-step cuts, energy-guard actions, CG
// iterations). Any constant with a unit — an absolute floor, an epsilon in metres or joules —
// breaks that exactness where it decides something. The first one found this way: the CG stopped
// when ‖r‖² fell below 10⁻³⁰ kg²m²/s², so DEDO's mask drawn at 2⁻¹² of its size stopped its solves
// earlier than in metres and parted from the first frame (decision 0020, "Units"); the second, Bridson's
// relaxation time of 0.01 s, is now the scene's collision.relaxation_time.
// Independent reference: the same engine on the unscaled scene; the property is exact, so there is
// no tolerance. Ranges the engine states elsewhere stay out: the contact energy's fixed point has
// units of 2⁻⁶⁴ J (decision 0024, "Energy guard"), so the scales here keep every energy within it.

#include <glcollide/engine.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <string>
#include <vector>

namespace glcollide {
namespace {

glm::dvec3 times2(glm::dvec3 v, int k) {
    return glm::dvec3(std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k));
}

/// The scene with every length times 2^k: positions, velocities, observers, rest lengths, gravity,
/// the ground's height, the thickness, the ghosts' perimeter, the CCD's separation and the wind
/// (its drag per area scaled so that its force scales like every other force, by 2^k).
Scene inLengthUnit(Scene s, int k) {
    for (Body& b : s.bodies) {
        for (glm::dvec3& x : b.positions) x = times2(x, k);
        for (glm::dvec3& v : b.velocities) v = times2(v, k);
        if (b.observer) b.observer = times2(*b.observer, k);
        if (b.observerEnd) b.observerEnd = times2(*b.observerEnd, k);
        for (Spring& spring : b.springs) spring.restLength = std::ldexp(spring.restLength, k);
    }
    s.gravity = times2(s.gravity, k);
    s.ground.height = std::ldexp(s.ground.height, k);
    s.wind.velocity = times2(s.wind.velocity, k);
    s.wind.drag = std::ldexp(s.wind.drag, -2 * k);
    s.collision.thickness = std::ldexp(s.collision.thickness, k);
    s.collision.ghostMaxPerimeter = std::ldexp(s.collision.ghostMaxPerimeter, k); // +inf stays
    s.collision.ccd.minSeparation = std::ldexp(s.collision.ccd.minSeparation, k);
    s.camera.reset();
    return s;
}

/// The scene with every mass times 2^j, and so every stiffness and damping (N = kg·m/s²) too.
Scene inMassUnit(Scene s, int j) {
    for (Body& b : s.bodies) {
        for (double& m : b.masses) m = std::ldexp(m, j);
        for (Spring& spring : b.springs) {
            spring.stiffness = std::ldexp(spring.stiffness, j);
            spring.damping = std::ldexp(spring.damping, j);
        }
    }
    s.wind.drag = std::ldexp(s.wind.drag, j);
    s.collision.stiffness = std::ldexp(s.collision.stiffness, j);
    s.collision.damping = std::ldexp(s.collision.damping, j);
    return s;
}

/// The scene with every time times 2^t: the frame's length, velocities (2^-t), accelerations and
/// stiffnesses (N/m = kg/s²: 2^-2t), dampings (2^-t) and the response's relaxation time (2^t).
Scene inTimeUnit(Scene s, int t) {
    s.time.dt = std::ldexp(s.time.dt, t);
    for (Body& b : s.bodies) {
        for (glm::dvec3& v : b.velocities) v = times2(v, -t);
        for (Spring& spring : b.springs) {
            spring.stiffness = std::ldexp(spring.stiffness, -2 * t);
            spring.damping = std::ldexp(spring.damping, -t);
        }
    }
    s.gravity = times2(s.gravity, -2 * t);
    s.damping = std::ldexp(s.damping, -t);
    s.wind.velocity = times2(s.wind.velocity, -t);
    s.wind.drag = std::ldexp(s.wind.drag, -t);
    s.collision.stiffness = std::ldexp(s.collision.stiffness, -2 * t);
    s.collision.damping = std::ldexp(s.collision.damping, -t);
    s.collision.relaxationTime = std::ldexp(s.collision.relaxationTime, t);
    return s;
}

/// What must agree exactly between the two runs besides the positions.
void expectSameCounts(const StepStats& a, const StepStats& b, int frame) {
    EXPECT_EQ(a.substeps, b.substeps) << "frame " << frame;
    EXPECT_EQ(a.collision.contacts, b.collision.contacts) << "frame " << frame;
    EXPECT_EQ(a.collision.safeStepSubsteps, b.collision.safeStepSubsteps) << "frame " << frame;
    EXPECT_EQ(a.collision.energyGuardSubsteps, b.collision.energyGuardSubsteps) << "frame " << frame;
    EXPECT_EQ(a.collision.energyGuardPulledBack, b.collision.energyGuardPulledBack) << "frame " << frame;
    EXPECT_EQ(a.solver.totalIterations, b.solver.totalIterations) << "frame " << frame;
}

/// Runs `frames` frames of `scene` and of each copy in another unit; after every frame the copy's
/// positions are the original's times 2^lengthExponent, exactly. Returns the contacts seen, so the
/// caller can check that the frames compared had some.
std::uint64_t expectUnitsChangeNothing(const Scene& scene, int frames) {
    struct Copy {
        std::string unit;
        Scene scene;
        int lengthExponent;
    };
    const Copy copies[] = {
        {"lengths x 2^-12", inLengthUnit(scene, -12), -12}, {"lengths x 2^12", inLengthUnit(scene, 12), 12},
        {"masses x 2^-10", inMassUnit(scene, -10), 0},      {"masses x 2^10", inMassUnit(scene, 10), 0},
        {"times x 2^-3", inTimeUnit(scene, -3), 0},         {"times x 2^3", inTimeUnit(scene, 3), 0}};
    Engine reference(scene);
    std::vector<Engine> engines;
    engines.reserve(std::size(copies));
    for (const Copy& c : copies) engines.emplace_back(c.scene);
    std::uint64_t contacts = 0;
    for (int frame = 1; frame <= frames; ++frame) {
        reference.step();
        const std::vector<glm::dvec3> x = reference.readPositions();
        contacts += reference.lastStep().collision.contacts;
        for (std::size_t c = 0; c < engines.size(); ++c) {
            SCOPED_TRACE(scene.name + ", " + copies[c].unit);
            engines[c].step();
            const std::vector<glm::dvec3> y = engines[c].readPositions();
            if (y.size() != x.size()) {
                ADD_FAILURE() << "node counts differ: " << y.size() << " against " << x.size();
                return contacts;
            }
            std::size_t differing = 0, first = x.size();
            for (std::size_t i = 0; i < x.size(); ++i)
                if (y[i] != times2(x[i], copies[c].lengthExponent)) {
                    ++differing;
                    first = std::min(first, i);
                }
            if (differing != 0) { // later frames would only repeat it
                ADD_FAILURE() << "frame " << frame << ": " << differing << " nodes differ, the first "
                              << first;
                return contacts;
            }
            expectSameCounts(reference.lastStep(), engines[c].lastStep(), frame);
        }
    }
    return contacts;
}

Scene shipped(const std::string& name) {
    return loadScene(std::string(GLCOLLIDE_SOURCE_DIR) + "/scenes/" + name);
}

// DEDO's mask folding onto a pinned ball: implicit Euler with the contacts in the solve and the
// contact margin, self-collisions with radial culling and ghost triangles, friction, the energy
// guard. The scene that found the CG's absolute floor.
TEST(UnitsGl, AMaskFoldingOntoABallRunsTheSameBitsInOtherUnits) {
    EXPECT_GT(expectUnitsChangeNothing(shipped("mask_fold.json"), 6), 0u) << "the frames must have contacts";
}

// Tet bodies piling up on the ground: contacts between objects, the ground's penalty and friction,
// air and spring damping, under implicit Euler (as shipped) and symplectic Euler (automatic
// substeps, Bridson's velocity response between the safe steps).
TEST(UnitsGl, ATetPileRunsTheSameBitsInOtherUnitsUnderBothIntegrators) {
    // 22 frames: the ball lands on the box in frame 12 and the safe step cuts a substep in frame 20.
    Scene implicitPile = shipped("tet_pile.json");
    implicitPile.time.integrator = Integrator::ImplicitEuler;
    EXPECT_GT(expectUnitsChangeNothing(implicitPile, 22), 0u) << "the frames must have contacts";
    // Symplectic Euler needs ~76 substeps per frame here, so two frames, with the box lowered to
    // 5 mm above the ground and the ball to 1 cm above the box (both within the thickness, 1 cm, of
    // their contact at once).
    Scene symplecticPile = implicitPile;
    symplecticPile.name += " (symplectic)";
    symplecticPile.time.integrator = Integrator::SymplecticEuler;
    symplecticPile.time.substeps = 0;
    for (glm::dvec3& x : symplecticPile.bodies.at(0).positions) x.y -= 0.045;
    for (glm::dvec3& x : symplecticPile.bodies.at(1).positions) x.y -= 0.185;
    EXPECT_GT(expectUnitsChangeNothing(symplecticPile, 2), 0u) << "the frames must have contacts";
}

} // namespace
} // namespace glcollide
