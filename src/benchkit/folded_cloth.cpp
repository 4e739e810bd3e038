#include "benchkit/folded_cloth.hpp"

#include <glcollide/error.hpp>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace glcollide::benchkit {
namespace {

struct Grid {
    std::uint32_t quadsPerRow = 0, rows = 0;
};

Grid gridFor(std::uint32_t faces) {
    Grid g;
    g.quadsPerRow = static_cast<std::uint32_t>(std::ceil(std::sqrt(faces / 2.0)));
    g.rows = (faces + 2 * g.quadsPerRow - 1) / (2 * g.quadsPerRow);
    return g;
}

/// Panel length of the fold with `layers` panels over a sheet of length `length`.
double panelLength(double length, int layers, double radius) {
    return (length - (layers - 1) * std::numbers::pi * radius) / layers;
}

} // namespace

int foldedClothLayers(const FoldedClothSpec& spec) {
    const Grid g = gridFor(spec.faces);
    const double cell = spec.cellFactor * spec.thickness;
    const double radius = 0.5 * spec.spacingFactor * spec.thickness;
    int layers = std::max(1, spec.layers);
    while (layers > 1 && panelLength(g.rows * cell, layers, radius) < 2.0 * cell) --layers;
    return layers;
}

Body foldedCloth(const FoldedClothSpec& spec) {
    if (spec.faces < 2) throw Error("folded cloth: at least 2 faces");
    if (!(spec.thickness > 0.0)) throw Error("folded cloth: the thickness must be positive");
    const Grid g = gridFor(spec.faces);
    const double cell = spec.cellFactor * spec.thickness;
    const double spacing = spec.spacingFactor * spec.thickness;
    const double radius = 0.5 * spacing;
    const int layers = foldedClothLayers(spec);
    const double length = g.rows * cell;
    const double panel = panelLength(length, layers, radius);
    const double period = panel + std::numbers::pi * radius;
    const double amplitude = spec.amplitudeFactor * cell;
    const double wavelength = spec.wavelengthFactor * cell;
    const double width = g.quadsPerRow * cell;

    // Arc length s along the sheet -> (z, height) of the fold.
    const auto fold = [&](double s) {
        const int k = std::min(layers - 1, static_cast<int>(std::floor(s / period)));
        const double t = s - k * period;
        const bool forwards = k % 2 == 0;
        if (t <= panel || k == layers - 1) {
            const double along = std::min(t, panel);
            return glm::dvec2(forwards ? along : panel - along, k * spacing);
        }
        const double angle = -0.5 * std::numbers::pi + (t - panel) / radius;
        const double out = radius * std::cos(angle);
        return glm::dvec2(forwards ? panel + out : -out, k * spacing + radius + radius * std::sin(angle));
    };

    const std::uint32_t nx = g.quadsPerRow + 1, ny = g.rows + 1;
    std::vector<glm::dvec3> grid;
    grid.reserve(std::size_t{nx} * ny);
    for (std::uint32_t j = 0; j < ny; ++j)
        for (std::uint32_t i = 0; i < nx; ++i) {
            const double x = -0.5 * width + i * cell;
            const glm::dvec2 zy = fold(j * cell);
            const double z = zy.x - 0.5 * panel;
            const double lift = amplitude * std::sin(2.0 * std::numbers::pi * x / wavelength) *
                                std::sin(2.0 * std::numbers::pi * z / wavelength);
            grid.emplace_back(x, zy.y + lift, z);
        }

    // The first `faces` triangles in row order: the surplus goes from the end of the last row.
    std::vector<std::array<std::uint32_t, 3>> faces;
    faces.reserve(spec.faces);
    for (std::uint32_t j = 0; j < g.rows && faces.size() < spec.faces; ++j)
        for (std::uint32_t i = 0; i < g.quadsPerRow && faces.size() < spec.faces; ++i) {
            const std::uint32_t tl = j * nx + i, tr = tl + 1, bl = tl + nx, br = bl + 1;
            faces.push_back({bl, br, tr});
            if (faces.size() < spec.faces) faces.push_back({bl, tr, tl});
        }

    // Drop unused nodes (the dropped triangles' corners), keeping the grid order.
    std::vector<std::uint32_t> remap(grid.size(), UINT32_MAX);
    for (const auto& f : faces)
        for (std::uint32_t n : f) remap[n] = 0;
    Body body;
    body.name = "folded cloth";
    for (std::size_t n = 0; n < grid.size(); ++n)
        if (remap[n] == 0) {
            remap[n] = static_cast<std::uint32_t>(body.positions.size());
            body.positions.push_back(grid[n]);
        }
    for (auto& f : faces)
        for (std::uint32_t& n : f) n = remap[n];
    body.faces = std::move(faces);

    body.masses.assign(body.positions.size(), 0.0);
    std::vector<std::uint64_t> edges;
    edges.reserve(3 * body.faces.size());
    for (const auto& f : body.faces) {
        const glm::dvec3 &a = body.positions[f[0]], &b = body.positions[f[1]], &c = body.positions[f[2]];
        const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
        for (int k = 0; k < 3; ++k) {
            body.masses[f[k]] += spec.arealDensity * area / 3.0;
            const std::uint32_t u = std::min(f[k], f[(k + 1) % 3]), v = std::max(f[k], f[(k + 1) % 3]);
            edges.push_back((std::uint64_t{u} << 32) | v);
        }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    body.springs.reserve(edges.size());
    for (std::uint64_t e : edges) {
        Spring s;
        s.a = static_cast<std::uint32_t>(e >> 32);
        s.b = static_cast<std::uint32_t>(e & 0xffffffffu);
        s.restLength = glm::length(body.positions[s.a] - body.positions[s.b]);
        s.stiffness = spec.springStiffness;
        s.kind = SpringKind::Edge;
        body.springs.push_back(s);
    }
    body.velocities.assign(body.positions.size(), glm::dvec3(0.0));
    body.pinned.assign(body.positions.size(), 0);
    return body;
}

} // namespace glcollide::benchkit
