#pragma once
// The CCD query sets of the Scalable-CCD sample data (Wang et al., "Time of Impact Dataset for
// Continuous Collision Detection and a Scalable Conservative Algorithm"): one time step of a
// cloth simulation given as two mesh frames (t = 0 and t = 1), a list of vertex-face or edge-edge
// pairs named by "box ids", and the exact answer of each pair (computed upstream in Mathematica).
// This file rebuilds each pair's 8 points from the frames, so the sets whose query CSVs are not
// published (cloth-ball) are read the same way as those that are (cloth-funnel).
// Data and formats: tests/data/external/scalable-ccd-data/README.md.
//
// Box ids number the primitives of the mesh: vertices 0 .. V-1, then edges V .. V+E-1, then
// faces V+E .. V+E+F-1 (faces in file order). The edges are those of libigl's igl::edges: every
// undirected edge once as (lo, hi), lo < hi, sorted by hi and then by lo (not by lo first).

#include "cpu/oracle/exact_ccd.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glcollide::cpu {

enum class CcdPairKind { VertexFace, EdgeEdge };

using MeshFace = std::array<std::uint32_t, 3>;
using MeshEdge = std::array<std::uint32_t, 2>; ///< (lo, hi), lo < hi
using BoxPair = std::array<std::uint64_t, 2>;  ///< two box ids

/// One linear time step of a triangle mesh: vertex i moves from start[i] to end[i].
struct CcdStep {
    std::vector<glm::dvec3> start, end; ///< exact copies of the files' values
    std::vector<MeshFace> faces;        ///< file order, corners in file order
    std::vector<MeshEdge> edges;        ///< libiglEdges(faces)
};

/// Reads the two frames of a step (PLY, any endianness, float or double coordinates; vertices and
/// faces kept as numbered in the files). Throws glcollide::Error naming the file when one cannot be
/// read, a face is not a triangle, or the frames differ in vertex count or faces.
CcdStep readCcdStep(const std::filesystem::path& startFrame, const std::filesystem::path& endFrame);

/// The edges of `faces` in igl::edges order (see the file comment). Faces repeating a vertex add
/// no edge from it to itself.
std::vector<MeshEdge> libiglEdges(const std::vector<MeshFace>& faces);

/// The 8 points of the pair `ids` in the benchmark's order (vertex-face: the vertex, then the
/// face's corners; edge-edge: the first id's edge as (lo, hi), then the second's; the t = 0 points,
/// then the t = 1 points). Throws glcollide::Error saying which id is not a primitive of `kind`.
std::array<glm::dvec3, 8> ccdPairPoints(const CcdStep& step, CcdPairKind kind, const BoxPair& ids);

/// A `boxes/<step>{vf,ee}.json` file: an array of [a, b] box-id pairs. Throws glcollide::Error
/// naming the file and the JSON pointer of a bad entry.
std::vector<BoxPair> readBoxPairs(const std::filesystem::path& path);

/// A `mma_bool/<step>{vf,ee}_mma_bool.json` file: an array of booleans, the exact answer of each
/// pair. Throws glcollide::Error naming the file and the JSON pointer of a bad entry.
std::vector<bool> readMmaBool(const std::filesystem::path& path);

/// One listed query of a set, in doubles (every coordinate of the data is exactly a float).
struct MeshCcdQuery {
    std::array<glm::dvec3, 8> points;
    bool truth = false;
};

/// One query set: a step's two frames, its listed pairs and their exact answers.
struct ScalableCcdSet {
    std::string name; ///< "cloth-funnel vf", "cloth-funnel ee", "cloth-ball vf", "cloth-ball ee"
    CcdPairKind kind = CcdPairKind::VertexFace;
    std::filesystem::path startFrame, endFrame, boxes, truth;
};

/// The four sets as laid out under `externalDir` (tests/data/external/): cloth-funnel 227 -> 228
/// (vf, ee) and cloth-ball 92 -> 93 (vf, ee; frames from ipc-toolkit-tests-data). Paths only.
std::vector<ScalableCcdSet> scalableCcdSets(const std::filesystem::path& externalDir);

/// The listed queries of `set` with their truth, the points taken from `step` (which must be the
/// step of set.startFrame and set.endFrame). Throws glcollide::Error naming the file and JSON
/// pointer of a pair that is not one of `step`, or when the answers do not match the pairs in number.
std::vector<MeshCcdQuery> readListedCcdQueries(const CcdStep& step, const ScalableCcdSet& set);

/// The same as exact queries (cpu::SampleCcdQuery, as readSampleCcdQueries returns), reading the
/// frames too.
std::vector<SampleCcdQuery> readScalableCcdQueries(const ScalableCcdSet& set);

/// Every pair of `kind` whose swept boxes overlap, as box ids (vertex-face: [vertex, face];
/// edge-edge: [a, b] with a < b), sorted, leaving out pairs that share a vertex. A primitive's
/// swept box is the axis-aligned box of its vertices at t = 0 and t = 1, not inflated; boxes
/// touching at a face overlap (closed boxes). These are the broad-phase candidates of the step,
/// of which the listed pairs are a subset (scalable-ccd-data/README.md counts them: 7,319 / 33,770
/// for cloth-funnel, 1,655,541 / 5,197,332 for cloth-ball).
std::vector<BoxPair> sweptBoxCandidates(const CcdStep& step, CcdPairKind kind);

} // namespace glcollide::cpu
