#pragma once
/// \file The engine: a scene's state in GPU buffers and the compute pipeline its effects call for.

#include <glcollide/scene.hpp>

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace glcollide {

struct EngineOptions {
    /// Time each pass with GL timestamp queries. step() then waits for the GPU at its end.
    bool gpuTiming = true;
};

/// GPU time of one pass over all substeps of a frame.
struct PassTiming {
    std::string name;
    double gpuMilliseconds = 0.0; ///< 0 when gpuTiming is off
};

/// What the collision passes found (effects collisions / self_collisions).
struct CollisionStats {
    std::uint32_t boxPairs = 0;          ///< overlapping leaf-box pairs (octree broad phase), last substep
    std::uint32_t candidatePairs = 0;    ///< face pairs within the contact thickness, last substep
    std::uint32_t intersectingPairs = 0; ///< face pairs whose closed triangles intersect, last substep
    std::uint32_t maxIntersectingPairs = 0; ///< the largest intersectingPairs of the frame's substeps
    std::uint32_t contacts = 0;          ///< vertex-face and edge-edge contacts with a force, last substep
    std::uint32_t exactFallbacks = 0;    ///< robust predicates decided by the exact path, last substep
    std::uint32_t listGrowths = 0;       ///< pair lists grown (and passes rerun) during the frame
};

struct StepStats {
    std::uint64_t frame = 0;      ///< frames completed, this one included
    double time = 0.0;            ///< s of simulated time after this frame
    int substeps = 0;
    double wallMilliseconds = 0.0; ///< CPU wall time of step(), including the wait for timings
    std::vector<PassTiming> passes;
    bool collisions = false;   ///< the collision passes ran (then `collision` is filled)
    CollisionStats collision;
};

/// How the substep count was chosen (docs/integration.md).
struct SubstepInfo {
    int substeps = 1;           ///< used per frame
    int stableSubsteps = 1;     ///< what the stability rule asks for
    double substepLength = 0.0; ///< s
    double maxStableSubstep = 0.0; ///< s, +inf when nothing limits it
    std::uint32_t limitingNode = 0; ///< global index of the node that sets the limit
    bool automatic = true;
};

/// Energies in joules, computed in double precision from the read-back state.
struct EnergyReport {
    double kinetic = 0.0;
    double potential = 0.0; ///< gravity (if on) + springs (if on)
    [[nodiscard]] double total() const { return kinetic + potential; }
};

/// Simulates a scene on the current GL ≥ 4.3 context: a HeadlessContext or the caller's own.
/// Not thread-safe; every call needs the construction context (or a sharing one) current.
class Engine {
public:
    /// Validates the scene, composes the pass list from its effects, allocates the buffers those
    /// passes need and uploads the state. Throws Error on bad scenes, missing GL 4.3, shader
    /// errors, or effects this version does not implement.
    explicit Engine(const Scene& scene, const EngineOptions& options = {});
    ~Engine();
    Engine(Engine&&) noexcept;
    Engine& operator=(Engine&&) noexcept;

    /// Advances one frame of Scene::time.dt in `substepInfo().substeps` substeps. Never throws.
    void step();
    [[nodiscard]] const StepStats& lastStep() const;

    /// The passes dispatched each substep, in order ("NodeForce", "SpringUpdate", "BBUpdate",
    /// "BBCollision", "TriTri", "ContactResponse", "NodeUpdate"; only those the effects call for).
    [[nodiscard]] std::vector<std::string> pipeline() const;
    /// Labels of the GPU buffers allocated for this scene ("positions", "springs", ...).
    [[nodiscard]] std::vector<std::string> allocatedBuffers() const;
    [[nodiscard]] std::size_t allocatedBytes() const;
    [[nodiscard]] const SubstepInfo& substepInfo() const;
    /// Warnings found at construction (e.g. explicit substeps below the stability limit).
    [[nodiscard]] const std::vector<std::string>& warnings() const;

    [[nodiscard]] const Scene& scene() const;
    [[nodiscard]] std::uint32_t nodeCount() const;
    [[nodiscard]] std::uint32_t faceCount() const;
    [[nodiscard]] std::uint32_t springCount() const;
    /// First global node index of each body (bodies are concatenated in scene order).
    [[nodiscard]] std::vector<std::uint32_t> bodyFirstNodes() const;

    /// Reads node positions / velocities back (waits for the GPU).
    [[nodiscard]] std::vector<glm::dvec3> readPositions() const;
    [[nodiscard]] std::vector<glm::dvec3> readVelocities() const;
    /// Face pairs (global face indices, first < second, sorted) whose closed triangles
    /// intersected in the last substep; empty without collision effects. Reads back.
    [[nodiscard]] std::vector<std::array<std::uint32_t, 2>> readIntersectingPairs() const;
    /// Candidate face pairs of the last substep's broad phase (sorted). Reads back.
    [[nodiscard]] std::vector<std::array<std::uint32_t, 2>> readCandidatePairs() const;
    /// Runs the broad and narrow phase on the current positions without moving anything (no forces,
    /// no contact response, no timing): afterwards readCandidatePairs() / readIntersectingPairs()
    /// describe exactly the state readPositions() returns (after step() they describe the positions
    /// before the last substep's NodeUpdate). Returns the counts (contacts 0); all zero without the
    /// collision effects. Waits for the GPU (one counter readback).
    CollisionStats detectCollisions();
    /// First global face index of each body.
    [[nodiscard]] std::vector<std::uint32_t> bodyFirstFaces() const;

    /// Kinetic and potential energy of the current state (reads back).
    [[nodiscard]] EnergyReport energy() const;

    /// GL name of the position buffer: vec4 per node (xyz metres, w inverse mass), stride 16,
    /// usable as GL_ARRAY_BUFFER after glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT).
    [[nodiscard]] std::uint32_t positionBuffer() const;
    /// GL name of the face buffer: 3 GLuint node indices per face, usable as
    /// GL_ELEMENT_ARRAY_BUFFER after glMemoryBarrier(GL_ELEMENT_ARRAY_BARRIER_BIT).
    [[nodiscard]] std::uint32_t faceIndexBuffer() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace glcollide
