#include "cpu/radial_twin.hpp"

#include "cpu/radial_library.hpp"

#include <glcollide/error.hpp>

#include <glm/vector_relational.hpp>

#include <algorithm>
#include <utility>
#include <string>

namespace glcollide::cpu {

RadialFaceView radialFaceView(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& x0,
                              const std::vector<glm::vec3>& x1, std::size_t f, std::uint32_t observer,
                              const std::vector<glm::vec3>& observers, const RadialSegmentEnds& segmentEnds,
                              bool inward) {
    const std::uint32_t a = faceIndices[3 * f];
    std::uint32_t b = faceIndices[3 * f + 1], c = faceIndices[3 * f + 2];
    if (inward) std::swap(b, c);
    const glm::vec3 q = observers[2 * std::size_t{observer}], qEnd = observers[2 * std::size_t{observer} + 1];
    RadialFaceView view;
    const bool segment = 2 * std::size_t{observer} + 1 < segmentEnds.size() &&
                         segmentEnds[2 * std::size_t{observer}].w != 0.0f;
    if (!segment) {
        view.cone = shader::glcRadialFootprint(x0[a], x0[b], x0[c], q, x1[a], x1[b], x1[c], qEnd);
        view.positive = shader::glcRadialPositive(x0[a], x0[b], x0[c], q, x1[a], x1[b], x1[c], qEnd);
        return view;
    }
    const glm::vec3 r = segmentEnds[2 * std::size_t{observer}],
                    rEnd = segmentEnds[2 * std::size_t{observer} + 1];
    view.feet = shader::glcRadialFeet(x0[a], x0[b], x0[c], q, r, x1[a], x1[b], x1[c], qEnd, rEnd);
    view.cone = shader::glcRadialSegmentFootprint(x0[a], x0[b], x0[c], q, r, x1[a], x1[b], x1[c], qEnd, rEnd,
                                                  view.feet);
    view.positive = shader::glcRadialSegmentPositive(x0[a], x0[b], x0[c], q, r, x1[a], x1[b], x1[c], qEnd,
                                                     rEnd, view.feet.x, view.feet.y);
    if (view.cone.w <= -1.0f) view.feet = shader::glcRadialWholeSegment(); // it may touch the segment
    return view;
}

std::vector<std::uint32_t>
radialPositiveMask(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& x0,
                   const std::vector<glm::vec3>& x1, const std::vector<std::uint32_t>& faceObserver,
                   const std::vector<glm::vec3>& observers, const RadialSegmentEnds& segmentEnds) {
    const std::size_t faces = faceObserver.size();
    std::vector<std::uint32_t> mask((faces + 31) / 32, 0u);
    for (std::size_t f = 0; f < faces; ++f) {
        const std::uint32_t o = faceObserver[f];
        if (o == 0xffffffffu) continue;
        if (radialFaceView(faceIndices, x0, x1, f, o, observers, segmentEnds).positive)
            mask[f / 32] |= 1u << (f % 32);
    }
    return mask;
}

std::vector<std::uint8_t> radialFreeFaces(const std::vector<std::uint32_t>& faceIndices,
                                          const std::vector<glm::vec3>& x0, const std::vector<glm::vec3>& x1,
                                          const std::vector<std::uint32_t>& faceObserver,
                                          const std::vector<glm::vec3>& observers,
                                          const RadialSegmentEnds& segmentEnds) {
    const std::size_t faces = faceObserver.size();
    std::vector<RadialFaceView> views(faces);
    for (std::size_t f = 0; f < faces; ++f)
        if (faceObserver[f] != 0xffffffffu)
            views[f] = radialFaceView(faceIndices, x0, x1, f, faceObserver[f], observers, segmentEnds);
    std::vector<std::uint8_t> free(faces, 0);
    for (std::size_t f = 0; f < faces; ++f) {
        if (!views[f].positive) continue;
        bool meets = false;
        for (std::size_t g = 0; g < faces && !meets; ++g)
            meets = faceObserver[g] == faceObserver[f] && !views[g].positive &&
                    shader::glcRadialFeetMeet(views[f].feet, views[g].feet) &&
                    shader::glcRadialFootprintsMeet(views[f].cone, views[g].cone);
        free[f] = meets ? 0 : 1;
    }
    return free;
}

std::vector<RadialWindingNumber> radialWindingNumbers(const std::vector<std::uint32_t>& faceIndices,
                                                      const std::vector<glm::vec3>& x0,
                                                      const std::vector<std::uint32_t>& faceObserver,
                                                      const std::vector<glm::vec3>& observers,
                                                      const std::vector<bool>& inward) {
    std::vector<RadialWindingNumber> out(observers.size());
    for (std::size_t f = 0; f < faceObserver.size(); ++f) {
        const std::uint32_t o = faceObserver[f];
        if (o == 0xffffffffu) continue;
        const glm::vec3 p0 = x0[faceIndices[3 * f]];
        glm::vec3 p1 = x0[faceIndices[3 * f + 1]], p2 = x0[faceIndices[3 * f + 2]];
        if (inward.at(o)) std::swap(p1, p2);
        const int crossing =
            shader::glcRadialRayCrossing(p0, p1, p2, observers.at(o), shader::GLC_RADIAL_RAY);
        if (crossing == shader::GLC_RADIAL_RAY_UNDECIDED)
            out[o].undecided = true;
        else
            out[o].number += crossing;
    }
    return out;
}

std::vector<RadialFacePair> radialViolatedPairs(const std::vector<std::uint32_t>& faceIndices,
                                                std::size_t realFaces,
                                                const std::vector<glm::vec3>& positions) {
    const std::size_t faces = faceIndices.size() / 3;
    const auto corner = [&](std::size_t f, int k) {
        return faceIndices[3 * f + static_cast<std::size_t>(k)];
    };
    const auto sharesNode = [&](std::size_t f, std::size_t g) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (corner(f, i) == corner(g, j)) return true;
        return false;
    };
    // Closed boxes: a pair whose boxes do not touch cannot intersect (touching counts).
    std::vector<glm::vec3> lo(faces), hi(faces);
    for (std::size_t f = 0; f < faces; ++f) {
        lo[f] = hi[f] = positions[corner(f, 0)];
        for (int k = 1; k < 3; ++k) {
            lo[f] = glm::min(lo[f], positions[corner(f, k)]);
            hi[f] = glm::max(hi[f], positions[corner(f, k)]);
        }
    }
    std::vector<RadialFacePair> violated;
    for (std::size_t g = realFaces; g < faces; ++g) // a ghost face against every face before it
        for (std::size_t f = 0; f < g; ++f) {
            if (glm::any(glm::lessThan(hi[f], lo[g])) || glm::any(glm::lessThan(hi[g], lo[f]))) continue;
            if (sharesNode(f, g)) continue;
            const bool hit = shader::glcTriTriExact(positions[corner(f, 0)], positions[corner(f, 1)],
                                                    positions[corner(f, 2)], positions[corner(g, 0)],
                                                    positions[corner(g, 1)], positions[corner(g, 2)]);
            if (shader::glcExactFailed)
                throw Error("radialViolatedPairs: the exact test could not decide faces " +
                            std::to_string(f) + " and " + std::to_string(g));
            if (hit) violated.push_back({static_cast<std::uint32_t>(f), static_cast<std::uint32_t>(g)});
        }
    std::sort(violated.begin(), violated.end());
    return violated;
}

} // namespace glcollide::cpu
