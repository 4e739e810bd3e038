#pragma once
// The bvh experiment's self-colliding cloth: a deterministic procedural sheet with exactly the
// requested number of triangles, folded like an accordion so that its layers lie on top of each
// other closer than the contact thickness, and gently crumpled so that its faces are not axis
// aligned. Every face then has candidates in the layers above and below it as well as in its own
// layer, the way a crumpled cloth's self-collision workload looks (docs/benchmarks.md, "The bvh
// experiment").
//
// The flat sheet: a grid of W x R quads of side `cell` (W = ceil(sqrt(faces / 2)), R = ceil(faces
// / 2W)), two triangles per quad; the surplus 2WR - faces triangles are dropped from the end of
// the last row and unused nodes removed, so the triangle count is exact. The fold: along the rows
// (the sheet's length R x cell) the sheet is cut into `layers` equal panels joined by half
// circles of diameter `spacing` (arc length preserved), panel k at height k x spacing running
// forwards (k even) or backwards (k odd). The crumpling: every node moves up by
// amplitude x sin(2 pi x / wavelength) x sin(2 pi z / wavelength), a function of the node's
// horizontal position only, so all layers move alike and stay `spacing` apart vertically.

#include <glcollide/scene.hpp>

#include <cstdint>

namespace glcollide::benchkit {

struct FoldedClothSpec {
    std::uint32_t faces = 2244;     ///< exact triangle count, >= 2
    double thickness = 0.01;        ///< m: the contact thickness the fold is made for
    int layers = 3;                 ///< panels stacked by the fold (fewer when the sheet is too short)
    double spacingFactor = 0.8;     ///< layer spacing / thickness: the layers are within contact distance
    double cellFactor = 2.0;        ///< grid cell / thickness
    double amplitudeFactor = 0.5;   ///< crumpling amplitude / cell
    double wavelengthFactor = 16.0; ///< crumpling wavelength / cell
    double arealDensity = 0.1;      ///< kg/m²: lumped node masses (area / 3 per face corner)
    double springStiffness = 20.0;  ///< N/m of every edge spring; rest length = the folded length
};

/// The folded cloth as one body: nodes, faces, edge springs (one per unique edge, at rest in the
/// folded shape), lumped masses, nothing pinned, zero velocities. Deterministic (no random numbers).
Body foldedCloth(const FoldedClothSpec& spec);

/// The number of layers foldedCloth() makes for `spec` (spec.layers unless the sheet is too short
/// for each panel to be at least two cells long).
int foldedClothLayers(const FoldedClothSpec& spec);

} // namespace glcollide::benchkit
