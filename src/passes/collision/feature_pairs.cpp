#include "passes/collision/feature_pairs.hpp"

#include "core/gpu_layout.hpp"

namespace glcollide::passes {
namespace {
constexpr std::size_t kPairBytes = 2 * sizeof(std::uint32_t); // uvec2
} // namespace

FeaturePairs::FeaturePairs(bool ccdComplete)
    : m_program("feature_pairs",
                ccdComplete ? std::vector<std::string>{"GLC_CCD_COMPLETE"} : std::vector<std::string>{}) {}

void FeaturePairs::addStages(StageChain& chain, AppendLists& lists, std::uint32_t vertexFaceCapacity,
                             std::uint32_t edgeEdgeCapacity) {
    lists.declare(GLC_LIST_VERTEX_FACE,
                  {"vertexFacePairs", "pairs", kPairBytes, GLC_BIND_VERTEX_FACE_PAIRS, vertexFaceCapacity});
    lists.declare(GLC_LIST_EDGE_EDGE,
                  {"edgeEdgePairs", "pairs", kPairBytes, GLC_BIND_EDGE_EDGE_PAIRS, edgeEdgeCapacity});
    chain.add({PassId::FeaturePairs, {GLC_LIST_VERTEX_FACE, GLC_LIST_EDGE_EDGE}, [this, &lists] {
                   lists.dispatchOver(m_program, GLC_LIST_CANDIDATES, GLC_WORKGROUP_SIZE);
               }});
}

} // namespace glcollide::passes
