// Clusters of open surfaces for radial culling (model/surface_clusters.hpp), checked against facts
// computed here without the cluster code: a box's sides are exactly its clusters (faces with equal
// normals); on a sphere and the DEDO mask every cluster is a partition piece that is edge-connected
// (a union-find of its own), inside its normal cone; every closed cluster winds exactly once
// around its observer (the winding number as a sum of solid angles, Van Oosterom & Strackee) and,
// at rest, has every real face in front of it (φ = n·(p0 − q) > 0, double).

#include "model/surface_clusters.hpp"
#include "scene/scene_detail.hpp"
#include "solid_angle_winding.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <map>
#include <numbers>
#include <numeric>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace glcollide {
namespace {

using test::windingNumber;

using model::Triangle;

const std::string kExternal = GLCOLLIDE_TEST_DATA_DIR "/external/";

glm::dvec3 unitNormal(const Triangle& t, const std::vector<glm::dvec3>& x) {
    return glm::normalize(glm::cross(x[t[1]] - x[t[0]], x[t[2]] - x[t[0]]));
}

/// Number of edge-connected pieces of `faces` (shared undirected edges), by union-find.
std::size_t edgePieces(const std::vector<Triangle>& faces) {
    std::vector<std::size_t> parent(faces.size());
    std::iota(parent.begin(), parent.end(), 0);
    const auto root = [&](std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> firstUser;
    for (std::size_t f = 0; f < faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const auto edge = std::minmax(faces[f][k], faces[f][(k + 1) % 3]);
            const auto [it, fresh] = firstUser.emplace(edge, f);
            if (!fresh) parent[root(f)] = root(it->second);
        }
    std::set<std::size_t> roots;
    for (std::size_t f = 0; f < faces.size(); ++f) roots.insert(root(f));
    return roots.size();
}

/// How many clusters closeCluster closed, and how many of those wind once around their observer
/// with every real face in front of it at the given positions.
struct Watched {
    std::size_t closed = 0, windOnce = 0;
};

/// Checks every property of `clusters` that does not depend on how they were grown (a partition
/// into edge-connected pieces within their normal cones; closures with ghost nodes where the
/// closure says); counts what Watched counts.
Watched checkClusters(const std::vector<Triangle>& faces, const std::vector<glm::dvec3>& x,
                      const model::SurfaceClusters& clusters, double maxAngle) {
    EXPECT_EQ(clusters.faceCluster.size(), faces.size());
    std::vector<std::vector<Triangle>> members(clusters.count);
    EXPECT_EQ(clusters.axes.size(), clusters.count);
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const std::uint32_t c = clusters.faceCluster[f];
        EXPECT_LT(c, clusters.count) << "face " << f;
        if (c >= clusters.count) continue;
        members[c].push_back(faces[f]);
    }
    const double depth = model::clusterObserverDepth(maxAngle);
    Watched watched;
    for (std::uint32_t c = 0; c < clusters.count; ++c) {
        EXPECT_FALSE(members[c].empty()) << "cluster " << c;
        if (members[c].empty()) continue;
        EXPECT_EQ(edgePieces(members[c]), 1u) << "cluster " << c;
        const glm::dvec3 axis = clusters.axes[c];
        EXPECT_NEAR(glm::length(axis), 1.0, 1e-12);
        // The cone bound, with 1e-12 for the rounding of two normalised double cross products.
        for (const Triangle& t : members[c])
            EXPECT_GE(glm::dot(unitNormal(t, x), axis), std::cos(maxAngle) - 1e-12) << "cluster " << c;
        const model::ClusterClosure closure = model::closeCluster(members[c], x, depth);
        if (!closure.closed) continue;
        ++watched.closed;
        std::vector<glm::dvec3> withGhosts = x;
        withGhosts.insert(withGhosts.end(), closure.ghostPositions.begin(), closure.ghostPositions.end());
        std::vector<Triangle> surface = members[c];
        surface.insert(surface.end(), closure.faces.begin(), closure.faces.end());
        // The ghost nodes where their kinds say, from the outer loop's frame computed here.
        const std::vector<std::uint32_t>& outer = closure.loops[closure.outerLoop];
        glm::dvec3 mean(0.0), area(0.0);
        double radius = 0.0;
        for (std::uint32_t n : outer) mean += x[n];
        mean /= static_cast<double>(outer.size());
        for (std::size_t i = 0; i < outer.size(); ++i) {
            area +=
                glm::cross(x[outer[i]], x[outer[(i + 1) % outer.size()]]); // about the origin: the same sum
            radius = std::max(radius, glm::length(x[outer[i]] - mean));
        }
        const glm::dvec3 back = -radius * glm::normalize(area);
        const double scale = 1e-9 * (1.0 + glm::length(mean) + radius * depth * model::kApexDepth);
        EXPECT_LT(glm::length(closure.observer - (mean + depth * back)), scale) << "cluster " << c;
        std::size_t apexes = 0, skirts = 0;
        for (std::size_t k = 0; k < closure.ghostNodes.size(); ++k) {
            const model::ClusterGhostNode& g = closure.ghostNodes[k];
            const glm::dvec3 p = closure.ghostPositions[k];
            if (g.kind == model::GhostKind::Apex) {
                ++apexes;
                EXPECT_LT(glm::length(p - (mean + model::kApexDepth * depth * back)), scale);
            } else if (g.kind == model::GhostKind::Skirt) {
                ++skirts;
                EXPECT_LT(glm::length(p - (x[g.hang] + model::kSkirtDepth * depth * back)), scale);
            } else { // a hole's fan: around the loop's mean
                glm::dvec3 holeMean(0.0);
                for (std::uint32_t n : closure.loops[g.loop]) holeMean += x[n];
                holeMean /= static_cast<double>(closure.loops[g.loop].size());
                EXPECT_LT(glm::length(p - holeMean), scale);
            }
        }
        EXPECT_EQ(apexes, 1u);
        EXPECT_EQ(skirts, outer.size());
        // The winding number is an integer up to the atan2 sums' rounding (1e-9 for some thousand terms).
        const double winding = windingNumber(surface, withGhosts, closure.observer);
        EXPECT_LT(std::abs(winding - std::round(winding)), 1e-9) << "cluster " << c;
        bool allInFront = true;
        for (const Triangle& t : members[c]) {
            const glm::dvec3 n = glm::cross(x[t[1]] - x[t[0]], x[t[2]] - x[t[0]]);
            allInFront = allInFront && glm::dot(n, x[t[0]] - closure.observer) > 0.0;
        }
        if (std::abs(winding - 1.0) < 1e-9 && allInFront) {
            ++watched.windOnce;
            EXPECT_GT(closure.volume6, 0.0) << "cluster " << c; // outward, as the observer sees it
        }
    }
    return watched;
}

/// Every cluster closed and wound once around its observer.
void expectAllWatched(const Watched& w, std::size_t count) {
    EXPECT_EQ(w.closed, count);
    EXPECT_EQ(w.windOnce, count);
}

TEST(SurfaceClusters, TheSidesOfABoxAreItsClusters) {
    const Body box = detail::generateTetBox({1.0, 2.0, 3.0}, {2, 3, 2});
    const model::SurfaceClusters clusters = model::surfaceClusters(box.faces, box.positions, {});
    EXPECT_EQ(clusters.count, 6u);
    for (std::size_t f = 0; f < box.faces.size(); ++f)
        for (std::size_t g = 0; g < box.faces.size(); ++g) {
            const bool sameSide = glm::dot(unitNormal(box.faces[f], box.positions),
                                           unitNormal(box.faces[g], box.positions)) > 0.999;
            EXPECT_EQ(clusters.faceCluster[f] == clusters.faceCluster[g], sameSide) << f << ", " << g;
        }
    expectAllWatched(checkClusters(box.faces, box.positions, clusters, std::numbers::pi / 4.0), 6u);
}

TEST(SurfaceClusters, AFlatClothIsOneClusterWatchedFromBehind) {
    const Body cloth = detail::generateCloth(2.0, 1.0, 8, 5, false, false);
    const model::SurfaceClusters clusters = model::surfaceClusters(cloth.faces, cloth.positions, {});
    EXPECT_EQ(clusters.count, 1u);
    expectAllWatched(checkClusters(cloth.faces, cloth.positions, clusters, std::numbers::pi / 4.0), 1u);
    // Far from the origin the cluster is closed and watched the same way.
    std::vector<glm::dvec3> far = cloth.positions;
    for (glm::dvec3& p : far) p += glm::dvec3(1.0e5, -3.0e4, 2.0e4);
    expectAllWatched(
        checkClusters(cloth.faces, far, model::surfaceClusters(cloth.faces, far, {}), std::numbers::pi / 4.0),
        1u);
}

TEST(SurfaceClusters, ASphereSplitsIntoClosedCapsWithinTheCone) {
    const Body sphere = detail::generateSphere(1.0, 2);
    for (double degrees : {30.0, 45.0, 60.0}) {
        SCOPED_TRACE(degrees);
        const double angle = degrees * std::numbers::pi / 180.0;
        const model::SurfaceClusters clusters =
            model::surfaceClusters(sphere.faces, sphere.positions, {angle});
        EXPECT_GT(clusters.count, 2u); // no cap under 90 degrees covers a hemisphere
        // A cap on a sphere is a dome: every cluster with manifold, unpinched loops closes.
        expectAllWatched(checkClusters(sphere.faces, sphere.positions, clusters, angle), clusters.count);
    }
}

TEST(SurfaceClusters, TheDedoMaskClosesEveryClusterAroundItsObserver) {
    const detail::SurfaceMesh m = detail::importSurfaceMesh(kExternal + "dedo-cloth-with-holes/mask_0.obj");
    // At rest the mask is nearly flat (4 cm deep over 1.5 m): within 10 degrees of its first face,
    // one cluster, wound once around an observer behind it; at 5 degrees the two ear regions split
    // off as C-shaped strips whose fans, from their loops' means, overlap: closed, but not wound
    // once (the engine's violated check then frees nothing of them: culling less, never wrongly).
    for (double degrees : {45.0, 10.0, 5.0}) {
        const double angle = degrees * std::numbers::pi / 180.0;
        const model::SurfaceClusters clusters = model::surfaceClusters(m.faces, m.positions, {angle});
        const Watched w = checkClusters(m.faces, m.positions, clusters, angle);
        std::cout << "[mask] " << degrees << " degrees: " << clusters.count << " clusters, " << w.closed
                  << " closed, " << w.windOnce << " wound once\n";
        EXPECT_EQ(w.closed, clusters.count);
        if (degrees >= 10.0) {
            EXPECT_EQ(clusters.count, 1u);
            EXPECT_EQ(w.windOnce, 1u);
        } else {
            EXPECT_GT(clusters.count, 1u);
            EXPECT_GE(w.windOnce, 1u); // the face of the mask
        }
    }
}

TEST(SurfaceClusters, ADegenerateFaceJoinsItsNeighbours) {
    // Three triangles facing +z and a zero-area one (collinear corners) across the edge 1-4.
    const std::vector<glm::dvec3> x{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {1.5, 0, 0}};
    const std::vector<Triangle> faces{{0, 1, 2}, {0, 2, 3}, {1, 4, 2}, {4, 1, 5}};
    const model::SurfaceClusters clusters = model::surfaceClusters(faces, x, {});
    EXPECT_EQ(clusters.count, 1u);
    // As a seed it stays alone: listed first, it makes a cluster of its own.
    const model::SurfaceClusters first =
        model::surfaceClusters({faces[3], faces[0], faces[1], faces[2]}, x, {});
    EXPECT_EQ(first.count, 2u);
    EXPECT_EQ(first.faceCluster[0], 0u);
    EXPECT_EQ(first.faceCluster[1], 1u);
}

TEST(SurfaceClusters, BadInputThrows) {
    const std::vector<glm::dvec3> x{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    EXPECT_THROW(model::surfaceClusters({{0, 1, 3}}, x, {}), std::out_of_range);
    EXPECT_THROW(model::surfaceClusters({{0, 1, 2}}, x, {0.0}), std::invalid_argument);
    EXPECT_THROW(model::surfaceClusters({{0, 1, 2}}, x, {std::numbers::pi / 2.0}), std::invalid_argument);
    EXPECT_THROW(model::closeCluster({{0, 1, 3}}, x, 2.0), std::out_of_range);
}

} // namespace
} // namespace glcollide
