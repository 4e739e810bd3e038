#include "passes/collision/narrow_phase_batch.hpp"

#include "core/gpu_layout.hpp"
#include "gl/handles.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/collision/stage_chain.hpp"

#include <glcollide/error.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <string>

namespace glcollide::passes {

TriTriQueryResult NarrowPhaseBatch::run(const std::vector<TriTriPair>& pairs) {
    TriTriQueryResult result;
    if (pairs.empty()) return result;
    if (pairs.size() > std::numeric_limits<std::uint32_t>::max() / 6u)
        throw Error(std::string(kName) + ": " + std::to_string(pairs.size()) +
                    " pairs are too many; split the batch");
    const auto count = static_cast<std::uint32_t>(pairs.size());

    // The model: corners a0 a1 a2 b0 b1 b2 of pair i are nodes 6i..6i+5 (w, the inverse mass,
    // is not read), faces 2i = (6i, 6i+1, 6i+2) and 2i+1 = (6i+3, 6i+4, 6i+5).
    std::vector<float> positions;
    std::vector<std::uint32_t> faces;
    std::vector<std::array<std::uint32_t, 2>> candidates;
    positions.reserve(std::size_t{24} * count);
    faces.reserve(std::size_t{6} * count);
    candidates.reserve(count);
    for (std::uint32_t i = 0; i < count; ++i) {
        for (std::size_t k = 0; k < 6; ++k) {
            positions.insert(positions.end(),
                             {pairs[i][3 * k], pairs[i][3 * k + 1], pairs[i][3 * k + 2], 1.0f});
            faces.push_back(6 * i + static_cast<std::uint32_t>(k));
        }
        candidates.push_back({2 * i, 2 * i + 1});
    }
    const gl::Buffer positionBuffer = gl::makeBuffer("batch_positions", positions);
    const gl::Buffer faceBuffer = gl::makeBuffer("batch_faces", faces);

    constexpr std::size_t kPairBytes = 2 * sizeof(std::uint32_t); // uvec2
    AppendLists& lists = m_lists;
    lists.declare(GLC_LIST_CANDIDATES, {"candidates", "pairs", kPairBytes, GLC_BIND_FACE_PAIRS, count});
    lists.declare(GLC_LIST_INTERSECTIONS,
                  {"intersections", "pairs", kPairBytes, GLC_BIND_INTERSECTIONS, count});
    lists.fillFromHost(GLC_LIST_CANDIDATES, candidates.data(), count);
    StageChain chain;
    m_narrowPhase.addStages(chain, lists);

    positionBuffer.bindStorage(GLC_BIND_NODE_POSITIONS);
    faceBuffer.bindStorage(GLC_BIND_FACES);
    (void)chain.run(lists, nullptr); // resets and fills the undecided and intersection lists
    NarrowPhase::throwIfExactPassFailed(lists);

    result.intersect.assign(count, 0);
    const std::uint32_t found = lists.storedCount(GLC_LIST_INTERSECTIONS);
    std::vector<std::array<std::uint32_t, 2>> intersections(found);
    if (found != 0)
        lists.storage(GLC_LIST_INTERSECTIONS).download(0, found * kPairBytes, intersections.data());
    for (const auto& pair : intersections) result.intersect.at(pair[0] / 2) = 1;
    result.exactFallbacks = lists.stat(GLC_STAT_EXACT_FALLBACKS);
    result.undecidedPairs = lists.declared(GLC_LIST_UNDECIDED) ? lists.count(GLC_LIST_UNDECIDED) : 0;
    return result;
}

} // namespace glcollide::passes
