#pragma once
// The paper's fused TriTri (seeds/002 Alg. 2-3) as a benchmark reference: every valid face pair
// tested with the fast triangle test in one O(faces^2) kernel, optionally behind the leaf-box
// overlap mask. The engine's masked and all-pairs broad phases emit candidates and let TriTri run
// on the list; this keeps the paper's own shape measurable next to them (shaders/bench/).

#include "model/flat_model.hpp"

#include <glcollide/scene.hpp>

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace glcollide::benchkit {

struct PaperFusedAnswer {
    std::vector<std::array<std::uint32_t, 2>> candidates; ///< valid pairs with overlapping face boxes, sorted
    std::vector<std::array<std::uint32_t, 2>> intersections; ///< valid pairs the fast test reports, sorted
    std::vector<double> milliseconds;                        ///< GPU time of each timed run
};

class PaperFusedTriTri {
  public:
    /// `masked`: the paper's masked scheme (BBUpdate, box mask, masked fused TriTri) over the
    /// octree of settings.octreeDepth; otherwise its all-pairs scheme (fused TriTri alone).
    /// Needs a current GL 4.3 context.
    PaperFusedTriTri(const model::FlatModel& model, const CollisionSettings& settings, bool betweenObjects,
                     bool selfCollisions, bool masked);
    ~PaperFusedTriTri();
    PaperFusedTriTri(const PaperFusedTriTri&) = delete;
    PaperFusedTriTri& operator=(const PaperFusedTriTri&) = delete;

    /// Uploads `positions`, runs the scheme `warmup + timed` times (lists grown as needed) and
    /// returns the last run's pairs and the timed runs' GPU milliseconds.
    PaperFusedAnswer run(const std::vector<glm::vec3>& positions, int warmup, int timed);

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace glcollide::benchkit
