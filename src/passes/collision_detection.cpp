#include "passes/collision_detection.hpp"

#include "core/contact_params.hpp"

#include "model/face_box.hpp"
#include "model/features.hpp"
#include "core/gpu_layout.hpp"
#include "passes/broad_phase/create_broad_phase.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <algorithm>
#include <bit>

namespace glcollide::passes {
namespace {

constexpr std::size_t kPairBytes = 2 * sizeof(std::uint32_t); // uvec2

std::uint32_t pairRules(const CollisionConfig& c) {
    return (c.betweenObjects ? GLC_RULE_BETWEEN_OBJECTS : 0u) | (c.selfCollisions ? GLC_RULE_SELF : 0u);
}

const CollisionSettings& checked(const CollisionSettings& s) {
    if (s.initialCapacity < 1) throw Error("collision: initialCapacity must be at least 1");
    if (!(s.thickness > 0.0)) throw Error("collision: thickness must be positive");
    return s;
}

} // namespace

CollisionTables::CollisionTables(const model::FlatModel& model, const model::OctreeLayout& layout,
                                 bool withFeatureOrphans) {
    std::vector<gpu::GpuFaceInfo> info(model.faceCount());
    for (std::size_t f = 0; f < info.size(); ++f)
        info[f] = {layout.faceObject[f], layout.faceBox[f], layout.faceOwned[f], 0u};
    faceInfo = gl::makeBuffer("faceInfo", info);
    std::vector<gpu::GpuObject> table;
    for (std::size_t o = 0; o < model.objects.size(); ++o) {
        const model::ObjectRange& r = model.objects[o];
        table.push_back({r.firstNode, r.nodeCount, r.firstFace, r.faceCount, r.firstSpring, r.springCount,
                         layout.firstBox[o], layout.closed[o]});
    }
    objects = gl::makeBuffer("objects", table);
    if (withFeatureOrphans)
        featureOrphans =
            gl::makeBuffer("featureOrphans", model::orphanTable(model.faceIndices, model.nodeCount()));
}

void CollisionTables::bind() const {
    faceInfo.bindStorage(GLC_BIND_FACE_INFO);
    objects.bindStorage(GLC_BIND_OBJECTS);
    if (featureOrphans) featureOrphans.bindStorage(GLC_BIND_FEATURE_ORPHANS);
}

CollisionDetection::CollisionDetection(const CollisionConfig& config, const model::FlatModel& model)
    : m_faceCount(static_cast<std::uint32_t>(model.faceCount())),
      m_layout(model::buildOctree(model, checked(config.settings).octreeDepth)),
      m_tables(model, m_layout, config.settings.detection == Detection::Continuous),
      m_lists(std::make_unique<AppendLists>(config.listByteLimit)), m_narrowPhase(config.settings.precision),
      m_featurePairs(config.settings.detection == Detection::Continuous) {
    const CollisionSettings& s = config.settings;
    const auto initial = [&](std::uint32_t capacity) { return capacity ? capacity : s.initialCapacity; };
    m_lists->declare(GLC_LIST_CANDIDATES, {"candidates", "pairs", kPairBytes, GLC_BIND_FACE_PAIRS,
                                           initial(config.candidateCapacity)});
    m_lists->declare(GLC_LIST_INTERSECTIONS, {"intersections", "pairs", kPairBytes, GLC_BIND_INTERSECTIONS,
                                              initial(config.intersectionCapacity)});
    if (config.radial) {
        if (s.detection != Detection::Continuous)
            throw Error("collision: radial culling needs continuous detection");
        m_radial.emplace(*config.radial);
        m_chain.add({PassId::RadialCulling, {}, [this] {
                         if (m_radialOn)
                             m_radial->run(*m_lists);
                         else
                             m_radial->switchOff();
                     }});
    }
    // Without culling the consumers read a mask whose word 0 is 0 (and a face table of "none").
    m_radialNone =
        gl::makeBuffer("radialNone", std::vector<std::uint32_t>{0u, GLC_RADIAL_NO_OBSERVER, 0u, 0u});
    BroadPhaseContext context{model, m_layout, s};
    context.pairRules = pairRules(config);
    context.halfThickness = model::halfThicknessFloat(s.thickness);
    context.boxPairCapacity = config.boxPairCapacity;
    context.substepsPerFrame = config.substepsPerFrame;
    context.sweptBoxes = s.detection == Detection::Continuous;
    m_broadPhase = createBroadPhase(context);
    m_broadPhase->addStages(m_chain, *m_lists);
    m_narrowPhase.addStages(m_chain, *m_lists);
    // After the narrow phase: an overflow of the feature-pair lists (up to 15 per candidate, the
    // likeliest to overflow) reruns only the expansion (decision 0018).
    m_featurePairs.addStages(m_chain, *m_lists, initial(config.vertexFaceCapacity),
                             initial(config.edgeEdgeCapacity));
    if (s.detection == Detection::Continuous) {
        m_ccd.emplace(static_cast<std::uint32_t>(model.nodeCount()),
                      static_cast<std::uint32_t>(model.faceCount()), s.ccd.budget,
                      static_cast<float>(s.ccd.minSeparation));
        m_ccd->compactPairs(m_radial.has_value());
        m_ccd->addStages(m_chain, *m_lists);
        // The safe step cuts moving nodes only: a still pair must not keep its rounds going.
        if (s.response == ContactResponse::IntersectionFree) {
            m_ccd->skipStillPairs(true);
            m_ccd->relativeSeparation(true, static_cast<float>(safeStepSeparation(s)));
            m_ccd->skipTangledPairs(true);
        }
    }
}

std::uint32_t CollisionDetection::recheckCcd(const DeviceBuffers& buffers) {
    if (!m_ccd) throw Error("CollisionDetection::recheckCcd: needs continuous detection");
    bindRequired(buffers.positions, GLC_BIND_NODE_POSITIONS, "Ccd", "positions");
    bindRequired(buffers.faces, GLC_BIND_FACES, "Ccd", "faces");
    bindRequired(buffers.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, "Ccd", "predictedPositions");
    m_ccd->bind();
    m_lists->bind();
    // The free mask holds for the motion it was computed on, x0 -> the predicted x1; a cut step
    // need not be a prefix of it for every surface, so the recheck culls nothing.
    if (m_radial) {
        m_radial->bindForConsumers();
        m_radial->switchOff();
    }
    m_ccd->run(*m_lists, false); // x0 and the intersections are the detection's: the marks stand
    m_lists->readCounters();
    return m_lists->stat(GLC_STAT_CCD_VERTEX_FACE_HITS) + m_lists->stat(GLC_STAT_CCD_EDGE_EDGE_HITS);
}

const gl::Buffer& CollisionDetection::tangled() const {
    static const gl::Buffer kNone;
    return m_ccd && m_ccd->skipsTangledPairs() ? m_ccd->tangled() : kNone;
}

std::uint32_t CollisionDetection::readStat(std::uint32_t id) {
    m_lists->readCounters();
    return m_lists->stat(id);
}

const gl::Buffer& CollisionDetection::nodeToi() const {
    static const gl::Buffer kNone;
    return m_ccd ? m_ccd->nodeToi() : kNone;
}

std::vector<std::string> CollisionDetection::passNames() const {
    std::vector<std::string> names;
    for (PassId p : passes()) names.emplace_back(passName(p));
    return names;
}

CollisionCounts CollisionDetection::detect(const DeviceBuffers& buffers, gl::GpuTimer* timer) {
    if (buffers.faceCount != m_faceCount)
        throw Error("CollisionDetection: built for " + std::to_string(m_faceCount) + " faces, given " +
                    std::to_string(buffers.faceCount));
    bindRequired(buffers.positions, GLC_BIND_NODE_POSITIONS, "CollisionDetection", "positions");
    bindRequired(buffers.faces, GLC_BIND_FACES, "CollisionDetection", "faces");
    if (m_ccd) {
        bindRequired(buffers.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, "CollisionDetection",
                     "predictedPositions");
        m_ccd->bind();
    }
    m_tables.bind();
    if (m_radial) {
        m_radial->bindForConsumers();
    } else {
        m_radialNone.bindStorage(GLC_BIND_RADIAL_FREE);
        m_radialNone.bindStorage(GLC_BIND_RADIAL_FACE_OBSERVER);
        m_radialNone.bindStorage(GLC_BIND_RADIAL_NODE_OBSERVER);
    }
    m_broadPhase->bind();
    m_broadPhase->prepare();
    // Also clears the contact response's counter: a new substep counts its contacts from zero.
    const std::uint32_t reruns = m_chain.run(*m_lists, timer);
    const AppendLists& l = *m_lists;
    NarrowPhase::throwIfExactPassFailed(l);
    m_counts = {};
    m_counts.boxPairs = l.count(GLC_LIST_BOX_PAIRS); // 0 when the broad phase has no such list
    m_counts.candidates = l.count(GLC_LIST_CANDIDATES);
    m_counts.intersections = l.count(GLC_LIST_INTERSECTIONS);
    m_counts.undecided = l.count(GLC_LIST_UNDECIDED); // 0 with fast precision
    m_counts.exactFallbacks = l.stat(GLC_STAT_EXACT_FALLBACKS);
    m_counts.reruns = reruns;
    m_counts.boxPairGrowths = l.growths(GLC_LIST_BOX_PAIRS);
    m_counts.candidateGrowths = l.growths(GLC_LIST_CANDIDATES);
    m_counts.intersectionGrowths = l.growths(GLC_LIST_INTERSECTIONS);
    const BroadPhaseStats broad = m_broadPhase->stats();
    m_counts.bvhRebuilt = broad.rebuilt;
    m_counts.bvhRounds = broad.rounds;
    m_counts.bvhNodeVisits = l.stat(GLC_STAT_BVH_NODE_VISITS);
    m_counts.vertexFacePairs = l.count(GLC_LIST_VERTEX_FACE);
    m_counts.edgeEdgePairs = l.count(GLC_LIST_EDGE_EDGE);
    m_counts.vertexFaceGrowths = l.growths(GLC_LIST_VERTEX_FACE);
    m_counts.edgeEdgeGrowths = l.growths(GLC_LIST_EDGE_EDGE);
    m_counts.vertexFacePairsWithoutOwnership = 6 * std::uint64_t{m_counts.candidates};
    m_counts.edgeEdgePairsWithoutOwnership = 9 * std::uint64_t{m_counts.candidates};
    m_counts.ccdVertexFaceHits = l.stat(GLC_STAT_CCD_VERTEX_FACE_HITS);
    m_counts.ccdEdgeEdgeHits = l.stat(GLC_STAT_CCD_EDGE_EDGE_HITS);
    m_counts.ccdCapped = l.stat(GLC_STAT_CCD_CAPPED);
    m_counts.ccdBoxes = l.stat(GLC_STAT_CCD_BOXES);
    m_counts.ccdEarliestToi = std::bit_cast<float>(l.stat(GLC_STAT_CCD_EARLIEST_TOI));
    m_counts.ccdTangled = l.stat(GLC_STAT_CCD_TANGLED);
    m_counts.radialOn = m_radialOn;
    if (m_radial) {
        m_counts.radialObserved = m_radial->observedFaces();
        m_counts.radialGhostFaces = m_radial->ghostFaces();
    }
    if (m_radialOn) {
        m_counts.radialNonPositive = l.stat(GLC_STAT_RADIAL_NON_POSITIVE);
        m_counts.radialFree = l.stat(GLC_STAT_RADIAL_FREE);
        m_counts.radialViolated = l.stat(GLC_STAT_RADIAL_VIOLATED);
        m_counts.radialCulledTriTri = l.stat(GLC_STAT_RADIAL_CULLED_TRI_TRI);
        m_counts.radialCulledCcd = l.stat(GLC_STAT_RADIAL_CULLED_CCD);
    }
    return m_counts;
}

namespace {
std::vector<std::array<std::uint32_t, 2>> readPairs(const gl::Buffer& list, std::uint32_t count) {
    std::vector<std::array<std::uint32_t, 2>> pairs(count);
    static_assert(sizeof(std::array<std::uint32_t, 2>) == kPairBytes);
    list.download(0, std::size_t{count} * kPairBytes, pairs.data());
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}
} // namespace

std::vector<std::array<std::uint32_t, 2>> CollisionDetection::readCandidates() const {
    return readPairs(candidates(), m_lists->storedCount(GLC_LIST_CANDIDATES));
}

std::vector<std::array<std::uint32_t, 2>> CollisionDetection::readIntersections() const {
    return readPairs(intersections(), m_lists->storedCount(GLC_LIST_INTERSECTIONS));
}

std::vector<std::array<std::uint32_t, 2>> CollisionDetection::readVertexFacePairs() const {
    return readPairs(m_lists->storage(GLC_LIST_VERTEX_FACE), m_lists->storedCount(GLC_LIST_VERTEX_FACE));
}

std::vector<std::array<std::uint32_t, 2>> CollisionDetection::readEdgeEdgePairs() const {
    return readPairs(m_lists->storage(GLC_LIST_EDGE_EDGE), m_lists->storedCount(GLC_LIST_EDGE_EDGE));
}

const gl::Buffer& CollisionDetection::broadPhaseBuffer(const std::string& label) const {
    static const gl::Buffer kNone;
    for (const gl::Buffer* b : m_broadPhase->buffers())
        if (b->label() == label) return *b;
    return kNone;
}

std::vector<const gl::Buffer*> CollisionDetection::allBuffers() const {
    std::vector<const gl::Buffer*> all = {&m_tables.faceInfo, &m_tables.objects};
    if (m_tables.featureOrphans) all.push_back(&m_tables.featureOrphans);
    for (const gl::Buffer* b : m_broadPhase->buffers()) all.push_back(b);
    for (const gl::Buffer* b : m_lists->buffers()) all.push_back(b);
    if (m_ccd) all.push_back(&m_ccd->nodeToi());
    return all;
}

std::size_t CollisionDetection::broadPhaseBytes() const {
    std::size_t bytes = 0;
    for (const gl::Buffer* b : m_broadPhase->buffers()) bytes += b->bytes();
    return bytes;
}

std::vector<std::string> CollisionDetection::allocatedLabels() const {
    std::vector<std::string> labels;
    for (const gl::Buffer* b : allBuffers()) labels.push_back(b->label());
    return labels;
}

std::size_t CollisionDetection::allocatedBytes() const {
    std::size_t bytes = 0;
    for (const gl::Buffer* b : allBuffers()) bytes += b->bytes();
    return bytes;
}

} // namespace glcollide::passes
