// Boundary points: points on the rim of an open surface, where the neighbours lie on one side.
//
// Why, twice over:
// - A wide cluster at a rim reaches past it: its surfel sits inside the rim, and the surface the
//   surfels blend into (an MLS projection) overshoots or falls short of the last input points (the
//   open base of the bunny holds its largest distance to the blended surface). Rim points get the
//   cluster limits of crease points (cluster_normalization.h), which lowers that largest distance
//   on the bunny by about 40 % for a 0.5 % larger count.
// - A surfel's blend fit (surfel_offset.h) compares its members with the blend of the surfels
//   around them. At a rim there are surfels on the inner side only, so the fit moves rim surfels
//   by a one-sided blend. A reconstruction that closes the opening (Screened Poisson caps it)
//   starts its cap from those surfels: on twirl, whose ends are open, the fitted rim raises the cap
//   above the unfitted one. So rim surfels are never fitted, and SpreadEvenly leaves the clusters
//   of the band along the rim unfitted as well (resampling.h): the boundary points and every point
//   with one among its k nearest neighbours, since the cap starts from the surfels along the rim,
//   not from the rim points alone (twirl: a band of the rim points' 4 nearest neighbours only
//   leaves its reconstruction's RMS distance 1.6 % higher).
//
// The neighbour search marks them (AdaptiveNeighborParams::boundaryGapDegrees, NeighborGraph::
// boundary), while each point's neighbours are at hand.
// The test: the directions from a point to its k nearest neighbours, projected onto its tangent
// plane, leave an angular gap wider than 150 degrees. On a rim the neighbours fill a half-plane
// (a gap of 180 degrees, more at a corner); inside, even a scan's uneven sampling leaves smaller
// gaps (1 % of the dragon's points reach 150 degrees, 15 % reach 90).
#ifndef VCG_EXT_GAUSSPHERE_BOUNDARY_POINTS_H
#define VCG_EXT_GAUSSPHERE_BOUNDARY_POINTS_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <vcg/space/point3.h>

#include <vcg_ext/gaussphere/support/flat_vector.h>

namespace vcg {
namespace gaussphere {

/// Gap, in degrees, between the tangent directions to a point's neighbours above which the
/// point lies on a boundary.
constexpr double kBoundaryGapDegrees = 150;

/// A direction in a tangent plane, and its key that orders directions by angle without
/// trigonometry (the "diamond angle"): in [0, 4), increasing counter-clockwise from +x, and
/// larger by exactly 2 half a turn later, so that keys 2 apart are directions half a turn apart.
struct TangentDirection
{
    double x = 0, y = 0, key = 0; ///< key: set by GapExceeds
    TangentDirection() = default;
    TangentDirection(double dx, double dy) : x(dx), y(dy) {}
    double Key() const
    {
        const double l1 = std::abs(x) + std::abs(y);
        if (y >= 0) return x >= 0 ? y / l1 : 1 - x / l1;
        return x < 0 ? 2 - y / l1 : 3 + x / l1;
    }
};

/// Sectors of the tangent plane for the quick test: each a sixth of a quadrant's keys, at most
/// kMaxSectorDegrees wide: the sixths of a quadrant span 11.3, 15.3, 18.4, 18.4, 15.3 and 11.3
/// degrees (the widest, from 26.57 to 45 degrees, rounded up).
constexpr int kTangentSectors = 24;
constexpr double kMaxSectorDegrees = 18.44;

/// The sector, 0 to 23, of the non-zero tangent direction (x, y): the keys [s / 6, (s + 1) / 6),
/// at most kMaxSectorDegrees wide. Found by comparisons alone: the quadrant, then the sixth of it.
inline int SectorOf(float x, float y)
{
    const bool left = x < 0, below = y < 0;
    const bool odd = left != below; // quadrants 1 and 3 swap the roles of |x| and |y|
    const int quadrant = (int(below) << 1) | int(odd);
    const float along = odd ? std::abs(y) : std::abs(x), across = odd ? std::abs(x) : std::abs(y);
    // The key within the quadrant is across / (along + across); it reaches j / 6 where
    // (6 - j) across >= j along.
    return 6 * quadrant + int(5 * across >= along) + int(4 * across >= 2 * along) + int(3 * across >= 3 * along) +
           int(2 * across >= 4 * along) + int(across >= 5 * along);
}

/// Whether directions in the sectors flagged in `occupied` (bit s: SectorOf) certainly leave no
/// gap wider than maxGapDegrees. A gap between directions with r empty sectors between theirs
/// spans at most r + 2 sectors of kMaxSectorDegrees: the test looks for a run, around the circle, of
/// empty sectors longer than the limit allows.
inline bool SectorsLeaveNoGapAbove(std::uint32_t occupied, double maxGapDegrees)
{
    const int allowedEmpty = int(std::floor(maxGapDegrees / kMaxSectorDegrees)) - 2;
    if (allowedEmpty < 0 || occupied == 0) return false;
    // Two turns of the circle side by side, so that runs across sector 0 are seen too.
    const std::uint64_t twice = std::uint64_t(occupied) | std::uint64_t(occupied) << kTangentSectors;
    std::uint64_t run = ~twice & ((std::uint64_t(1) << (2 * kTangentSectors)) - 1); // empty sectors
    for (int t = 0; t < allowedEmpty && run; ++t) run &= run >> 1; // starts of runs longer than t + 1
    return run == 0;
}

/// Whether the largest angular gap between `directions` (non-zero tangent vectors, in any order;
/// reordered here) exceeds `maxGapDegrees`, in (0, 180), measured exactly: the directions are
/// sorted by key, and the gap from each to the next counter-clockwise is over half a turn when
/// their keys are more than 2 apart, else it exceeds the limit when their cosine is below the
/// limit's. Fewer than two directions: a gap of a full turn.
inline bool GapExceedsExactly(std::vector<TangentDirection> &directions, double maxGapDegrees)
{
    if (directions.size() < 2) return true;
    for (TangentDirection &d : directions) d.key = d.Key();
    std::sort(directions.begin(), directions.end(),
              [](const TangentDirection &a, const TangentDirection &b) { return a.key < b.key; });
    const double cosLimit = std::cos(maxGapDegrees * std::acos(-1.0) / 180.0);
    const TangentDirection *last = &directions.back();
    double turn = 4; // the wrap-around pair: its keys are a full turn (4) apart, less their difference
    for (const TangentDirection &d : directions) {
        if (d.key + turn - last->key > 2) return true;
        const double dot = last->x * d.x + last->y * d.y;
        const double lengths = std::sqrt((last->x * last->x + last->y * last->y) * (d.x * d.x + d.y * d.y));
        if (dot < cosLimit * lengths) return true;
        last = &d;
        turn = 0;
    }
    return false;
}

/// GapExceedsExactly, with a quick test first: most points have neighbours all around, which
/// SectorsLeaveNoGapAbove settles.
inline bool GapExceeds(std::vector<TangentDirection> &directions, double maxGapDegrees)
{
    if (directions.size() < 2) return true;
    std::uint32_t occupied = 0;
    for (const TangentDirection &d : directions) occupied |= 1u << SectorOf(float(d.x), float(d.y));
    if (SectorsLeaveNoGapAbove(occupied, maxGapDegrees)) return false;
    return GapExceedsExactly(directions, maxGapDegrees);
}

/// Whether point i lies on a boundary: the directions to its neighbours `neighbors[0, count)`,
/// projected onto its tangent plane, leave a gap wider than gapDegrees. Neighbours at its own
/// position have no direction and are passed over. `scratch` is reused between calls.
/// \pre unit normals[i]; gapDegrees in (0, 180); count <= 255 (NeighborGraph's stride at most).
inline bool IsBoundaryPoint(const PointArray &points, const PointArray &normals, int i, const int *neighbors,
                            int count, double gapDegrees, std::vector<TangentDirection> &scratch)
{
    const vcg::Point3f &normal = normals[i];
    const vcg::Point3f side = std::abs(normal[0]) < 0.9f ? vcg::Point3f(1, 0, 0) : vcg::Point3f(0, 1, 0);
    const vcg::Point3f u = (normal ^ side).Normalize(), v = normal ^ u;
    // The tangent coordinates, then the sectors, in flat loops the compiler vectorizes (this runs
    // for every point, inside the neighbour search). The quick test first, on the sectors alone;
    // the exact one only where it cannot decide.
    float x[255], y[255];
    int sector[255];
    for (int t = 0; t < count; ++t) {
        const vcg::Point3f d = points[neighbors[t]] - points[i];
        x[t] = d.dot(u);
        y[t] = d.dot(v);
    }
    for (int t = 0; t < count; ++t) sector[t] = SectorOf(x[t], y[t]);
    std::uint32_t occupied = 0;
    int directions = 0;
    for (int t = 0; t < count; ++t) {
        const bool atPoint = x[t] == 0 && y[t] == 0; // no direction
        occupied |= std::uint32_t(!atPoint) << sector[t];
        directions += int(!atPoint);
    }
    if (directions >= 2 && SectorsLeaveNoGapAbove(occupied, gapDegrees)) return false;
    scratch.clear();
    for (int t = 0; t < count; ++t)
        if (x[t] != 0 || y[t] != 0) scratch.emplace_back(x[t], y[t]);
    return GapExceedsExactly(scratch, gapDegrees);
}

/// The points flagged in `rim` and those with one among their found neighbours in `graph`
/// (a NeighborGraph): the band along the rim.
/// \pre one flag of `rim` per point of `graph`. \post one flag per point; the same for any
///      thread count.
template <class Graph>
FlatVector<char> BoundaryBand(const Graph &graph, const FlatVector<char> &rim)
{
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
