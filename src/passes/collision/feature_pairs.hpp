#pragma once
// FeaturePairs, the Representative-Triangle expansion (seeds/001, Kim 2024;
// docs/design/decisions/0018-representative-triangles.md): one kernel (feature_pairs.comp),
// dispatched indirectly over the candidate face pairs, appends each owned vertex against the
// other face to GLC_LIST_VERTEX_FACE and each owned edge against each owned edge of the other face
// to GLC_LIST_EDGE_EDGE. The contact response then runs one invocation per feature pair. Reads
// the faces (GLC_BIND_FACES) and the face table (GLC_BIND_FACE_INFO), which the collision
// detection binds. CPU twin: cpu::featurePairs.

#include "gl/program.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/collision/stage_chain.hpp"

#include <cstdint>

namespace glcollide::passes {

class FeaturePairs {
  public:
    /// `ccdComplete` (continuous detection): also append, each once, the feature pairs that
    /// ownership loses in self-collisions (orphans; GLC_CCD_COMPLETE; reads the orphan table,
    /// GLC_BIND_FEATURE_ORPHANS).
    explicit FeaturePairs(bool ccdComplete);
    /// Declares the vertex-face and edge-edge lists with these first capacities (>= 1) and adds
    /// the FeaturePairs stage to `chain`. Call after the candidate list is declared and the stages
    /// that write it are added.
    void addStages(StageChain& chain, AppendLists& lists, std::uint32_t vertexFaceCapacity,
                   std::uint32_t edgeEdgeCapacity);

  private:
    gl::ComputeProgram m_program;
};

} // namespace glcollide::passes
