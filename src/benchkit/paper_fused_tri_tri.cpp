#include "benchkit/paper_fused_tri_tri.hpp"

#include "model/face_box.hpp"
#include "model/octree_layout.hpp"
#include "gl/gpu_timer.hpp"
#include "core/gpu_layout.hpp"
#include "passes/broad_phase/leaf_boxes.hpp"
#include "passes/broad_phase/upper_triangle.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/collision/stage_chain.hpp"
#include "passes/collision_detection.hpp"

#include <glm/vec4.hpp>

#include <algorithm>
#include <optional>

namespace glcollide::benchkit {

using passes::PassId;

struct PaperFusedTriTri::Impl {
    model::OctreeLayout layout;
    passes::CollisionTables tables;
    gl::Buffer faces, positions;
    std::uint32_t faceCount;
    passes::AppendLists lists{0}; // the device's block limit
    std::optional<passes::LeafBoxes> leafBoxes;
    gl::Buffer mask;
    gl::ComputeProgram boxMask, fused;
    passes::StageChain chain;

    Impl(const model::FlatModel& model, const CollisionSettings& s, std::uint32_t rules, bool masked)
        : layout(model::buildOctree(model, s.octreeDepth)), tables(model, layout),
          faces(gl::makeBuffer("faces", model.faceIndices)),
          faceCount(static_cast<std::uint32_t>(model.faceCount())),
          fused(masked ? "paper_masked_tri_tri" : "paper_all_pairs_tri_tri") {
        const float halfThickness = model::halfThicknessFloat(s.thickness);
        lists.declare(GLC_LIST_CANDIDATES,
                      {"candidates", "pairs", 8, GLC_BIND_FACE_PAIRS, s.initialCapacity});
        lists.declare(GLC_LIST_INTERSECTIONS,
                      {"intersections", "pairs", 8, GLC_BIND_INTERSECTIONS, s.initialCapacity});
        fused.set("u_faceCount", faceCount);
        fused.set("u_pairRules", rules);
        fused.set("u_halfThickness", halfThickness);
        fused.set("u_boxCount", layout.boxCount);
        if (masked) {
            const passes::BroadPhaseContext context{model, layout, s, rules, halfThickness};
            leafBoxes.emplace(context);
            mask =
                gl::Buffer("boxMask", std::size_t{layout.boxCount} * layout.boxCount * sizeof(std::uint32_t));
            boxMask = gl::ComputeProgram("box_mask");
            boxMask.set("u_pairRules", rules);
            boxMask.set("u_boxCount", layout.boxCount);
            boxMask.set("u_boxesPerObject", layout.boxesPerObject);
            chain.add(leafBoxes->refitStage());
            chain.add({PassId::BBCollision, {}, [this] {
                           passes::dispatchUpperTriangle(boxMask, layout.boxCount, GLC_BOX_PAIR_TILE);
                       }});
        }
        chain.add({PassId::TriTri, {GLC_LIST_CANDIDATES, GLC_LIST_INTERSECTIONS}, [this] {
                       passes::dispatchUpperTriangle(fused, faceCount, GLC_FACE_PAIR_TILE);
                   }});
    }

    void bind() const {
        positions.bindStorage(GLC_BIND_NODE_POSITIONS);
        faces.bindStorage(GLC_BIND_FACES);
        tables.bind();
        if (leafBoxes) {
            leafBoxes->bind();
            mask.bindStorage(GLC_BIND_BOX_MASK);
        }
    }

    std::vector<std::array<std::uint32_t, 2>> read(std::uint32_t list) const {
        std::vector<std::array<std::uint32_t, 2>> pairs(lists.storedCount(list));
        lists.storage(list).download(0, pairs.size() * sizeof pairs[0], pairs.data());
        std::sort(pairs.begin(), pairs.end());
        return pairs;
    }
};

PaperFusedTriTri::PaperFusedTriTri(const model::FlatModel& model, const CollisionSettings& settings,
                                   bool betweenObjects, bool selfCollisions, bool masked)
    : m_impl(std::make_unique<Impl>(
          model, settings,
          (betweenObjects ? GLC_RULE_BETWEEN_OBJECTS : 0u) | (selfCollisions ? GLC_RULE_SELF : 0u), masked)) {
}

PaperFusedTriTri::~PaperFusedTriTri() = default;

PaperFusedAnswer PaperFusedTriTri::run(const std::vector<glm::vec3>& positions, int warmup, int timed) {
    Impl& d = *m_impl;
    std::vector<glm::vec4> packed;
    packed.reserve(positions.size());
    for (const glm::vec3& p : positions) packed.emplace_back(p, 0.0f);
    d.positions = gl::makeBuffer("positions", packed);
    PaperFusedAnswer answer;
    gl::GpuTimer timer(passes::kPassCount);
    for (int i = 0; i < warmup + timed; ++i) {
        timer.beginFrame();
        d.bind();
        d.chain.run(d.lists, &timer);
        const std::vector<double> ms = timer.resolveMilliseconds();
        double sum = 0.0;
        for (double m : ms) sum += m;
        if (i >= warmup) answer.milliseconds.push_back(sum);
    }
    answer.candidates = d.read(GLC_LIST_CANDIDATES);
    answer.intersections = d.read(GLC_LIST_INTERSECTIONS);
    return answer;
}

} // namespace glcollide::benchkit
