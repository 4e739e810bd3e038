#include "passes/radial_culling.hpp"

#include "core/gpu_layout.hpp"
#include "model/ghost_triangles.hpp"
#include "model/observer_frame.hpp"
#include "model/radial_surfaces.hpp"
#include "model/surface_clusters.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace glcollide::passes {

static_assert(GLC_GHOST_LOOP_MEAN == static_cast<std::uint32_t>(model::GhostKind::LoopMean));
static_assert(GLC_GHOST_APEX == static_cast<std::uint32_t>(model::GhostKind::Apex));
static_assert(GLC_GHOST_SKIRT == static_cast<std::uint32_t>(model::GhostKind::Skirt));

namespace {
/// A frame's four nodes, then the bits of its four weights: two uvec4.
void appendFrame(std::vector<std::uint32_t>& ranges, const std::array<std::uint32_t, 4>& nodes,
                 const std::array<float, 4>& weights) {
    ranges.insert(ranges.end(), nodes.begin(), nodes.end());
    for (const float w : weights) {
        std::uint32_t bits = 0;
        std::memcpy(&bits, &w, sizeof bits);
        ranges.push_back(bits);
    }
}

/// GLC_BIND_RADIAL_OBSERVER_NODES: per observer five uvec4 — (first node, node count, inward,
/// 0 centroid / 1 user point / 2 user segment), the frame of the point (or the segment's first
/// end), the frame of the segment's second end (RadialSurface).
std::vector<std::uint32_t> surfaceRanges(const std::vector<RadialSurface>& surfaces) {
    std::vector<std::uint32_t> ranges;
    for (const RadialSurface& s : surfaces) {
        const std::uint32_t user = s.segment ? 2u : s.framed ? 1u : 0u;
        ranges.insert(ranges.end(), {s.firstNode, s.nodeCount, s.inward ? 1u : 0u, user});
        appendFrame(ranges, s.frameNodes, s.frameWeights);
        appendFrame(ranges, s.segmentFrameNodes, s.segmentFrameWeights);
    }
    if (ranges.empty()) ranges.assign(20, 0u); // a buffer the consumers can bind
    return ranges;
}

/// The classified faces' observers: the real faces', then the ghost faces'.
std::vector<std::uint32_t> classifiedFaceObservers(const RadialCullingConfig& config) {
    std::vector<std::uint32_t> all = config.faceObserver;
    all.insert(all.end(), config.ghosts.faceObserver.begin(), config.ghosts.faceObserver.end());
    return all;
}

/// RadialGhostNodes' table: per ghost node two uvec4 (where its loop's nodes are listed, counted
/// from the buffer's start; how many; its kind; the node a skirt node hangs behind) and (its
/// depth's bits; the observer it places or GLC_RADIAL_NO_OBSERVER; that observer's depth's bits;
/// unused), then the loop nodes.
std::vector<std::uint32_t> ghostNodeTable(const RadialGhosts& g) {
    if (g.nodes.empty()) return {0u};
    const auto shift = static_cast<std::uint32_t>(8 * g.nodes.size());
    const auto bits = [](float v) {
        std::uint32_t b = 0;
        std::memcpy(&b, &v, sizeof b);
        return b;
    };
    std::vector<std::uint32_t> table;
    for (const RadialGhostNode& n : g.nodes)
        table.insert(table.end(), {shift + n.loopFirst, n.loopCount, static_cast<std::uint32_t>(n.kind),
                                   n.hang, bits(n.depth), n.observerOf, bits(n.observerDepth), 0u});
    table.insert(table.end(), g.loopNodes.begin(), g.loopNodes.end());
    return table;
}

std::uint32_t ghostNodeCount(const RadialGhosts& g) {
    return static_cast<std::uint32_t>(g.nodes.size());
}

/// Checks the ghosts' tables against each other and the surfaces; returns the ghost faces.
RadialGhostFaces checkedGhosts(const RadialCullingConfig& config) {
    const RadialGhosts& g = config.ghosts;
    const std::string name = RadialCullingPass::kName;
    const std::uint32_t nodes = ghostNodeCount(g);
    if (g.faces.size() != 3 * g.faceObserver.size())
        throw Error(name + ": " + std::to_string(g.faces.size()) + " ghost face indices for " +
                    std::to_string(g.faceObserver.size()) + " ghost faces");
    for (std::size_t k = 0; k < g.nodes.size(); ++k) {
        const RadialGhostNode& n = g.nodes[k];
        if (n.loopCount == 0 || std::uint64_t{n.loopFirst} + n.loopCount > g.loopNodes.size())
            throw Error(name + ": ghost node " + std::to_string(k) + "'s loop lies outside the " +
                        std::to_string(g.loopNodes.size()) + " loop nodes, or is empty");
        if (n.kind == model::GhostKind::Skirt && n.hang >= g.nodeCount)
            throw Error(name + ": ghost node " + std::to_string(k) + " hangs behind node " +
                        std::to_string(n.hang) + " of " + std::to_string(g.nodeCount));
    }
    for (std::uint32_t n : g.loopNodes)
        if (n >= g.nodeCount)
            throw Error(name + ": a ghost loop names node " + std::to_string(n) + " of " +
                        std::to_string(g.nodeCount));
    if (config.nodeObserver.size() != g.nodeCount)
        throw Error(name + ": a node observer table of " + std::to_string(config.nodeObserver.size()) +
                    " entries for " + std::to_string(g.nodeCount) + " nodes");
    std::vector<std::uint32_t> watchers(config.surfaces.size(), 0);
    for (const RadialGhostNode& n : g.nodes)
        if (n.observerOf != kNoRadialObserver) {
            if (n.observerOf >= config.surfaces.size() || n.kind != model::GhostKind::Apex)
                throw Error(name + ": a ghost node places observer " + std::to_string(n.observerOf) + " of " +
                            std::to_string(config.surfaces.size()) + ", or is no apex");
            ++watchers[n.observerOf];
        }
    for (std::size_t o = 0; o < config.surfaces.size(); ++o) {
        const RadialSurface& s = config.surfaces[o];
        if (std::uint64_t{s.firstGhostFace} + s.ghostFaceCount > g.faceObserver.size())
            throw Error(name + ": observer " + std::to_string(o) +
                        "'s ghost faces lie outside the ghost faces");
        if (watchers[o] != (s.nodeCount == 0 ? 1u : 0u))
            throw Error(name + ": observer " + std::to_string(o) + " is placed by " +
                        std::to_string(watchers[o]) + " ghost nodes and " + std::to_string(s.nodeCount) +
                        " nodes");
    }
    return {g.nodeCount, nodes, g.faces};
}

/// Six times the volume a closed surface bounds, signed: positive when its faces wind outward
/// (faces[3k .. 3k + 2] index `positions`). Decides only which way the classification turns the
/// faces (decision 0025, "Orientation").
double signedVolume6(const std::vector<std::uint32_t>& faces, std::uint32_t firstFace,
                     std::uint32_t faceCount, const std::vector<glm::dvec3>& positions) {
    double sum = 0.0;
    for (std::size_t f = firstFace; f < std::size_t{firstFace} + faceCount; ++f)
        sum += glm::dot(positions[faces[3 * f]],
                        glm::cross(positions[faces[3 * f + 1]], positions[faces[3 * f + 2]]));
    return sum;
}

/// Object `r`'s faces in its own node indices.
std::vector<model::Triangle> objectFaces(const model::FlatModel& model, const model::ObjectRange& r) {
    std::vector<model::Triangle> faces;
    for (std::uint32_t f = 0; f < r.faceCount; ++f) {
        const std::uint32_t* n = &model.faceIndices[3 * std::size_t{r.firstFace + f}];
        faces.push_back({n[0] - r.firstNode, n[1] - r.firstNode, n[2] - r.firstNode});
    }
    return faces;
}

/// Object `r`'s initial node positions.
std::vector<glm::dvec3> objectPositions(const model::FlatModel& model, const model::ObjectRange& r) {
    return {model.positions.begin() + r.firstNode, model.positions.begin() + r.firstNode + r.nodeCount};
}

/// The ghost closure of one object (docs/culling.md, "Ghost triangles"), in the object's own node
/// indices (ghost node g is nodeCount + g); empty when no loop is filled or the closed surface is
/// not one closed, consistently oriented, connected surface. `inward`: the closed surface winds
/// inward at the model's positions.
model::GhostTriangles objectGhosts(const model::FlatModel& model, const model::ObjectRange& r,
                                   double maxPerimeter, bool& inward, double& roundness) {
    const std::vector<model::Triangle> faces = objectFaces(model, r);
    const std::vector<glm::dvec3> positions = objectPositions(model, r);
    model::GhostTriangles ghosts = model::ghostTriangles(faces, positions, {maxPerimeter});
    std::vector<std::uint32_t> closed;
    for (const model::Triangle& t : faces) closed.insert(closed.end(), t.begin(), t.end());
    for (const model::Triangle& t : ghosts.faces) closed.insert(closed.end(), t.begin(), t.end());
    const auto all = static_cast<std::uint32_t>(closed.size() / 3);
    if (ghosts.faces.empty() || !model::isClosedOrientedConnected(closed, 0, all)) return {};
    std::vector<glm::dvec3> withGhosts = positions;
    for (const glm::dvec3& p : model::ghostNodePositions(ghosts, positions)) withGhosts.push_back(p);
    const double volume6 = signedVolume6(closed, 0, all, withGhosts);
    inward = volume6 < 0.0;
    double area = 0.0;
    for (std::size_t f = 0; f < closed.size(); f += 3)
        area += 0.5 * glm::length(glm::cross(withGhosts[closed[f + 1]] - withGhosts[closed[f]],
                                             withGhosts[closed[f + 2]] - withGhosts[closed[f]]));
    roundness = area > 0.0 ? std::abs(volume6) / 6.0 / std::pow(area, 1.5) : 0.0;
    return ghosts;
}

/// Below this V / A^1.5 (the volume a closed surface bounds over its area to the power 1.5; a
/// sphere's is 1 / (6 √π) ≈ 0.094, the sleeve closed by its cuffs' fans about 0.07, a flat sheet
/// closed by a flat fan 0) an object closed by ghosts is too flat for one observer inside it:
/// "observers": "auto" cuts it into clusters instead (docs/culling.md, "Clusters").
constexpr double kFlatRoundness = 0.01;

/// Appends the ghost fans of one surface, in object-local node indices (a node >= `objectNodes` is
/// the object's ghost node index − objectNodes), to the model's ghosts.
void appendGhostFans(RadialGhosts& g, const model::ObjectRange& r, std::uint32_t observer,
                     const std::vector<model::Triangle>& faces) {
    const auto base = static_cast<std::uint32_t>(g.nodes.size());
    for (const model::Triangle& t : faces) {
        for (std::uint32_t n : t)
            g.faces.push_back(n < r.nodeCount ? r.firstNode + n : g.nodeCount + base + (n - r.nodeCount));
        g.faceObserver.push_back(observer);
    }
}

/// Appends a loop (object-local nodes) to the ghosts' loop nodes; returns where it starts.
std::uint32_t appendLoop(RadialGhosts& g, const model::ObjectRange& r,
                         const std::vector<std::uint32_t>& loop) {
    const auto first = static_cast<std::uint32_t>(g.loopNodes.size());
    for (std::uint32_t n : loop) g.loopNodes.push_back(r.firstNode + n);
    return first;
}

/// Appends the fans of model::ghostTriangles (object-local nodes) for `observer`: their faces, and a
/// ghost node at the mean of each filled loop.
void appendMeanFans(RadialGhosts& g, const model::ObjectRange& r, std::uint32_t observer,
                    const model::GhostTriangles& fans) {
    appendGhostFans(g, r, observer, fans.faces);
    for (std::uint32_t loop : fans.ghostNodeLoop) {
        const std::vector<std::uint32_t>& nodes = fans.loops[loop].nodes;
        RadialGhostNode node;
        node.loopFirst = appendLoop(g, r, nodes);
        node.loopCount = static_cast<std::uint32_t>(nodes.size());
        g.nodes.push_back(node);
    }
}

/// Ties a user observer at `point` to four of object `r`'s nodes (model::observerFrame).
void frameObserver(std::array<std::uint32_t, 4>& nodes, std::array<float, 4>& weights,
                   const model::FlatModel& model, const model::ObjectRange& r, std::size_t object,
                   const glm::dvec3& point) {
    model::ObserverFrame frame;
    try {
        frame = model::observerFrame(objectPositions(model, r), point);
    } catch (const std::invalid_argument& e) {
        throw Error(std::string(RadialCullingPass::kName) + ": object " + std::to_string(object) +
                    "'s observer: " + e.what());
    }
    for (std::size_t k = 0; k < 4; ++k) {
        nodes[k] = r.firstNode + frame.nodes[k];
        weights[k] = static_cast<float>(frame.weights[k]);
    }
}

/// The object's user observer, a point or a segment (settings.objectObservers, objectObserverEnds).
void userObserver(RadialSurface& surface, const model::FlatModel& model, const model::ObjectRange& r,
                  std::size_t object, const RadialObserverSettings& settings) {
    if (object >= settings.objectObservers.size() || !settings.objectObservers[object]) return;
    frameObserver(surface.frameNodes, surface.frameWeights, model, r, object,
                  *settings.objectObservers[object]);
    surface.framed = true;
    if (object >= settings.objectObserverEnds.size() || !settings.objectObserverEnds[object]) return;
    frameObserver(surface.segmentFrameNodes, surface.segmentFrameWeights, model, r, object,
                  *settings.objectObserverEnds[object]);
    surface.segment = true;
}

/// Object `r` (the model's object `object`) as one observed surface, closed by itself or by ghosts;
/// false when it cannot be.
bool observeObject(RadialCullingConfig& config, const model::FlatModel& model, const model::ObjectRange& r,
                   std::size_t object, const RadialObserverSettings& settings) {
    const auto observer = static_cast<std::uint32_t>(config.surfaces.size());
    RadialSurface surface{r.firstNode, r.nodeCount,
                          static_cast<std::uint32_t>(config.ghosts.faceObserver.size()), 0};
    userObserver(surface, model, r, object, settings);
    if (model::isClosedOrientedConnected(model.faceIndices, r.firstFace, r.faceCount)) {
        surface.inward = signedVolume6(model.faceIndices, r.firstFace, r.faceCount, model.positions) < 0.0;
    } else {
        if (settings.observers == RadialObservers::Clusters || !(settings.ghostMaxPerimeter > 0.0))
            return false;
        double roundness = 0.0;
        const model::GhostTriangles ghosts =
            objectGhosts(model, r, settings.ghostMaxPerimeter, surface.inward, roundness);
        if (ghosts.faces.empty()) return false;
        // "auto": a closure with (almost) no inside has nowhere to put an observer; clusters serve it.
        if (settings.observers == RadialObservers::Auto && roundness < kFlatRoundness) return false;
        appendMeanFans(config.ghosts, r, observer, ghosts);
        surface.ghostFaceCount = static_cast<std::uint32_t>(ghosts.faces.size());
    }
    for (std::uint32_t f = 0; f < r.faceCount; ++f) {
        config.faceObserver[r.firstFace + f] = observer;
    }
    config.surfaces.push_back(std::move(surface));
    return true;
}

/// Object `r` cut into clusters of its initial shape (docs/culling.md, "Clusters"), each closed by
/// model::closeCluster and watched from behind; a cluster whose loops cannot all be filled gets none.
void observeClusters(RadialCullingConfig& config, const model::FlatModel& model, const model::ObjectRange& r,
                     const RadialObserverSettings& settings) {
    const std::vector<model::Triangle> faces = objectFaces(model, r);
    const std::vector<glm::dvec3> positions = objectPositions(model, r);
    const model::SurfaceClusters clusters =
        model::surfaceClusters(faces, positions, {settings.clusterMaxAngle, settings.clusterMaxFaces});
    std::vector<std::vector<std::uint32_t>> members(clusters.count);
    for (std::uint32_t f = 0; f < r.faceCount; ++f) members[clusters.faceCluster[f]].push_back(f);
    const double depth = model::clusterObserverDepth(settings.clusterMaxAngle);
    for (const std::vector<std::uint32_t>& member : members) {
        std::vector<model::Triangle> clusterFaces;
        for (std::uint32_t f : member) clusterFaces.push_back(faces[f]);
        const model::ClusterClosure closure = model::closeCluster(clusterFaces, positions, depth);
        if (!closure.closed) {
            ++config.openClusters;
            continue;
        }
        const auto observer = static_cast<std::uint32_t>(config.surfaces.size());
        RadialSurface surface{r.firstNode, 0, static_cast<std::uint32_t>(config.ghosts.faceObserver.size()),
                              static_cast<std::uint32_t>(closure.faces.size()), closure.volume6 < 0.0};
        appendGhostFans(config.ghosts, r, observer, closure.faces);
        std::vector<std::uint32_t> loopFirst;
        for (const std::vector<std::uint32_t>& loop : closure.loops)
            loopFirst.push_back(appendLoop(config.ghosts, r, loop));
        for (const model::ClusterGhostNode& c : closure.ghostNodes) {
            RadialGhostNode node;
            node.loopFirst = loopFirst[c.loop];
            node.loopCount = static_cast<std::uint32_t>(closure.loops[c.loop].size());
            node.kind = c.kind;
            node.hang = r.firstNode + c.hang;
            node.depth = static_cast<float>(c.depth);
            if (c.kind == model::GhostKind::Apex) {
                node.observerOf = observer;
                node.observerDepth = static_cast<float>(closure.observerDepth);
            }
            config.ghosts.nodes.push_back(node);
        }
        for (std::uint32_t f : member) {
            config.faceObserver[r.firstFace + f] = observer;
        }
        config.surfaces.push_back(std::move(surface));
        ++config.clusters;
    }
}

/// Object `r` (the model's object `object`) watched by its skeleton (docs/culling.md, "Skeletons"):
/// the faces nearest each bone, piece by piece (model::boneClusters), each closed by fans over all
/// its loops and watched by its bone, whose ends are tied to the object's nodes like a user
/// segment's; a piece that cannot be closed gets no observer.
void observeBones(RadialCullingConfig& config, const model::FlatModel& model, const model::ObjectRange& r,
                  std::size_t object, const std::vector<model::Bone>& bones) {
    const std::vector<model::Triangle> faces = objectFaces(model, r);
    const std::vector<glm::dvec3> positions = objectPositions(model, r);
    model::BoneClusters pieces;
    try {
        pieces = model::boneClusters(faces, positions, bones);
    } catch (const std::invalid_argument& e) {
        throw Error(std::string(RadialCullingPass::kName) + ": object " + std::to_string(object) +
                    "'s skeleton: " + e.what());
    }
    std::vector<std::vector<std::uint32_t>> members(pieces.count);
    for (std::uint32_t f = 0; f < r.faceCount; ++f) members[pieces.faceCluster[f]].push_back(f);
    for (std::uint32_t piece = 0; piece < pieces.count; ++piece) {
        std::vector<model::Triangle> pieceFaces;
        for (std::uint32_t f : members[piece]) pieceFaces.push_back(faces[f]);
        const model::BoneClosure closure = model::closeBoneCluster(pieceFaces, positions);
        if (!closure.closed) {
            ++config.openClusters;
            continue;
        }
        const auto observer = static_cast<std::uint32_t>(config.surfaces.size());
        RadialSurface surface{r.firstNode, r.nodeCount,
                              static_cast<std::uint32_t>(config.ghosts.faceObserver.size()),
                              static_cast<std::uint32_t>(closure.ghosts.faces.size()), closure.volume6 < 0.0};
        const model::Bone& bone = bones[pieces.clusterBone[piece]];
        frameObserver(surface.frameNodes, surface.frameWeights, model, r, object, bone[0]);
        frameObserver(surface.segmentFrameNodes, surface.segmentFrameWeights, model, r, object, bone[1]);
        surface.framed = surface.segment = true;
        appendMeanFans(config.ghosts, r, observer, closure.ghosts);
        for (std::uint32_t f : members[piece]) config.faceObserver[r.firstFace + f] = observer;
        config.surfaces.push_back(std::move(surface));
        ++config.clusters;
    }
}

/// Per node: the observer shared by every face around it (RadialCullingConfig::nodeObserver).
std::vector<std::uint32_t> nodeObservers(const RadialCullingConfig& config, const model::FlatModel& model) {
    constexpr std::uint32_t kUnset = kNoRadialObserver - 1u;
    std::vector<std::uint32_t> nodes(model.nodeCount(), kUnset);
    for (std::size_t f = 0; f < model.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) {
            std::uint32_t& n = nodes[model.faceIndices[3 * f + k]];
            n = n == kUnset || n == config.faceObserver[f] ? config.faceObserver[f] : kNoRadialObserver;
        }
    for (std::uint32_t& n : nodes)
        if (n == kUnset) n = kNoRadialObserver;
    return nodes;
}

} // namespace

RadialCullingConfig radialCullingConfig(const model::FlatModel& model,
                                        const RadialObserverSettings& settings) {
    RadialCullingConfig config;
    config.faceObserver.assign(model.faceCount(), kNoRadialObserver);
    config.ghosts.nodeCount = static_cast<std::uint32_t>(model.nodeCount());
    for (std::size_t object = 0; object < model.objects.size(); ++object) {
        const model::ObjectRange& r = model.objects[object];
        if (object < settings.objectSkeletons.size() && !settings.objectSkeletons[object].empty()) {
            observeBones(config, model, r, object, settings.objectSkeletons[object]);
            continue;
        }
        if (observeObject(config, model, r, object, settings)) continue;
        if (object < settings.objectObservers.size() && settings.objectObservers[object])
            throw Error(std::string(RadialCullingPass::kName) + ": object " + std::to_string(object) +
                        " has an observer, but its surface is not closed by itself or by ghost fans (holes "
                        "up to ghost_max_perimeter; \"observers\": \"auto\" leaves flat closures to "
                        "clusters): only a closed surface can wind around it");
        if (settings.observers != RadialObservers::Objects && r.faceCount > 0)
            observeClusters(config, model, r, settings);
    }
    config.nodeObserver = nodeObservers(config, model);
    return config;
}

RadialCullingConfig radialCullingConfig(const model::FlatModel& model, double ghostMaxPerimeter) {
    RadialObserverSettings settings;
    settings.ghostMaxPerimeter = ghostMaxPerimeter;
    settings.observers = RadialObservers::Objects;
    return radialCullingConfig(model, settings);
}

RadialCullingPass::RadialCullingPass(const RadialCullingConfig& config)
    : m_faceCount(static_cast<std::uint32_t>(config.faceObserver.size())),
      m_observerCount(static_cast<std::uint32_t>(config.surfaces.size())),
      m_ghostNodeCount(ghostNodeCount(config.ghosts)),
      m_ghostFaceCount(static_cast<std::uint32_t>(config.ghosts.faceObserver.size())),
      m_classify(classifiedFaceObservers(config), m_observerCount, checkedGhosts(config)),
      m_surfaces(gl::makeBuffer("radialSurfaces", surfaceRanges(config.surfaces))),
      m_ghostLoops(gl::makeBuffer("radialGhostLoops", ghostNodeTable(config.ghosts))),
      m_nodeObservers(gl::makeBuffer(
          "radialNodeObservers",
          config.nodeObserver.empty() ? std::vector<std::uint32_t>{kNoRadialObserver} : config.nodeObserver)),
      m_free("radialFree", (1u + (m_faceCount + 31u) / 32u) * sizeof(std::uint32_t)),
      m_moved("radialMoved", sizeof(std::uint32_t)),
      m_winding("radialWinding", 2 * std::size_t{std::max(m_observerCount, 1u)} * sizeof(std::uint32_t)),
      m_observers("radial_observers"), m_windingProgram("radial_winding"), m_freeProgram("radial_free"),
      m_hostCheck("radial_host_check") {
    for (std::uint32_t o : config.faceObserver) m_observedFaces += o != kNoRadialObserver ? 1u : 0u;
    m_freeProgram.set("u_faceCount", m_faceCount);
    m_freeProgram.set("u_observerCount", m_observerCount);
    m_windingProgram.set("u_faceCount", m_faceCount + m_ghostFaceCount);
    m_classify.setGhostUniforms(m_windingProgram);
    m_free.fill32(0u);
    m_winding.fill32(0u);
    if (m_ghostFaceCount > 0) { // compiled only for scenes with ghosts (start-up cost)
        m_ghostNodes.emplace("radial_ghost_nodes");
        m_ghostNodes->set("u_ghostNodeCount", m_ghostNodeCount);
    }
}

void RadialCullingPass::bindForConsumers() const {
    m_classify.faceObserver().bindStorage(GLC_BIND_RADIAL_FACE_OBSERVER);
    m_surfaces.bindStorage(GLC_BIND_RADIAL_OBSERVER_NODES);
    m_nodeObservers.bindStorage(GLC_BIND_RADIAL_NODE_OBSERVER);
    m_free.bindStorage(GLC_BIND_RADIAL_FREE);
}

void RadialCullingPass::run(AppendLists& lists) const {
    lists.resetStats({GLC_STAT_RADIAL_NON_POSITIVE, GLC_STAT_RADIAL_FREE, GLC_STAT_RADIAL_VIOLATED});
    bindForConsumers();
    m_classify.observers().bindStorage(GLC_BIND_RADIAL_OBSERVERS);
    m_classify.segments().bindStorage(GLC_BIND_RADIAL_SEGMENTS);
    m_observers.use();
    gl::ComputeProgram::dispatch(m_observerCount, 1, 1); // one work group per observer; counted
    if (m_ghostNodes) {
        m_ghostLoops.bindStorage(GLC_BIND_RADIAL_GHOST_LOOPS);
        m_classify.ghostPositions().bindStorage(GLC_BIND_RADIAL_GHOST_POSITIONS);
        m_ghostNodes->use();
        m_ghostNodes->dispatch1D(m_ghostNodeCount, GLC_WORKGROUP_SIZE);
    }
    m_winding.fill32(0u);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_classify.dispatchOnBoundPositions();
    // The observer check over the same stored positions (the ghost faces and positions are still
    // bound by the classification).
    m_winding.bindStorage(GLC_BIND_RADIAL_WINDING);
    m_windingProgram.use();
    m_windingProgram.dispatch1D(m_faceCount + m_ghostFaceCount, GLC_WORKGROUP_SIZE);
    m_free.fill32(0u);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_freeProgram.use();
    m_freeProgram.dispatch1D(std::max(m_faceCount, 1u), GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void RadialCullingPass::switchOff() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // after the last substep's reads of the mask
    const std::uint32_t off = 0;
    m_free.upload(0, sizeof off, &off);
}

bool RadialCullingPass::hostMovedNodes(const DeviceBuffers& b) const {
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, "RadialHostCheck", "positions");
    bindRequired(b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, "RadialHostCheck", "predictedPositions");
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    m_moved.fill32(0u);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_moved.bindStorage(GLC_BIND_RADIAL_MOVED);
    m_hostCheck.use();
    m_hostCheck.set("u_nodeCount", b.nodeCount);
    m_hostCheck.dispatch1D(std::max(b.nodeCount, 1u), GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::uint32_t moved = 0;
    m_moved.download(0, sizeof moved, &moved);
    return moved != 0;
}

std::vector<std::uint32_t> RadialCullingPass::readFreeMask() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> words((m_faceCount + 31u) / 32u);
    if (!words.empty())
        m_free.download(sizeof(std::uint32_t), words.size() * sizeof(std::uint32_t), words.data());
    return words;
}

std::vector<RadialObserver> RadialCullingPass::readGhostNodes() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> packed(2 * std::size_t{m_ghostNodeCount});
    if (!packed.empty())
        m_classify.ghostPositions().download(0, packed.size() * sizeof(glm::vec4), packed.data());
    std::vector<RadialObserver> out;
    for (std::size_t g = 0; g < m_ghostNodeCount; ++g)
        out.push_back({glm::vec3(packed[2 * g]), glm::vec3(packed[2 * g + 1])});
    return out;
}

std::vector<RadialWinding> RadialCullingPass::readWinding() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> words(2 * std::size_t{m_observerCount});
    if (!words.empty()) m_winding.download(0, words.size() * sizeof(std::uint32_t), words.data());
    std::vector<RadialWinding> out;
    for (std::size_t o = 0; o < m_observerCount; ++o)
        out.push_back({static_cast<std::int32_t>(words[2 * o]), words[2 * o + 1] != 0});
    return out;
}

std::vector<RadialObserver> RadialCullingPass::readObservers() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> packed(2 * std::size_t{m_observerCount}), segments(packed.size());
    if (!packed.empty()) {
        m_classify.observers().download(0, packed.size() * sizeof(glm::vec4), packed.data());
        m_classify.segments().download(0, segments.size() * sizeof(glm::vec4), segments.data());
    }
    std::vector<RadialObserver> out;
    for (std::size_t o = 0; o < m_observerCount; ++o) {
        RadialObserver observer{glm::vec3(packed[2 * o]), glm::vec3(packed[2 * o + 1]), std::nullopt};
        if (segments[2 * o].w != 0.0f)
            observer.segment =
                std::array<glm::vec3, 2>{glm::vec3(segments[2 * o]), glm::vec3(segments[2 * o + 1])};
        out.push_back(observer);
    }
    return out;
}

} // namespace glcollide::passes
