#pragma once
// Surfels as plain arrays: what the renderer uploads, independent of MeshLab's mesh types.
// The ellipse of surfel i is { p + x·E + y·F : x² + y² ≤ 1 } (docs/surfel_format.md).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace splat {

struct SurfelArrays
{
    std::vector<float> positions; // x y z per surfel
    std::vector<float> normals;   // unit normal per surfel (orients the splat and shades it)
    std::vector<float> majorAxes; // semi-axis vector E per surfel, tangent to the normal
    std::vector<float> minorAxes; // semi-axis vector F per surfel, tangent, orthogonal to E
    std::vector<std::uint8_t> colors; // r g b a per surfel; empty: every splat gets the default colour

    std::size_t size() const { return positions.size() / 3; }
    bool hasColors() const { return colors.size() == 4 * size(); }
};

// Called now and then by long computations with the fraction done (0 to 1), from the thread
// that called them.
using ProgressCallback = std::function<void(double fraction)>;

// The largest coordinate magnitude of a usable position, normal or ellipse axis: squared
// distances and sums of such values stay finite in float (3e38 does not).
constexpr float kMaxCoordinate = 1e18f;

// True when the three coordinates at v are finite and within kMaxCoordinate.
bool isUsableVector(const float *v);

// Radius of each point's circular splat: the distance to its k-th nearest neighbour (itself
// excluded), so neighbouring splats overlap on a uniformly sampled surface (for k = 8 the
// radius is about 1.5 times the sample spacing). The neighbours come from the grid search of
// vcg_ext/gaussphere/neighbors/point_grid.h, in parallel. Positions that are not usable
// (isUsableVector) are left out of the search and get radius 0, as does a lone point.
std::vector<float> nearestNeighbourRadii(const std::vector<float> &positions, int k,
                                         const ProgressCallback &progress = nullptr);

// The number of neighbours nearestNeighbourRadii uses when a caller has no better idea.
constexpr int kDefaultSplatNeighbours = 8;

// Fills majorAxes/minorAxes with circles of the given radii in the plane orthogonal to each
// normal (E × F points along the normal).
void assignCircularFrames(SurfelArrays &surfels, const std::vector<float> &radii);

// Removes the surfels that cannot be drawn: a position, normal or semi-axis that is not usable
// (isUsableVector), or a zero normal. Returns how many it removed.
// Expects a normal and both axes per surfel.
std::size_t removeUnusableSurfels(SurfelArrays &surfels);

// Moves each surfel back from where the resampler fitted it to its blended (MLS) surface onto
// the sampled surface: position -= fitOffset · normal (the SurfelFitOffset attribute,
// `fit_offset` in .surfel files; docs/surfel_format.md). Splats blend shading, not positions:
// drawn at the fitted positions they swell the silhouettes (bench/render). Empty `fitOffsets`
// (no fit recorded) and surfels without normals are left as they are; otherwise there is one
// offset per surfel (asserted), and a non-finite one counts as 0.
void undoFitOffsets(SurfelArrays &surfels, const std::vector<float> &fitOffsets);

} // namespace splat
