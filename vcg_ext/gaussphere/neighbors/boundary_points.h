// Boundary points: points on the rim of an open surface, where the neighbours lie on one side.
//
// Why: a surfel's blend fit (surfel_offset.h) compares its members with the blend of the
// surfels around them. At the rim of an open scan or part there are surfels on the inner side
// only, so the fit moves rim surfels by a one-sided blend. A reconstruction that closes the
// opening (Screened Poisson caps it) starts its cap from those surfels: on twirl, whose ends are
// open, the fitted rim raises the cap above the unfitted one. SpreadEvenly leaves the clusters of
// the band along the rim unfitted (resampling.h): the boundary points and every point with one
// among its k nearest neighbours, since the cap starts from the surfels along the rim, not from
// the rim points alone (twirl: a band of the rim points' 4 nearest neighbours only leaves its
// reconstruction's RMS distance 1.6 % higher).
//
// The test: the directions from a point to its k nearest neighbours, projected onto its tangent
// plane, leave an angular gap wider than 150 degrees. On a rim the neighbours fill a half-plane
// (a gap of 180 degrees, more at a corner); inside, even a scan's uneven sampling leaves smaller
// gaps (1 % of the dragon's points reach 150 degrees, 15 % reach 90).
#ifndef VCG_EXT_GAUSSPHERE_BOUNDARY_POINTS_H
#define VCG_EXT_GAUSSPHERE_BOUNDARY_POINTS_H

#include <algorithm>
#include <cmath>
#include <vector>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>

namespace vcg {
namespace gaussphere {

/// Gap, in degrees, between the tangent directions to a point's neighbours above which the
/// point lies on a boundary.
constexpr double kBoundaryGapDegrees = 150;

/// Whether the largest angular gap between `directions` (tangent-plane angles in radians, in
/// any order; sorted here) exceeds `maxGap`. Fewer than two directions: a gap of a full turn.
inline bool GapExceeds(std::vector<double> &directions, double maxGap)
{
    const double turn = 2 * std::acos(-1.0);
    if (directions.size() < 2) return turn > maxGap;
    std::sort(directions.begin(), directions.end());
    double gap = directions.front() + turn - directions.back();
    for (size_t t = 1; t < directions.size(); ++t) gap = std::max(gap, directions[t] - directions[t - 1]);
    return gap > maxGap;
}

/// Per point: 1 where the directions to all of its found neighbours in `graph` (inside its cone
/// or not), projected onto its tangent plane, leave a gap wider than gapDegrees, else 0.
/// Neighbours at the point's own position have no direction and are passed over.
/// \pre `graph` is the neighbour graph of `points` with every found slot (before KeepFirstSlots);
///      unit `normals`.
/// \post one flag per point; the same for any thread count.
inline FlatVector<char> BoundaryPoints(const PointArray &points, const PointArray &normals, const NeighborGraph &graph,
                                       double gapDegrees = kBoundaryGapDegrees)
{
    const int n = graph.Size();
    const double maxGap = gapDegrees * std::acos(-1.0) / 180.0;
    FlatVector<char> boundary(n);
#pragma omp parallel
    {
        std::vector<double> directions;
#pragma omp for schedule(static)
        for (int i = 0; i < n; ++i) {
            const vcg::Point3f &normal = normals[i];
            const vcg::Point3f side = std::abs(normal[0]) < 0.9f ? vcg::Point3f(1, 0, 0) : vcg::Point3f(0, 1, 0);
            const vcg::Point3f u = (normal ^ side).Normalize(), v = normal ^ u;
            directions.clear();
            for (const int *q = graph.begin(i), *end = q + graph.found[i]; q != end; ++q) {
                const vcg::Point3f d = points[*q] - points[i];
                const float x = d.dot(u), y = d.dot(v);
                if (x != 0 || y != 0) directions.push_back(std::atan2(double(y), double(x)));
            }
            boundary[i] = GapExceeds(directions, maxGap) ? 1 : 0;
        }
    }
    return boundary;
}

/// BoundaryPoints, and the points with one among their found neighbours (the band along the rim).
/// \pre as BoundaryPoints. \post one flag per point; the same for any thread count.
inline FlatVector<char> BoundaryBand(const PointArray &points, const PointArray &normals, const NeighborGraph &graph)
{
    const FlatVector<char> rim = BoundaryPoints(points, normals, graph);
    const int n = graph.Size();
    FlatVector<char> band(n);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
        const int *q = graph.begin(i), *end = q + graph.found[i];
        band[i] = rim[i] || std::any_of(q, end, [&rim](int j) { return rim[j] != 0; }) ? 1 : 0;
    }
    return band;
}

} // namespace gaussphere
} // namespace vcg

#endif
