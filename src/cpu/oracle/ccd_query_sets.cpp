#include "cpu/oracle/ccd_query_sets.hpp"

#include "scene/json_errors.hpp"
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>

#include <glm/common.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <utility>

namespace glcollide::cpu {
namespace {

using nlohmann::json;

/// A frame's faces, numbered as in the file: every face element must be one triangle, or the
/// box ids of the faces would not be the file's face numbers.
std::vector<MeshFace> triangleFaces(const detail::PlyMesh& mesh, const std::string& file) {
    for (std::size_t j = 0; j < mesh.faces.size(); ++j)
        if (mesh.faceElement[j] != j)
            throw Error(file + ": face " + std::to_string(mesh.faceElement[j]) +
                        " is not a triangle (the CCD sets number faces as the file does)");
    if (mesh.faces.size() != mesh.faceElements)
        throw Error(file + ": face " + std::to_string(mesh.faces.size()) +
                    " is not a triangle (the CCD sets number faces as the file does)");
    return {mesh.faces.begin(), mesh.faces.end()};
}

json readJson(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(file + ": cannot open file");
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    try {
        return json::parse(text);
    } catch (const json::exception& e) {
        throw Error(detail::invalidJsonMessage(e, text, file));
    }
}

const json& topArray(const json& doc, const std::string& file, const std::string& what) {
    if (!doc.is_array()) throw Error(file + ": expected an array of " + what + " at the top");
    return doc;
}

std::string pointer(std::size_t i) {
    return "/" + std::to_string(i);
}

/// A primitive's swept box, with up to three vertices and its box id.
struct SweptBox {
    glm::dvec3 lo, hi;
    std::array<std::uint32_t, 3> vertices;
    int vertexCount;
    std::uint64_t id;
    int group; // which side of a pair it may be (vertex-face: 0 vertex, 1 face; edge-edge: 0)
};

SweptBox sweptBox(const CcdStep& step, const std::uint32_t* vertices, int count, std::uint64_t id,
                  int group) {
    SweptBox box{step.start[vertices[0]], step.start[vertices[0]], {}, count, id, group};
    for (int k = 0; k < count; ++k) {
        box.vertices[k] = vertices[k];
        for (const glm::dvec3& p : {step.start[vertices[k]], step.end[vertices[k]]}) {
            box.lo = glm::min(box.lo, p);
            box.hi = glm::max(box.hi, p);
        }
    }
    return box;
}

bool shareAVertex(const SweptBox& a, const SweptBox& b) {
    for (int i = 0; i < a.vertexCount; ++i)
        for (int j = 0; j < b.vertexCount; ++j)
            if (a.vertices[i] == b.vertices[j]) return true;
    return false;
}

} // namespace

std::vector<MeshEdge> libiglEdges(const std::vector<MeshFace>& faces) {
    // Key hi * 2^32 + lo: sorting the keys sorts by hi, then lo (igl::edges walks the columns of
    // the adjacency matrix, one column per hi, rows lo ascending).
    std::vector<std::uint64_t> keys;
    keys.reserve(3 * faces.size());
    for (const MeshFace& f : faces)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = f[k], b = f[(k + 1) % 3];
            if (a == b) continue;
            keys.push_back((std::uint64_t{std::max(a, b)} << 32) | std::min(a, b));
        }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<MeshEdge> edges;
    edges.reserve(keys.size());
    for (const std::uint64_t key : keys)
        edges.push_back(
            {static_cast<std::uint32_t>(key & 0xffffffffu), static_cast<std::uint32_t>(key >> 32)});
    return edges;
}

CcdStep readCcdStep(const std::filesystem::path& startFrame, const std::filesystem::path& endFrame) {
    const detail::PlyMesh start = detail::readPlyAsStored(startFrame),
                          end = detail::readPlyAsStored(endFrame);
    CcdStep step;
    step.faces = triangleFaces(start, startFrame.string());
    const std::vector<MeshFace> endFaces = triangleFaces(end, endFrame.string());
    if (end.positions.size() != start.positions.size())
        throw Error(endFrame.string() + ": " + std::to_string(end.positions.size()) + " vertices, but " +
                    startFrame.string() + " has " + std::to_string(start.positions.size()) +
                    " (the two frames of a step must have the same vertices)");
    if (endFaces.size() != step.faces.size())
        throw Error(endFrame.string() + ": " + std::to_string(endFaces.size()) + " faces, but " +
                    startFrame.string() + " has " + std::to_string(step.faces.size()) +
                    " (the two frames of a step must have the same faces)");
    const auto differ = std::mismatch(step.faces.begin(), step.faces.end(), endFaces.begin());
    if (differ.first != step.faces.end())
        throw Error(endFrame.string() + ": face " + std::to_string(differ.first - step.faces.begin()) +
                    " differs from " + startFrame.string() +
                    "'s (the two frames of a step must have the same faces)");
    step.start = start.positions;
    step.end = end.positions;
    step.edges = libiglEdges(step.faces);
    return step;
}

std::array<glm::dvec3, 8> ccdPairPoints(const CcdStep& step, CcdPairKind kind, const BoxPair& ids) {
    const std::uint64_t vertices = step.start.size(), edges = step.edges.size(), faces = step.faces.size();
    const auto range = [](std::uint64_t lo, std::uint64_t count) {
        return std::to_string(lo) + " .. " + std::to_string(lo + count - 1);
    };
    std::array<std::uint32_t, 4> v{};
    if (kind == CcdPairKind::VertexFace) {
        if (ids[0] >= vertices)
            throw Error("box id " + std::to_string(ids[0]) + " is not a vertex (" + range(0, vertices) + ")");
        if (ids[1] < vertices + edges || ids[1] >= vertices + edges + faces)
            throw Error("box id " + std::to_string(ids[1]) + " is not a face (" +
                        range(vertices + edges, faces) + ")");
        const MeshFace& f = step.faces[ids[1] - vertices - edges];
        v = {static_cast<std::uint32_t>(ids[0]), f[0], f[1], f[2]};
    } else {
        for (const std::uint64_t id : ids)
            if (id < vertices || id >= vertices + edges)
                throw Error("box id " + std::to_string(id) + " is not an edge (" + range(vertices, edges) +
                            ")");
        const MeshEdge &a = step.edges[ids[0] - vertices], &b = step.edges[ids[1] - vertices];
        v = {a[0], a[1], b[0], b[1]};
    }
    std::array<glm::dvec3, 8> points;
    for (int k = 0; k < 4; ++k) {
        points[k] = step.start[v[k]];
        points[k + 4] = step.end[v[k]];
    }
    return points;
}

std::vector<BoxPair> readBoxPairs(const std::filesystem::path& path) {
    const std::string file = path.string();
    const json doc = readJson(path);
    const json& entries = topArray(doc, file, "[a, b] box-id pairs");
    std::vector<BoxPair> pairs;
    pairs.reserve(entries.size());
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const json& entry = entries[i];
        if (!entry.is_array() || entry.size() != 2 || !entry[0].is_number_unsigned() ||
            !entry[1].is_number_unsigned())
            throw Error(file + ": " + pointer(i) +
                        ": expected [a, b], two non-negative integer box ids, found " +
                        entry.dump().substr(0, 60));
        pairs.push_back({entry[0].get<std::uint64_t>(), entry[1].get<std::uint64_t>()});
    }
    return pairs;
}

std::vector<bool> readMmaBool(const std::filesystem::path& path) {
    const std::string file = path.string();
    const json doc = readJson(path);
    const json& entries = topArray(doc, file, "booleans");
    std::vector<bool> answers;
    answers.reserve(entries.size());
    for (std::size_t i = 0; i < entries.size(); ++i) {
        if (!entries[i].is_boolean())
            throw Error(file + ": " + pointer(i) + ": expected true or false, found " +
                        entries[i].dump().substr(0, 60));
        answers.push_back(entries[i].get<bool>());
    }
    return answers;
}

std::vector<ScalableCcdSet> scalableCcdSets(const std::filesystem::path& externalDir) {
    const std::filesystem::path data = externalDir / "scalable-ccd-data";
    const std::filesystem::path funnel = data / "cloth-funnel", ball = data / "cloth-ball",
                                ballFrames = externalDir / "ipc-toolkit-tests-data";
    auto set = [](std::string name, CcdPairKind kind, const std::filesystem::path& dir,
                  const std::string& step, const std::filesystem::path& start,
                  const std::filesystem::path& end) {
        const std::string kindName = kind == CcdPairKind::VertexFace ? "vf" : "ee";
        return ScalableCcdSet{std::move(name),
                              kind,
                              start,
                              end,
                              dir / "boxes" / (step + kindName + ".json"),
                              dir / "mma_bool" / (step + kindName + "_mma_bool.json")};
    };
    const std::filesystem::path f0 = funnel / "frames" / "227.ply", f1 = funnel / "frames" / "228.ply";
    const std::filesystem::path b0 = ballFrames / "cloth_ball92.ply", b1 = ballFrames / "cloth_ball93.ply";
    return {set("cloth-funnel vf", CcdPairKind::VertexFace, funnel, "227", f0, f1),
            set("cloth-funnel ee", CcdPairKind::EdgeEdge, funnel, "227", f0, f1),
            set("cloth-ball vf", CcdPairKind::VertexFace, ball, "92", b0, b1),
            set("cloth-ball ee", CcdPairKind::EdgeEdge, ball, "92", b0, b1)};
}

std::vector<MeshCcdQuery> readListedCcdQueries(const CcdStep& step, const ScalableCcdSet& set) {
    const std::vector<BoxPair> pairs = readBoxPairs(set.boxes);
    const std::vector<bool> truth = readMmaBool(set.truth);
    if (truth.size() != pairs.size())
        throw Error(set.truth.string() + ": " + std::to_string(truth.size()) + " answers for the " +
                    std::to_string(pairs.size()) + " pairs of " + set.boxes.string());
    std::vector<MeshCcdQuery> queries;
    queries.reserve(pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        try {
            queries.push_back({ccdPairPoints(step, set.kind, pairs[i]), truth[i]});
        } catch (const Error& e) {
            throw Error(set.boxes.string() + ": " + pointer(i) + ": " + e.what() + " of " +
                        set.startFrame.string());
        }
    }
    return queries;
}

std::vector<BoxPair> sweptBoxCandidates(const CcdStep& step, CcdPairKind kind) {
    const std::uint64_t vertices = step.start.size(), edges = step.edges.size();
    std::vector<SweptBox> boxes;
    if (kind == CcdPairKind::VertexFace) {
        for (std::uint32_t v = 0; v < vertices; ++v) boxes.push_back(sweptBox(step, &v, 1, v, 0));
        for (std::size_t f = 0; f < step.faces.size(); ++f)
            boxes.push_back(sweptBox(step, step.faces[f].data(), 3, vertices + edges + f, 1));
    } else {
        for (std::size_t e = 0; e < edges; ++e)
            boxes.push_back(sweptBox(step, step.edges[e].data(), 2, vertices + e, 0));
    }
    // Sweep and prune along x: after sorting by lo.x, the boxes that overlap box i in x and come
    // after it are those that start before box i ends.
    std::sort(boxes.begin(), boxes.end(),
              [](const SweptBox& a, const SweptBox& b) { return a.lo.x < b.lo.x; });
    std::vector<BoxPair> pairs;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const SweptBox& a = boxes[i];
        for (std::size_t j = i + 1; j < boxes.size() && boxes[j].lo.x <= a.hi.x; ++j) {
            const SweptBox& b = boxes[j];
            if (kind == CcdPairKind::VertexFace && a.group == b.group) continue;
            if (b.lo.y > a.hi.y || a.lo.y > b.hi.y || b.lo.z > a.hi.z || a.lo.z > b.hi.z) continue;
            if (shareAVertex(a, b)) continue;
            pairs.push_back({std::min(a.id, b.id), std::max(a.id, b.id)}); // vertex ids < face ids
        }
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

std::vector<SampleCcdQuery> readScalableCcdQueries(const ScalableCcdSet& set) {
    const CcdStep step = readCcdStep(set.startFrame, set.endFrame);
    std::vector<SampleCcdQuery> queries;
    for (const MeshCcdQuery& q : readListedCcdQueries(step, set))
        queries.push_back({rationalQuery(q.points), q.truth});
    return queries;
}

} // namespace glcollide::cpu
