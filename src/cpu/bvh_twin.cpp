#include "cpu/bvh_twin.hpp"

#include <glm/common.hpp>

#include <algorithm>
#include <bit>

namespace glcollide::cpu {
namespace {

std::uint32_t spreadBits(std::uint32_t v) {
    v &= 0x3ffu;
    v = (v | (v << 16u)) & 0x030000ffu;
    v = (v | (v << 8u)) & 0x0300f00fu;
    v = (v | (v << 4u)) & 0x030c30c3u;
    v = (v | (v << 2u)) & 0x09249249u;
    return v;
}

class Karras {
  public:
    explicit Karras(const std::vector<std::uint32_t>& keys)
        : m_keys(keys), m_n(static_cast<int>(keys.size())) {}

    int delta(int i, int j) const {
        if (j < 0 || j >= m_n) return -1;
        const std::uint32_t a = m_keys[static_cast<std::size_t>(i)], b = m_keys[static_cast<std::size_t>(j)];
        if (a == b) return 32 + std::countl_zero(static_cast<std::uint32_t>(i ^ j));
        return std::countl_zero(a ^ b);
    }
    int direction(int k) const { return delta(k, k + 1) > delta(k, k - 1) ? 1 : -1; }
    std::uint32_t leaf(std::uint32_t i) const { return static_cast<std::uint32_t>(m_n) - 1 + i; }
    std::uint32_t escapeAfter(std::uint32_t last) const {
        const std::uint32_t next = last + 1;
        if (next >= static_cast<std::uint32_t>(m_n)) return kBvhNone;
        if (next + 1 < static_cast<std::uint32_t>(m_n) && direction(static_cast<int>(next)) > 0) return next;
        return leaf(next);
    }

  private:
    const std::vector<std::uint32_t>& m_keys;
    int m_n;
};

} // namespace

std::uint32_t mortonCode(const glm::vec3& centroid, const glm::vec3& lo, const glm::vec3& hi) {
    const glm::vec3 extent = hi - lo;
    const float largest = std::max(std::max(extent.x, extent.y), extent.z);
    const float scale = largest > 0.0f ? 1024.0f / largest : 0.0f;
    const glm::vec3 t = glm::clamp((centroid - lo) * scale, glm::vec3(0.0f), glm::vec3(1023.0f));
    const glm::uvec3 q(t);
    return (spreadBits(q.x) << 2u) | (spreadBits(q.y) << 1u) | spreadBits(q.z);
}

glm::vec3 faceCentroid(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& positions,
                       std::uint32_t face) {
    const glm::vec3 a = positions[faceIndices[3 * face]], b = positions[faceIndices[3 * face + 1]],
                    c = positions[faceIndices[3 * face + 2]];
    return 0.5f * (glm::min(glm::min(a, b), c) + glm::max(glm::max(a, b), c));
}

std::vector<glm::uvec4> twinHierarchy(const std::vector<std::uint32_t>& sortedKeys,
                                      const std::vector<std::uint32_t>& sortedFaces) {
    const auto n = static_cast<std::uint32_t>(sortedKeys.size());
    if (n == 0) return {};
    std::vector<glm::uvec4> links(2 * std::size_t{n} - 1, glm::uvec4(0));
    const Karras k(sortedKeys);
    for (std::uint32_t i = 0; i < n; ++i) {
        glm::uvec4& leaf = links[k.leaf(i)];
        leaf.x = sortedFaces[i];
        leaf.y = i;
        leaf.w = k.escapeAfter(i);
    }
    links[0].z = kBvhNone;
    for (int i = 0; i + 1 < static_cast<int>(n); ++i) {
        const int d = k.direction(i);
        const int deltaMin = k.delta(i, i - d);
        int lengthMax = 2;
        while (k.delta(i, i + lengthMax * d) > deltaMin) lengthMax *= 2;
        int l = 0;
        for (int t = lengthMax / 2; t >= 1; t /= 2)
            if (k.delta(i, i + (l + t) * d) > deltaMin) l += t;
        const int j = i + l * d;
        const int deltaNode = k.delta(i, j);
        int s = 0, step = l;
        do {
            step = (step + 1) >> 1;
            if (k.delta(i, i + (s + step) * d) > deltaNode) s += step;
        } while (step > 1);
        const int gamma = i + s * d + std::min(d, 0);
        const auto first = static_cast<std::uint32_t>(std::min(i, j));
        const auto last = static_cast<std::uint32_t>(std::max(i, j));
        const auto g = static_cast<std::uint32_t>(gamma);
        const std::uint32_t left = first == g ? k.leaf(g) : g;
        const std::uint32_t right = last == g + 1 ? k.leaf(g + 1) : g + 1;
        glm::uvec4& node = links[static_cast<std::size_t>(i)];
        node.x = left;
        node.y = right;
        node.w = k.escapeAfter(last);
        links[left].z = static_cast<std::uint32_t>(i);
        links[right].z = static_cast<std::uint32_t>(i);
    }
    return links;
}

std::vector<FloatBox> twinRefit(const std::vector<glm::uvec4>& links,
                                const std::vector<std::uint32_t>& faceIndices,
                                const std::vector<glm::vec3>& positions, float halfThickness) {
    std::vector<FloatBox> boxes(links.size());
    if (links.empty()) return boxes;
    const std::size_t n = (links.size() + 1) / 2;
    for (std::size_t i = n - 1; i < links.size(); ++i)
        boxes[i] = faceBox(faceIndices, positions, links[i].x, halfThickness);
    // Children before parents: a post-order walk from the root.
    std::vector<std::pair<std::uint32_t, bool>> stack = {{0u, false}};
    while (!stack.empty()) {
        auto [node, expanded] = stack.back();
        stack.pop_back();
        if (node >= n - 1) continue;
        if (expanded) {
            const FloatBox &a = boxes[links[node].x], &b = boxes[links[node].y];
            boxes[node] = {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
        } else {
            stack.push_back({node, true});
            stack.push_back({links[node].x, false});
            stack.push_back({links[node].y, false});
        }
    }
    return boxes;
}

std::vector<FacePair> twinBvhCandidates(const std::vector<glm::uvec4>& links,
                                        const std::vector<FloatBox>& boxes,
                                        const std::vector<std::uint32_t>& faceIndices,
                                        const std::vector<std::uint32_t>& faceObject, const PairRules& rules,
                                        std::uint64_t* nodeVisits) {
    std::vector<FacePair> pairs;
    const auto n = static_cast<std::uint32_t>((links.size() + 1) / 2);
    const auto escapeStart = [n](std::uint32_t escape) {
        if (escape == kBvhNone) return n;
        return escape >= n - 1 ? escape - (n - 1) : escape;
    };
    std::uint64_t visits = 0;
    for (std::uint32_t q = 0; q < n; ++q) {
        const std::uint32_t queryNode = n - 1 + q, face = links[queryNode].x;
        for (std::uint32_t node = 0; node != kBvhNone; ++visits) {
            const glm::uvec4& l = links[node];
            if (escapeStart(l.w) > q + 1 && boxesOverlap(boxes[queryNode], boxes[node])) {
                if (node >= n - 1) {
                    if (validFacePair(faceIndices, faceObject, face, l.x, rules))
                        pairs.push_back({std::min(face, l.x), std::max(face, l.x)});
                    node = l.w;
                } else {
                    node = l.x;
                }
            } else {
                node = l.w;
            }
        }
    }
    if (nodeVisits) *nodeVisits = visits;
    return pairs;
}

} // namespace glcollide::cpu
