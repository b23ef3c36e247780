// Beyond the paper: an error bound checked on the surface the surfels define.
//
// ClusterRefiner::SplitToErrorBound bounds each point's distance to its own surfel's plane.
// What a user sees, and what bench/ measures (vcg_ext/surfel_error), is the distance to the
// blended surface of all surfels (MLS projection, Gaussian weights sized by each ellipse):
// near creases that blend pulls points off even when every own plane is close, because a
// wide neighbouring surfel across the crease weighs on it. SplitToSurfaceErrorBound closes
// that gap: it projects every point on the blended surface, and splits the clusters of the
// surfels blended at each point farther than the bound (the point's own and its neighbours'),
// round after round.
//
// Even when every surfel around a point is down to one member, the blend rounds a sharp crease
// by a fraction of the sample spacing (S' = S does too: the metric's floor); splitting cannot
// help there, narrower weights can. So in the same rounds, every one-point surfel among the
// surfels nearest to a point still beyond the bound has the width of its weight halved
// (Surfel::blendScale), down to kMinBlendScale, and the blend there follows the nearest surfel's
// plane instead of averaging across the crease. All of them, not only those across the crease:
// with only those narrowed, the wider surfels farther away take over the blend. Only the weight
// narrows: the ellipse keeps its size, since narrower ellipses leave gaps along every crease of
// a splat rendering.
// The rounds end when no point is beyond the bound, when nothing is left to split or narrow, or
// after maxRounds; the points still beyond it are counted in the result, so that the caller can
// report them.
#ifndef VCG_EXT_GAUSSPHERE_SURFACE_ERROR_BOUND_H
#define VCG_EXT_GAUSSPHERE_SURFACE_ERROR_BOUND_H

#include <algorithm>
#include <functional>
#include <vector>

#include <vcg_ext/surfel/blended_surface.h>

#include <vcg_ext/gaussphere/size_control/cluster_refinement.h>
#include <vcg_ext/gaussphere/clustering/clustering.h>
#include <vcg_ext/gaussphere/surfels/surfel_generation.h>

namespace vcg {
namespace gaussphere {

/// The narrowest a one-point surfel's blend gets for the error bound (Surfel::blendScale): its
/// Gaussian weight then falls to e^-50 one sample spacing away (with the default coverage margin),
/// so the blend follows the nearest surfel: narrow enough to meet ε = 0.002 on every model of
/// bench/.
constexpr float kMinBlendScale = 0.125f;

/// The blended surface of the surfels `which[0, count)` of `surfels` (null: the first count) as
/// vcg_ext/surfel_error defines it (their ellipses and blend scales), for projections with
/// `metric`'s parameters; `smallestSize` > 0 replaces the floor on their sizes taken from their box
/// (MakeEllipseSurfelSurface), so that a part of a set blends as in the whole set.
/// \pre count > 0, surfels as GenerateSurfels makes them.
inline SurfelSurface BlendedSurfaceOf(const std::vector<Surfel> &surfels, const int *which, size_t count,
                                                const BlendParams &metric, double smallestSize = 0)
{
    std::vector<vcg::Point3f> centers(count), normals(count), major(count), minor(count);
    std::vector<float> blendScale(count);
    for (size_t t = 0; t < count; ++t) {
        const Surfel &s = surfels[which ? size_t(which[t]) : t];
        centers[t] = s.position;
        normals[t] = s.normal;
        major[t] = s.majorAxis;
        minor[t] = s.minorAxis;
        blendScale[t] = s.blendScale;
    }
    return MakeEllipseSurfelSurface(centers, normals, major, minor, metric, &blendScale, smallestSize);
}

/// The blended surface of all of `surfels`.
inline SurfelSurface BlendedSurfaceOf(const std::vector<Surfel> &surfels,
                                                const BlendParams &metric = BlendParams())
{
    return BlendedSurfaceOf(surfels, nullptr, surfels.size(), metric);
}

struct SurfaceErrorBoundResult
{
    int splits = 0;         ///< clusters split (with those re-split for their own planes)
    int narrowings = 0;     ///< halvings of one-point surfels' blend scale (up to 3 per surfel)
    int rounds = 0;         ///< projections of every point
    int pointsAbove = 0;    ///< points still farther than the bound from the blended surface
    double maxDistance = 0; ///< the largest distance of the last projection, model units
    bool cancelled = false; ///< progress returned false
    std::vector<Surfel> surfels; ///< GenerateSurfels of the final clusters (unless cancelled)
};

namespace detail {

/// What one projection of every point on the blended surface finds (SplitToSurfaceErrorBound).
struct BoundCheck
{
    std::vector<int> marked; ///< clusters to split (their surfels blended at a point beyond the bound)
    std::vector<int> narrow; ///< one-point surfels among them
    int above = 0;           ///< points farther than the bound
    double worst = 0;        ///< the largest distance
    bool cancelled = false;  ///< progress returned false
};

/// Projects every point on `surface` and collects the clusters of the surfels nearest to the
/// projection of each point beyond maxDistance (the ones the blend draws from, and a few facing
/// away) and the point's own: collected per thread, merged in cluster order (deterministic).
/// `progress(roundNumber, f)` is called between blocks of points (they only pace it).
inline BoundCheck CheckSurfaceErrorBound(const SurfelSurface &surface, const PointArray &points,
                                         const PointArray &normals, const BlendParams &metric, double tolerance,
                                         double maxDistance, const ClusterRefiner &refiner,
                                         const Clustering &clusters, int roundNumber,
                                         const std::function<bool(int, double)> &progress)
{
    const int n = int(points.size());
    BoundCheck check;
    int above = 0;
    double worst = 0;
    const int block = 1 << 16;
    for (int start = 0; start < n; start += block) {
        if (progress && !progress(roundNumber, double(start) / n)) {
            check.cancelled = true;
            return check;
        }
        const int end = std::min(n, start + block);
#pragma omp parallel reduction(+ : above) reduction(max : worst)
        {
            SurfelSurface::Scratch scratch;
            std::vector<int> local, localNarrow;
#pragma omp for schedule(dynamic, 1024)
            for (int i = start; i < end; ++i) {
                const vcg::Point3d q = vcg::Point3d::Construct(points[i]);
                const auto projection = surface.Project(q, vcg::Point3d::Construct(normals[i]), metric.maxIterations,
                                                        tolerance, scratch);
                const double d = (q - projection.foot).Norm();
                worst = std::max(worst, d);
                if (d <= maxDistance) continue;
                ++above;
                local.push_back(clusters.label[i]);
                for (int j = 0; j < scratch.queue.getNofElements(); ++j) {
                    const int c = scratch.queue.getIndex(j);
                    local.push_back(c);
                    if (refiner.Size(c) == 1) localNarrow.push_back(c);
                }
            }
#pragma omp critical
            {
                check.marked.insert(check.marked.end(), local.begin(), local.end());
                check.narrow.insert(check.narrow.end(), localNarrow.begin(), localNarrow.end());
            }
        }
    }
    check.above = above;
    check.worst = worst;
    return check;
}

/// Splits the marked clusters of more than one member and halves the blend scale of the
/// one-point surfels to narrow, down to kMinBlendScale; returns the splits, `narrowed` receives
/// the halvings.
inline int SplitAndNarrow(BoundCheck &check, ClusterRefiner &refiner, std::vector<float> &blendScale, int &narrowed)
{
    SortUnique(check.marked);
    SortUnique(check.narrow);
    int splits = 0;
    narrowed = 0;
    for (int c : check.marked)
        if (refiner.Size(c) > 1 && refiner.Split(c) >= 0) ++splits;
    for (int c : check.narrow)
        if (blendScale[c] > kMinBlendScale) {
            blendScale[c] = std::max(kMinBlendScale, 0.5f * blendScale[c]);
            ++narrowed;
        }
    return splits;
}

} // namespace detail

/// Splits clusters of `refiner` (which works on `clusters`) until every point lies within
/// maxDistance of the blended surface of the surfels GenerateSurfels makes from them, measured
/// as metric::ComputeSurfelError measures (default BlendParams), narrowing one-point
/// surfels as the file header says, or until nothing near a point beyond it can be split or
/// narrowed, or after maxRounds projections. `progress(r, f)` is
/// called from the calling thread during projection round r (from 1) with the fraction f of
/// points projected so far; when it returns false the refinement stops at once and the result
/// has cancelled = true (its figures are then partial). `adjustSurfels`, if given, adjusts each
/// round's surfels before they are checked (the resampler's NarrowBlendsAroundCreases and
/// FitSurfelOffsets: blend scales of surfels of more than one member, positions): the figures and
/// the bound are those of the adjusted surfels.
/// \pre points and normals (unit) as given to the refiner; spacing as for GenerateSurfels;
///      maxDistance > 0; the points' bounding-box diagonal `diagonal` > 0.
/// \post Deterministic: the result does not depend on the thread count.
inline SurfaceErrorBoundResult SplitToSurfaceErrorBound(const PointArray &points,
                                                        const PointArray &normals,
                                                        const FlatVector<float> &spacing,
                                                        const SurfelGenerationParams &surfelParam,
                                                        double maxDistance, double diagonal, int maxRounds,
                                                        ClusterRefiner &refiner, Clustering &clusters,
                                                        const std::function<bool(int, double)> &progress = nullptr,
                                                        const std::function<void(std::vector<Surfel> &)> &adjustSurfels = nullptr)
{
    const BlendParams metric;
    const double tolerance = metric.convergenceTolerance * diagonal;
    SurfaceErrorBoundResult result;
    std::vector<float> blendScale; // per cluster, 1 until narrowed
    SurfelGenerationParams narrowedParam = surfelParam;
    narrowedParam.blendScale = &blendScale;
    for (;;) {
        blendScale.resize(clusters.clusterCount, 1.f);
        result.surfels = GenerateSurfels(points, normals, spacing, clusters, narrowedParam);
        if (adjustSurfels) adjustSurfels(result.surfels);
        const SurfelSurface surface = BlendedSurfaceOf(result.surfels, metric);
        ++result.rounds;
        detail::BoundCheck check = detail::CheckSurfaceErrorBound(surface, points, normals, metric, tolerance, maxDistance,
                                                                  refiner, clusters, result.rounds, progress);
        if (check.cancelled) {
            result.cancelled = true;
            return result;
        }
        result.pointsAbove = check.above;
        result.maxDistance = check.worst;
        if (check.above == 0 || result.rounds >= maxRounds) break;
        int narrowed = 0;
        const int splits = detail::SplitAndNarrow(check, refiner, blendScale, narrowed);
        result.narrowings += narrowed;
        if (splits == 0 && narrowed == 0) break;
        // A half's plane is fitted anew and may lie farther from a member than the whole's did.
        if (splits > 0) result.splits += splits + refiner.SplitToErrorBound(maxDistance);
    }
    return result;
}

} // namespace gaussphere
} // namespace vcg

#endif
