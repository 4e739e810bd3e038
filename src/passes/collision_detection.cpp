#include "passes/collision_detection.hpp"

#include "core/gpu_layout.hpp"
#include "gl/debug_output.hpp"
#include "model/face_box.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <algorithm>
#include <bit>
#include <cstddef>

namespace glcollide::passes {
namespace {

// Mirrors of shaders/common/collision.glsl and the work-group sizes of the collision shaders.
constexpr std::uint32_t kRuleBetweenObjects = 1u, kRuleSelf = 2u;
constexpr std::uint32_t kBBUpdateGroup = 64;   // bb_update.comp GLC_BB_UPDATE_GROUP
constexpr std::uint32_t kBoxPairTile = 8;      // bb_collision.comp box-pair variants: 8 x 8
constexpr std::uint32_t kFacePairTile = 16;    // tri_tri.comp GLC_TRITRI_ALL_PAIRS: 16 x 16
constexpr std::uint32_t kMaxGroups = 65535;    // GL 4.3 minimum of GL_MAX_COMPUTE_WORK_GROUP_COUNT
constexpr std::size_t kPairBytes = 2 * sizeof(std::uint32_t); // uvec2

// Counter words of GpuCollisionCounters; the three list capacities follow from kBoxPairCapacity.
constexpr std::size_t kBoxPairCount = 0, kCandidateCount = 1, kIntersectionCount = 2,
                      kExactFallbackCount = 3, kBoxPairCapacity = 4, kUndecidedCount = 8;
static_assert(offsetof(gpu::GpuCollisionCounters, undecidedCount) == kUndecidedCount * sizeof(std::uint32_t));
// Lists with indirect dispatch arguments (u_source and slot of collision_dispatch_args.comp).
constexpr std::uint32_t kBoxPairList = 0, kCandidateList = 1, kUndecidedList = 2;

template <typename T>
gl::Buffer makeBuffer(const char* label, const std::vector<T>& data) {
    return gl::Buffer(label, data.size() * sizeof(T), data.empty() ? nullptr : data.data());
}

bool robust(const CollisionConfig& c) { return c.settings.precision == TriTriPrecision::Robust; }

std::vector<std::string> triTriDefines(const CollisionConfig& c) {
    std::vector<std::string> d;
    if (c.settings.precision == TriTriPrecision::Robust) d.emplace_back("GLC_PRECISION_ROBUST");
    if (c.settings.broadPhase != BroadPhase::Octree) d.emplace_back("GLC_TRITRI_ALL_PAIRS");
    if (c.settings.broadPhase == BroadPhase::Masked) d.emplace_back("GLC_TRITRI_MASKED");
    return d;
}

/// Dispatches `program` over the upper triangle (x >= y, diagonal included) of an n x n grid of
/// invocations in groups of tile x tile, in chunks of at most 65535 groups per dimension; the
/// shader adds (u_originX, u_originY) and rejects the invocations below the diagonal itself.
void dispatchUpperTriangle(const gl::ComputeProgram& program, std::uint32_t n, std::uint32_t tile) {
    if (n == 0) return;
    const std::uint32_t groups = (n + tile - 1) / tile;
    for (std::uint32_t gy = 0; gy < groups; gy += kMaxGroups) {
        const std::uint32_t ny = std::min(kMaxGroups, groups - gy);
        // Chunks wholly below the diagonal hold no invocation with x >= y.
        for (std::uint32_t gx = gy; gx < groups; gx += kMaxGroups) {
            const std::uint32_t nx = std::min(kMaxGroups, groups - gx);
            program.set("u_originX", gx * tile);
            program.set("u_originY", gy * tile);
            glDispatchCompute(nx, ny, 1);
        }
        if (gy + ny >= groups) break;
    }
}

} // namespace

CollisionDetection::CollisionDetection(const CollisionConfig& config, const model::FlatModel& model)
    : m_config(config),
      m_pairRules((config.betweenObjects ? kRuleBetweenObjects : 0u) | (config.selfCollisions ? kRuleSelf : 0u)),
      m_halfThickness(model::halfThicknessFloat(config.settings.thickness)),
      m_faceCount(static_cast<std::uint32_t>(model.faceCount())),
      m_layout(model::buildOctree(model, config.settings.octreeDepth)) {
    const CollisionSettings& s = config.settings;
    if (s.initialCapacity < 1) throw Error("collision: initialCapacity must be at least 1");
    const auto initial = [&](std::uint32_t listCapacity) { return listCapacity ? listCapacity : s.initialCapacity; };
    if (config.listByteLimit != 0) {
        m_listByteLimit = config.listByteLimit;
    } else {
        GLint64 limit = 0;
        glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &limit);
        m_listByteLimit = static_cast<std::uint64_t>(std::max<GLint64>(limit, GLint64{1} << 24)); // 2^24: GL 4.3's minimum
    }
    if (!(s.thickness > 0.0)) throw Error("collision: thickness must be positive");
    const BroadPhase mode = s.broadPhase;

    std::vector<gpu::GpuFaceInfo> info(m_faceCount);
    for (std::uint32_t f = 0; f < m_faceCount; ++f)
        info[f] = {m_layout.faceObject[f], m_layout.faceBox[f], m_layout.faceOwned[f], 0u};
    m_faceInfo = makeBuffer("faceInfo", info);
    std::vector<gpu::GpuObject> objects;
    for (std::size_t o = 0; o < model.objects.size(); ++o) {
        const model::ObjectRange& r = model.objects[o];
        objects.push_back({r.firstNode, r.nodeCount, r.firstFace, r.faceCount, r.firstSpring, r.springCount,
                           m_layout.firstBox[o], m_layout.closed[o]});
    }
    m_objects = makeBuffer("objects", objects);

    if (mode != BroadPhase::AllPairs) {
        m_boxes = gl::Buffer("boxes", std::size_t{m_layout.boxCount} * sizeof(gpu::GpuBox));
        m_boxFaceOffsets = makeBuffer("boxFaceOffsets", m_layout.boxFaces.offsets);
        m_boxFaceList = makeBuffer("boxFaceList", m_layout.boxFaces.items);
        // The expansion shares a box pair's nA x nB face pairs out over 64 threads x slices so no
        // invocation loops more than 2^15 times (llvmpipe stops an invocation after 65535 loop
        // iterations); its flat index needs nA x nB < 2^32.
        std::uint64_t largest = 0;
        for (std::size_t b = 0; b + 1 < m_layout.boxFaces.offsets.size(); ++b)
            largest = std::max<std::uint64_t>(largest, m_layout.boxFaces.offsets[b + 1] - m_layout.boxFaces.offsets[b]);
        if (largest >= 65536)
            throw Error("collision octree: a leaf box holds " + std::to_string(largest) +
                        " faces (at most 65535); raise /collision/octree_depth");
        m_expandSlices = static_cast<std::uint32_t>(std::max<std::uint64_t>(1, (largest * largest + 64 * 32768 - 1) / (64 * 32768)));
        m_bbUpdate = gl::ComputeProgram("bb_update");
        m_bbUpdate.set("u_boxCount", m_layout.boxCount);
        m_bbUpdate.set("u_halfThickness", m_halfThickness);
    }
    if (mode == BroadPhase::Masked) {
        if (m_layout.boxCount > kMaxGroups)
            throw Error("collision: masked broad phase supports at most 65535 leaf boxes (the mask is boxes^2)");
        m_boxMaskBuffer = gl::Buffer("boxMask", std::size_t{m_layout.boxCount} * m_layout.boxCount * sizeof(std::uint32_t));
        m_boxMask = gl::ComputeProgram("bb_collision", {"GLC_BB_MASK"});
    }
    if (mode == BroadPhase::Octree) {
        m_boxPairs = gl::ComputeProgram("bb_collision");
        m_expand = gl::ComputeProgram("bb_collision", {"GLC_BB_EXPAND"});
        m_boxPairCapacity = initial(config.boxPairCapacity);
        m_boxPairList = gl::Buffer("boxPairs", std::size_t{m_boxPairCapacity} * kPairBytes);
    }
    // Indirect dispatch arguments (writeDispatchArgs): the expansion and TriTri in octree mode,
    // TriTriExact with robust precision.
    if (mode == BroadPhase::Octree || robust(config)) {
        m_args = gl::ComputeProgram("collision_dispatch_args");
        m_dispatchArgs = gl::Buffer("dispatchArgs", 3 * 3 * sizeof(std::uint32_t));
    }
    if (robust(config)) m_triTriExact = gl::ComputeProgram("tri_tri_exact");
    for (const gl::ComputeProgram* p : {&m_boxPairs, &m_boxMask, &m_expand}) {
        if (p->name() == 0) continue; // not used by this mode
        p->set("u_pairRules", m_pairRules);
        p->set("u_boxCount", m_layout.boxCount);
        p->set("u_boxesPerObject", m_layout.boxesPerObject);
        p->set("u_halfThickness", m_halfThickness);
    }
    m_triTri = gl::ComputeProgram("tri_tri", triTriDefines(config));
    m_triTri.set("u_faceCount", m_faceCount);
    m_triTri.set("u_pairRules", m_pairRules);
    m_triTri.set("u_halfThickness", m_halfThickness);
    m_triTri.set("u_boxCount", m_layout.boxCount);

    m_candidateCapacity = initial(config.candidateCapacity);
    m_intersectionCapacity = initial(config.intersectionCapacity);
    m_candidates = gl::Buffer("candidates", std::size_t{m_candidateCapacity} * kPairBytes);
    if (robust(config)) m_undecided = gl::Buffer("undecided", std::size_t{m_candidateCapacity} * sizeof(std::uint32_t));
    m_intersections = gl::Buffer("intersections", std::size_t{m_intersectionCapacity} * kPairBytes);
    m_counters = gl::Buffer("collisionCounters", sizeof(gpu::GpuCollisionCounters));
    writeCapacities();
}

std::vector<std::string> CollisionDetection::passNames() const {
    if (m_config.settings.broadPhase == BroadPhase::AllPairs) return {kTriTri};
    return {kBBUpdate, kBBCollision, kTriTri};
}

template <typename F>
void CollisionDetection::timed(gl::GpuTimer* timer, std::size_t section, const char* name, F&& work) const {
    gl::DebugGroup group(name);
    if (timer) timer->begin(section);
    work();
    if (timer) timer->end(section);
}

void CollisionDetection::bindInputs(const DeviceBuffers& b) const {
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, "CollisionDetection", "positions");
    bindRequired(b.faces, GLC_BIND_FACES, "CollisionDetection", "faces");
    m_faceInfo.bindStorage(GLC_BIND_FACE_INFO);
    m_objects.bindStorage(GLC_BIND_OBJECTS);
    m_candidates.bindStorage(GLC_BIND_FACE_PAIRS);
    m_intersections.bindStorage(GLC_BIND_INTERSECTIONS);
    m_counters.bindStorage(GLC_BIND_COLLISION_COUNTERS);
    if (m_boxes) {
        m_boxes.bindStorage(GLC_BIND_BOXES);
        m_boxFaceOffsets.bindStorage(GLC_BIND_BOX_FACE_OFFSETS);
        m_boxFaceList.bindStorage(GLC_BIND_BOX_FACE_LIST);
    }
    if (m_boxMaskBuffer) m_boxMaskBuffer.bindStorage(GLC_BIND_BOX_MASK);
    if (m_boxPairList) m_boxPairList.bindStorage(GLC_BIND_BOX_PAIRS);
    if (m_dispatchArgs) m_dispatchArgs.bindStorage(GLC_BIND_DISPATCH_ARGS);
    if (m_undecided) m_undecided.bindStorage(GLC_BIND_UNDECIDED);
}

void CollisionDetection::bindOutputs() const {
    m_faceInfo.bindStorage(GLC_BIND_FACE_INFO);
    m_objects.bindStorage(GLC_BIND_OBJECTS);
    m_candidates.bindStorage(GLC_BIND_FACE_PAIRS);
    m_intersections.bindStorage(GLC_BIND_INTERSECTIONS);
    m_counters.bindStorage(GLC_BIND_COLLISION_COUNTERS);
}

void CollisionDetection::writeCapacities() {
    const std::uint32_t caps[3] = {m_boxPairCapacity, m_candidateCapacity, m_intersectionCapacity};
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // after earlier shader writes to the counters
    m_counters.upload(kBoxPairCapacity * sizeof(std::uint32_t), sizeof caps, caps);
}

void CollisionDetection::resetCounts(bool boxPairs, bool candidates, bool intersections) {
    // Counts of later stages are reset with their producer's, since they depend on its output;
    // the exact-fallback count belongs to the last TriTri run. contactCount (the response's) is
    // cleared once per detect().
    if (!boxPairs && !candidates && !intersections) return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::uint32_t zeros[4] = {0, 0, 0, 0};
    const std::size_t first = boxPairs ? kBoxPairCount : candidates ? kCandidateCount : kIntersectionCount;
    m_counters.upload(first * sizeof(std::uint32_t), (kExactFallbackCount + 1 - first) * sizeof(std::uint32_t), zeros);
    m_counters.upload(kUndecidedCount * sizeof(std::uint32_t), sizeof(std::uint32_t), zeros); // TriTri's, like the intersections
}

void CollisionDetection::readCounters() {
    m_counters.download(0, sizeof m_rawCounters, m_rawCounters.data());
    m_counts.boxPairs = m_rawCounters[kBoxPairCount];
    m_counts.candidates = m_rawCounters[kCandidateCount];
    m_counts.intersections = m_rawCounters[kIntersectionCount];
    m_counts.exactFallbacks = m_rawCounters[kExactFallbackCount];
    m_counts.undecided = m_rawCounters[kUndecidedCount];
}

void CollisionDetection::grow(gl::Buffer& list, std::uint32_t& capacity, std::uint32_t count, const char* label,
                              std::uint32_t& growths) {
    ++growths;
    // A list is bound whole as one shader storage block: past the limit the pairs cannot be
    // stored, and dropping them silently is not an option.
    const std::uint64_t maxEntries = m_listByteLimit / kPairBytes;
    if (count > maxEntries)
        throw Error(std::string("collision list '") + label + "' needs " + std::to_string(count) + " pairs (" +
                    std::to_string(std::uint64_t{count} * kPairBytes) + " bytes), more than one shader storage "
                    "block can hold on this device (GL_MAX_SHADER_STORAGE_BLOCK_SIZE, " + std::to_string(m_listByteLimit) +
                    " bytes); no pair was dropped: use fewer or smaller bodies, a smaller thickness or a deeper octree");
    // Next power of two (fewer regrowths) when it fits; 2^31 and up: exact size.
    capacity = count <= (1u << 31) ? std::bit_ceil(count) : count;
    if (capacity > maxEntries) capacity = count;
    list = gl::Buffer(label, std::size_t{capacity} * kPairBytes);
    // The undecided list holds candidate indices: it has the candidates' capacity, so it never
    // overflows on its own.
    if (&list == &m_candidates && m_undecided)
        m_undecided = gl::Buffer("undecided", std::size_t{capacity} * sizeof(std::uint32_t));
    writeCapacities();
}

void CollisionDetection::runBBUpdate() const {
    m_bbUpdate.use();
    m_bbUpdate.dispatch1D(m_layout.boxCount * kBBUpdateGroup, kBBUpdateGroup); // one group per box
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

// Indirect dispatch arguments, one slot per list, written on the GPU from the list's count
// (collision_dispatch_args.comp): 0 box pairs (the expansion), 1 candidates (TriTri), 2 undecided
// candidates (TriTriExact).
void CollisionDetection::writeDispatchArgs(std::uint32_t list, std::uint32_t itemsPerGroup, std::uint32_t zGroups) const {
    m_args.use();
    m_args.set("u_source", list);
    m_args.set("u_invocationsPerGroup", itemsPerGroup);
    m_args.set("u_slot", list);
    m_args.set("u_z", zGroups);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT);
}

void CollisionDetection::dispatchIndirect(const gl::ComputeProgram& program, std::uint32_t list) const {
    program.use();
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, m_dispatchArgs.name());
    glDispatchComputeIndirect(static_cast<GLintptr>(list * 3 * sizeof(std::uint32_t)));
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void CollisionDetection::runBoxPairs() const {
    m_boxPairs.use();
    dispatchUpperTriangle(m_boxPairs, m_layout.boxCount, kBoxPairTile);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    writeDispatchArgs(kBoxPairList, 1u, m_expandSlices); // the expansion: one group per box pair
}

void CollisionDetection::runExpand() const {
    dispatchIndirect(m_expand, kBoxPairList);
    writeDispatchArgs(kCandidateList, GLC_WORKGROUP_SIZE, 1u);
}

void CollisionDetection::runTriTriCandidates() const {
    dispatchIndirect(m_triTri, kCandidateList);
    runTriTriExact();
}

void CollisionDetection::runTriTriAllPairs(std::uint32_t faceCount) const {
    m_triTri.use();
    dispatchUpperTriangle(m_triTri, faceCount, kFacePairTile);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    runTriTriExact();
}

void CollisionDetection::runTriTriExact() const {
    if (m_triTriExact.name() == 0) return; // fast
    writeDispatchArgs(kUndecidedList, GLC_WORKGROUP_SIZE, 1u);
    dispatchIndirect(m_triTriExact, kUndecidedList);
}

CollisionCounts CollisionDetection::detect(const DeviceBuffers& buffers, gl::GpuTimer* timer, std::size_t timerBase) {
    if (buffers.faceCount != m_faceCount)
        throw Error("CollisionDetection: built for " + std::to_string(m_faceCount) + " faces, given " +
                    std::to_string(buffers.faceCount));
    m_counts = {};
    bindInputs(buffers);
    resetCounts(true, true, true);
    // A new substep: the contact response (which runs on this detection's candidates) counts
    // its contacts from zero too.
    const std::uint32_t zero = 0;
    m_counters.upload(offsetof(gpu::GpuCollisionCounters, contactCount), sizeof zero, &zero);
    const BroadPhase mode = m_config.settings.broadPhase;
    const std::size_t bbUpdate = timerBase, bbCollision = timerBase + 1,
                      triTri = mode == BroadPhase::AllPairs ? timerBase : timerBase + 2;
    const std::uint32_t faces = m_faceCount;
    std::uint32_t reruns = 0;

    if (mode != BroadPhase::AllPairs) timed(timer, bbUpdate, kBBUpdate, [&] { runBBUpdate(); });
    if (mode == BroadPhase::Octree) {
        // Sync point: one read-back after the whole chain; the expansion and TriTri are sized on
        // the GPU (indirect dispatch). A list that overflowed invalidates what was built from it,
        // so the rerun starts at the stage whose list overflowed.
        timed(timer, bbCollision, kBBCollision, [&] { runBoxPairs(); runExpand(); });
        timed(timer, triTri, kTriTri, [&] { runTriTriCandidates(); });
        for (readCounters();; readCounters()) {
            if (m_counts.boxPairs > m_boxPairCapacity) {
                grow(m_boxPairList, m_boxPairCapacity, m_counts.boxPairs, "boxPairs", m_counts.boxPairGrowths);
                bindInputs(buffers);
                resetCounts(true, true, true);
                timed(timer, bbCollision, kBBCollision, [&] { runBoxPairs(); runExpand(); });
                timed(timer, triTri, kTriTri, [&] { runTriTriCandidates(); });
            } else if (m_counts.candidates > m_candidateCapacity) {
                grow(m_candidates, m_candidateCapacity, m_counts.candidates, "candidates", m_counts.candidateGrowths);
                bindInputs(buffers);
                resetCounts(false, true, true);
                // The box pairs are intact: rerun from their expansion.
                timed(timer, bbCollision, kBBCollision, [&] { runExpand(); });
                timed(timer, triTri, kTriTri, [&] { runTriTriCandidates(); });
            } else if (m_counts.intersections > m_intersectionCapacity) {
                grow(m_intersections, m_intersectionCapacity, m_counts.intersections, "intersections", m_counts.intersectionGrowths);
                bindInputs(buffers);
                resetCounts(false, false, true);
                timed(timer, triTri, kTriTri, [&] { runTriTriCandidates(); });
            } else {
                break;
            }
            ++reruns;
        }
    } else {
        if (mode == BroadPhase::Masked)
            timed(timer, bbCollision, kBBCollision, [&] {
                m_boxMask.use();
                dispatchUpperTriangle(m_boxMask, m_layout.boxCount, kBoxPairTile);
                glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
            });
        // Sync point: one read-back after TriTri, which fills both lists in one pass.
        timed(timer, triTri, kTriTri, [&] { runTriTriAllPairs(faces); });
        for (readCounters(); m_counts.candidates > m_candidateCapacity ||
                             m_counts.intersections > m_intersectionCapacity;
             readCounters()) {
            if (m_counts.candidates > m_candidateCapacity)
                grow(m_candidates, m_candidateCapacity, m_counts.candidates, "candidates", m_counts.candidateGrowths);
            if (m_counts.intersections > m_intersectionCapacity)
                grow(m_intersections, m_intersectionCapacity, m_counts.intersections, "intersections", m_counts.intersectionGrowths);
            bindInputs(buffers);
            resetCounts(false, true, true);
            timed(timer, triTri, kTriTri, [&] { runTriTriAllPairs(faces); });
            ++reruns;
        }
    }
    m_counts.reruns = reruns;
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
    return readPairs(m_candidates, std::min(m_counts.candidates, m_candidateCapacity));
}

std::vector<std::array<std::uint32_t, 2>> CollisionDetection::readIntersections() const {
    return readPairs(m_intersections, std::min(m_counts.intersections, m_intersectionCapacity));
}

std::vector<std::string> CollisionDetection::allocatedLabels() const {
    std::vector<std::string> labels;
    for (const gl::Buffer* b : {&m_faceInfo, &m_objects, &m_boxes, &m_boxFaceOffsets, &m_boxFaceList,
                                &m_boxMaskBuffer, &m_boxPairList, &m_candidates, &m_undecided, &m_intersections,
                                &m_counters, &m_dispatchArgs})
        if (*b) labels.push_back(b->label());
    return labels;
}

std::size_t CollisionDetection::allocatedBytes() const {
    std::size_t bytes = 0;
    for (const gl::Buffer* b : {&m_faceInfo, &m_objects, &m_boxes, &m_boxFaceOffsets, &m_boxFaceList,
                                &m_boxMaskBuffer, &m_boxPairList, &m_candidates, &m_undecided, &m_intersections,
                                &m_counters, &m_dispatchArgs})
        if (*b) bytes += b->bytes();
    return bytes;
}

} // namespace glcollide::passes
