#ifndef VCG_EXT_SURFEL_ERROR_SURFEL_ERROR_H
#define VCG_EXT_SURFEL_ERROR_SURFEL_ERROR_H

/** \file
 * Approximation error of a simplified oriented point set S' (surfels) against the original
 * oriented point set S, as defined in section 5.2 of "Feature sensitive re-sampling of point
 * set surfaces with Gaussian spheres", with the shape L2,1 error of its section 3.5.
 *
 * \section surfel_error_surface The surface defined by S'
 * Every usable surfel i of S' (finite position p_i, non-zero finite normal n_i) carries an
 * anisotropic Gaussian weight
 *
 *     w_i(x) = exp( -( u²/a_i² + v²/b_i² + w²/a_i² ) / σ² ),   (u, v, w) = coordinates of
 *                                                               x − p_i in (major, minor, n_i)
 *
 * where σ = SurfelErrorParams::widthFactor and a_i ≥ b_i are the surfel's semi-axes:
 *  - the lengths of its EllipseMajorAxis / EllipseMinorAxis vectors when given (the major
 *    direction is projected onto the tangent plane; the normal direction uses the major
 *    length so that a narrow surfel does not lose weight merely for being off its plane);
 *  - otherwise a_i = b_i = R() when the mesh has per-vertex radius and R() > 0;
 *  - otherwise a_i = b_i = the local spacing of S': the mean distance from p_i to its
 *    SurfelErrorParams::spacingNeighborCount nearest other surfel centers (with the default
 *    of 6 this is exactly the step of a hexagonal sampling).
 * Plain oriented points are thus circular surfels, and with the defaults the Gaussian width of a
 * plain point is 1.5× its local spacing. A surfel may carry a blend scale s_i in (0, 1]
 * (SurfelErrorAttributes::blendScale, the SurfelBlendScale attribute), which multiplies a_i and
 * b_i in its weight only: the blend then follows that surfel closely near its center (at a sharp
 * crease), while its ellipse keeps the size that covers its area in a rendering.
 *
 * At a point x the k = SurfelErrorParams::neighborCount surfels whose centers are nearest to
 * x are blended (Alexa & Adamson 2004, "On normals and projection operators for surfaces
 * defined by point sets"):
 *
 *     a(x) = Σ w_i(x) p_i / Σ w_i(x),    n(x) = Σ w_i(x) n_i / ‖Σ w_i(x) n_i‖
 *
 * and the "almost orthogonal" projection of q iterates x ← x − ((x − a(x))·n(x)) n(x) from
 * x = q until the step is at most convergenceTolerance × diag(S) or maxIterations steps were
 * taken. The result is q0 and d(q, S') = ‖q − q0‖. The blended normal n(q0) is the one of the
 * last evaluation (at most one converged step away from q0).
 * Of the k surfels, only those facing the same side as q (n_i · n_q > 0) are blended: on thin
 * parts the nearest centers include the opposite sheet, whose surfels would pull a(x) between
 * the sheets, cancel n(x) or capture the projection. When q has no usable normal, or none of the
 * k surfels faces its side, the side of the heaviest surfel is used instead. Only the sheet is
 * chosen this way: within it, n_q plays no part in a(x), n(x) or the weights. The weights are
 * scaled so that the largest blended one is 1, so the operator stays defined far from every
 * surfel, where it tends to the plane of the surfel nearest in the weights' metric.
 *
 * The projection of a plane sample onto itself is exact; on curved surfaces a(x) lies inside
 * the surface, so S' = S gives a small non-zero floor that grows with widthFactor. With the
 * defaults, on ../shared/data: bunny.ply (34,834 points) Δ*_RMS 3.3e-4, Δ*_max 3.9e-3
 * (widthFactor 1.0: 2.7e-4; 2.0: 3.5e-4); dragon.ply (437,645 points) Δ*_RMS 4.7e-5
 * (bench/results/table1.md lists every model). Read a simplification's figures against it.
 *
 * \section surfel_error_figures Figures
 * Over the points q of S with a finite position:
 *  - distance: d(q, S'): Δ_RMS and Δ_max of the paper; normalizedDistance: the same divided by
 *    the bounding-box diagonal of S (Δ*_RMS, Δ*_max).
 * Over the points that also have a non-zero finite normal n_q (normalized before use):
 *  - normalToOwnSurfel: ‖n_q − n'‖ with n' the unit normal of the surfel representing q: the
 *    one named by SurfelErrorAttributes::representative, else the surfel whose center is
 *    nearest to q;
 *  - normalToBlended: ‖n_q − n(q0)‖.
 * The shape error is reported as the norm ‖n' − n_i‖ (range [0, 2]), not the paper's squared
 * d²(n', n_i): the RMS of the norm over the points is the square root of the mean of the
 * paper's per-point L2,1 term, which is what fits the magnitudes of the paper's Table 1
 * (RMS ≈ 0.04, max 0.25–0.97). Each figure comes with its 99.9th percentile beside the maximum.
 *
 * Results do not depend on the number of OpenMP threads: every point is computed
 * independently and the sums are taken sequentially afterwards.
 */

#include <vcg/complex/complex.h>
#include <vcg/space/index/kdtree/kdtree.h>
#include <vcg_ext/surfel/blended_surface.h>
#include <vcg_ext/surfel/percentile.h>
#include <wrap/callback.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace vcg {
namespace gaussphere {
namespace metric {

/// Parameters of ComputeSurfelError(): the blend's (BlendParams: k = 8, sigma = 1.5, 10 steps,
/// tolerance 1e-7 of the diagonal) and the size of surfels without axes or radius.
struct SurfelErrorParams : BlendParams
{
    /// Surfels with neither ellipse axes nor radius take as size the mean distance to this many
    /// nearest other surfel centers. Default 6.
    int spacingNeighborCount = 6;
};

/// Optional per-vertex data beside the two meshes, as plain arrays indexed like mesh.vert.
struct SurfelErrorAttributes
{
    /// Per vertex of S': major semi-axis vectors (EllipseMajorAxis). Null: circular surfels.
    const std::vector<vcg::Point3f>* ellipseMajorAxes = nullptr;
    /// Per vertex of S': minor semi-axis vectors (EllipseMinorAxis); given with the major axes.
    const std::vector<vcg::Point3f>* ellipseMinorAxes = nullptr;
    /// Per vertex of S: index in simplified.vert of the surfel representing it (SurfelIndex);
    /// -1, or a surfel without usable normal, falls back to the nearest surfel center.
    const std::vector<int>* representative = nullptr;
    /// Per vertex of S': a factor in (0, 1] on the widths of its weight only (SurfelBlendScale:
    /// a resampler's way to make the blend follow a surfel closely, at a crease, while the
    /// ellipse still covers its area). Null, or a value outside (0, 1]: 1.
    const std::vector<float>* blendScale = nullptr;
};

/// RMS, maximum and 99.9th percentile of one per-point error over the points it is defined for.
struct ErrorSummary
{
    std::size_t count = 0; ///< points summarized; the figures are NaN when 0
    double rms = std::numeric_limits<double>::quiet_NaN();
    double max = std::numeric_limits<double>::quiet_NaN();
    double p999 = std::numeric_limits<double>::quiet_NaN(); ///< nearest-rank 99.9th percentile
};

/// Everything ComputeSurfelError() measures.
struct SurfelErrorStats
{
    std::size_t originalPointCount = 0; ///< live vertices of S
    std::size_t surfelCount = 0;        ///< live vertices of S'
    std::size_t usableSurfelCount = 0;  ///< surfels with a finite position and a non-zero normal
    /// Points of normalToOwnSurfel that used the nearest surfel for lack of a usable representative.
    std::size_t ownSurfelFromNearestCount = 0;
    std::size_t unconvergedCount = 0; ///< projections stopped by maxIterations
    double diagonal = 0;              ///< bounding-box diagonal of S (finite positions)
    ErrorSummary distance;            ///< d(q, S'): Δ_RMS, Δ_max
    ErrorSummary normalizedDistance;  ///< d(q, S') / diagonal: Δ*_RMS, Δ*_max
    ErrorSummary normalToOwnSurfel;   ///< L2,1 form (a): ‖n_q − n_representative‖
    ErrorSummary normalToBlended;     ///< L2,1 form (b): ‖n_q − n(q0)‖
};


/// Summary of the non-NaN entries of `perPoint` (NaN marks a point the error is undefined for).
inline ErrorSummary SummarizeDefined(const std::vector<double>& perPoint)
{
    std::vector<double> defined;
    defined.reserve(perPoint.size());
    for (double e : perPoint)
        if (!std::isnan(e))
            defined.push_back(e);
    ErrorSummary summary;
    summary.count = defined.size();
    if (defined.empty())
        return summary;
    double sumOfSquares = 0;
    for (double e : defined)
        sumOfSquares += e * e;
    summary.rms = std::sqrt(sumOfSquares / double(defined.size()));
    summary.max = *std::max_element(defined.begin(), defined.end());
    summary.p999 = NearestRankPercentile(std::move(defined), 99.9);
    return summary;
}

namespace surfel_error_detail {

inline bool IsFinite(const Point3d& p)
{
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

/// Largest coordinate magnitude accepted (see CheckCoordinates).
constexpr double kMaxCoordinate = 1e18;

/// Throws std::invalid_argument when a coordinate of the finite point p, vertex `vertex` of
/// the `set` ("original", "simplified"), exceeds kMaxCoordinate in magnitude. The center tree
/// (vcg::KdTree<float>) adds coordinates and squares their differences in single precision:
/// beyond about 1.8e19 distances become infinite, and near FLT_MAX its split values do, which
/// makes vcg's KdTree::split read past its buffer. Within ±1e18 the largest squared distance
/// between two accepted points, 1.2e37, is finite.
inline void CheckCoordinates(const Point3d& p, std::size_t vertex, const char* set)
{
    for (int axis = 0; axis < 3; ++axis)
        if (std::abs(p[axis]) > kMaxCoordinate) {
            char message[256];
            std::snprintf(message, sizeof message,
                          "surfel error: vertex %zu of the %s set has the coordinate %.3g, beyond the "
                          "supported +-1e18 (the spatial index works in single precision): scale the "
                          "layers down",
                          vertex, set, p[axis]);
            throw std::invalid_argument(message);
        }
}





inline void CheckParams(const SurfelErrorParams& p)
{
    if (p.neighborCount < 1 || p.spacingNeighborCount < 1 || p.maxIterations < 1)
        throw std::invalid_argument(
            "surfel error: neighborCount, spacingNeighborCount and maxIterations must be at least 1");
    if (!(p.widthFactor > 0) || !std::isfinite(p.widthFactor))
        throw std::invalid_argument("surfel error: widthFactor must be positive");
    if (!(p.convergenceTolerance >= 0))
        throw std::invalid_argument("surfel error: convergenceTolerance must not be negative");
}

inline void CheckAttributes(const SurfelErrorAttributes& a, std::size_t originalSize,
                            std::size_t simplifiedSize)
{
    if ((a.ellipseMajorAxes == nullptr) != (a.ellipseMinorAxes == nullptr))
        throw std::invalid_argument("surfel error: give both ellipse axes or neither");
    if (a.ellipseMajorAxes != nullptr &&
        (a.ellipseMajorAxes->size() != simplifiedSize || a.ellipseMinorAxes->size() != simplifiedSize))
        throw std::invalid_argument(
            "surfel error: the ellipse axes must have one entry per vertex of the simplified set");
    if (a.blendScale != nullptr && a.blendScale->size() != simplifiedSize)
        throw std::invalid_argument(
            "surfel error: the blend scales must have one entry per vertex of the simplified set");
    if (a.representative == nullptr)
        return;
    if (a.representative->size() != originalSize)
        throw std::invalid_argument(
            "surfel error: the representative array must have one entry per vertex of the original set");
    for (int r : *a.representative)
        if (r < -1 || r >= int(simplifiedSize))
            throw std::invalid_argument("surfel error: a representative index is outside the simplified set "
                                        "(does the SurfelIndex attribute belong to another layer?)");
}

/// Semi-axes (a, b) and minor direction of surfel `vertex` from its ellipse, if it has a usable one.
inline bool EllipseOf(const SurfelErrorAttributes& a, std::size_t vertex, const Point3d& normal,
                      double& major, double& minor, Point3d& minorDirection)
{
    return a.ellipseMajorAxes != nullptr && EllipseWidths((*a.ellipseMajorAxes)[vertex], (*a.ellipseMinorAxes)[vertex],
                                                          normal, major, minor, minorDirection);
}


/// The blend scale of vertex v of S' (SurfelErrorAttributes::blendScale), 1 when absent or invalid.
inline double BlendScaleOf(const SurfelErrorAttributes& a, std::size_t vertex)
{
    return a.blendScale ? UsableBlendScale((*a.blendScale)[vertex]) : 1.0;
}


/// Mean distance from centers[i] to its `count` nearest other centers (0 if it has none).
inline double LocalSpacing(const CenterTree& tree, const std::vector<Point3d>& centers, std::size_t i,
                           int count, CenterTree::Queue& queue)
{
    tree.Nearest(centers[i], count + 1, queue);
    if (queue.getNofElements() < 2)
        return 0;
    // The query point itself (or a duplicate of it) is among the results at distance 0.
    double sum = 0;
    for (int j = 0; j < queue.getNofElements(); ++j)
        sum += (centers[queue.getIndex(j)] - centers[i]).Norm();
    return sum / (queue.getNofElements() - 1);
}

/// Builds the surface of S'; `surfelOfVertex` receives, per vertex of S', its surfel index or -1.
/// \throws std::invalid_argument when S' has no usable surfel.
template <class SimplifiedMesh>
SurfelSurface MakeSurfelSurface(const SimplifiedMesh& simplified, const SurfelErrorAttributes& attributes,
                                const SurfelErrorParams& params, std::vector<int>& surfelOfVertex,
                                std::size_t& liveCount)
{
    std::vector<BlendingSurfel> surfels;
    std::vector<Point3d> centers;
    std::vector<std::size_t> vertexOfSurfel;
    surfelOfVertex.assign(simplified.vert.size(), -1);
    liveCount = 0;
    Box3d box;
    for (std::size_t v = 0; v < simplified.vert.size(); ++v) {
        if (simplified.vert[v].IsD())
            continue;
        ++liveCount;
        BlendingSurfel s;
        s.center = Point3d::Construct(simplified.vert[v].cP());
        s.normal = UnitOrZero(Point3d::Construct(simplified.vert[v].cN()));
        if (!IsFinite(s.center) || s.normal == Point3d(0, 0, 0))
            continue;
        CheckCoordinates(s.center, v, "simplified");
        surfelOfVertex[v] = int(surfels.size());
        surfels.push_back(s);
        centers.push_back(s.center);
        vertexOfSurfel.push_back(v);
        box.Add(s.center);
    }
    if (surfels.empty())
        throw std::invalid_argument(
            "surfel error: the simplified set has no point with a finite position and a "
            "non-zero normal (no normals?)");

    CenterTree tree(centers);
    const double smallestSize = SmallestSurfelSize(box);
    const bool hasRadius = HasPerVertexRadius(simplified);
    const double sigma = params.widthFactor;
    const long surfelCount = long(surfels.size());
#pragma omp parallel
    {
        CenterTree::Queue queue;
#pragma omp for schedule(static)
        for (long i = 0; i < surfelCount; ++i) {
            BlendingSurfel& s = surfels[i];
            const std::size_t v = vertexOfSurfel[i];
            double major = 0, minor = 0;
            if (!EllipseOf(attributes, v, s.normal, major, minor, s.minorDirection)) {
                const double radius = hasRadius ? double(simplified.vert[v].cR()) : 0.0;
                major = minor = (radius > 0 && std::isfinite(radius))
                                    ? radius
                                    : LocalSpacing(tree, centers, i, params.spacingNeighborCount, queue);
            }
            const double scale = BlendScaleOf(attributes, v);
            SetWidths(scale * major, scale * minor, sigma, smallestSize, s);
        }
    }
    return SurfelSurface(std::move(surfels), std::move(tree), params.neighborCount);
}

/// Bounding-box diagonal of the finite positions of S; `liveCount` counts its live vertices.
/// \throws std::invalid_argument when S has no finite position, or one beyond kMaxCoordinate.
template <class OriginalMesh>
double OriginalDiagonal(const OriginalMesh& original, std::size_t& liveCount)
{
    Box3d box;
    for (std::size_t i = 0; i < original.vert.size(); ++i) {
        const auto& v = original.vert[i];
        if (v.IsD())
            continue;
        ++liveCount;
        const Point3d p = Point3d::Construct(v.cP());
        if (!IsFinite(p))
            continue;
        CheckCoordinates(p, i, "original");
        box.Add(p);
    }
    if (box.IsNull())
        throw std::invalid_argument("surfel error: the original set has no point with a finite position");
    return box.Diag();
}

/// Per vertex of S: its errors (NaN where undefined: deleted, skipped, or without a normal for
/// the normal errors) and flags.
struct PointErrors
{
    explicit PointErrors(std::size_t n)
        : distance(n, std::numeric_limits<double>::quiet_NaN()),
          ownNormalError(n, std::numeric_limits<double>::quiet_NaN()),
          blendedNormalError(n, std::numeric_limits<double>::quiet_NaN()), unconverged(n, 0), ownFromNearest(n, 0)
    {}
    std::vector<double> distance, ownNormalError, blendedNormalError;
    std::vector<char> unconverged, ownFromNearest;
};

/// Projects every live point of S with a finite position on `surface` (file header) and fills
/// its entries of `e`; `cb` reports the progress, from the calling thread.
template <class OriginalMesh>
void ProjectOriginal(const OriginalMesh& original, const SurfelSurface& surface,
                     const std::vector<int>& surfelOfVertex, const SurfelErrorAttributes& attributes,
                     const SurfelErrorParams& params, double tolerance, vcg::CallBackPos* cb, PointErrors& e)
{
    const std::size_t n = original.vert.size();
    // Blocks only pace the progress reports; each point is independent of the others.
    const long blockSize = 8192;
    for (long blockStart = 0; blockStart < long(n); blockStart += blockSize) {
        if (cb)
            cb(int(5 + 95 * double(blockStart) / double(n)), "Surfel error: projecting the original points");
        const long blockEnd = std::min(long(n), blockStart + blockSize);
#pragma omp parallel
        {
            SurfelSurface::Scratch scratch;
#pragma omp for schedule(static)
            for (long i = blockStart; i < blockEnd; ++i) {
                const auto& v = original.vert[i];
                const Point3d q = Point3d::Construct(v.cP());
                if (v.IsD() || !IsFinite(q))
                    continue;
                const Point3d normal = UnitOrZero(Point3d::Construct(v.cN()));
                const SurfelSurface::Projection projection =
                    surface.Project(q, normal, params.maxIterations, tolerance, scratch);
                e.distance[i] = (q - projection.foot).Norm();
                e.unconverged[i] = !projection.converged;
                if (normal == Point3d(0, 0, 0))
                    continue;
                const int named = attributes.representative ? (*attributes.representative)[i] : -1;
                const int own = named >= 0 ? surfelOfVertex[named] : -1;
                e.ownFromNearest[i] = own < 0;
                e.ownNormalError[i] =
                    (normal - surface[own >= 0 ? own : projection.nearestSurfel].normal).Norm();
                e.blendedNormalError[i] = (normal - projection.normal).Norm();
            }
        }
    }
}

/// The counts and summaries of `e` into `stats` (whose diagonal is set).
inline void SummarizeErrors(const PointErrors& e, SurfelErrorStats& stats)
{
    stats.unconvergedCount = std::size_t(std::count(e.unconverged.begin(), e.unconverged.end(), 1));
    stats.ownSurfelFromNearestCount =
        std::size_t(std::count(e.ownFromNearest.begin(), e.ownFromNearest.end(), 1));
    stats.distance = SummarizeDefined(e.distance);
    stats.normalizedDistance = stats.distance;
    const double scale = stats.diagonal > 0 ? 1.0 / stats.diagonal : std::numeric_limits<double>::quiet_NaN();
    stats.normalizedDistance.rms *= scale;
    stats.normalizedDistance.max *= scale;
    stats.normalizedDistance.p999 *= scale;
    stats.normalToOwnSurfel = SummarizeDefined(e.ownNormalError);
    stats.normalToBlended = SummarizeDefined(e.blendedNormalError);
}

} // namespace surfel_error_detail



/** Measures how well the surfels S' approximate the oriented point set S (see the file header
 * for the exact operator and figures).
 *
 * \tparam OriginalMesh, SimplifiedMesh  vcg::tri::TriMesh-like types whose vertices have
 *   Coord, Normal and BitFlags (deleted vertices are ignored); a per-vertex Radius of S',
 *   possibly optional (ocf) and disabled, is used when enabled and positive.
 * \param original        S. Points with a non-finite position are skipped; points with a zero
 *                        or non-finite normal count for the distance only.
 * \param simplified      S'. Surfels with a non-finite position or a zero normal are ignored.
 * \param params          see SurfelErrorParams.
 * \param attributes      optional ellipse axes of S' and representatives of S.
 * \param perPointDistance if non-null, resized to original.vert.size() and filled with
 *                        d(q, S'), NaN for deleted or skipped points.
 * \param cb              progress in percent, called from the calling thread only; its return
 *                        value is ignored.
 *
 * \pre  S has at least one live vertex with a finite position; S' at least one usable surfel;
 *       the attribute arrays, when given, have one entry per element of mesh.vert and the
 *       representatives lie in [-1, simplified.vert.size()); params are valid (counts ≥ 1,
 *       widthFactor > 0, convergenceTolerance ≥ 0). A violated precondition throws
 *       std::invalid_argument with a message meant for the user; nothing is written then.
 *       So does a finite coordinate beyond ±1e18 in S or in a usable surfel of S'
 *       (surfel_error_detail::CheckCoordinates: the spatial index works in single precision).
 * \post The figures are computed in double precision and do not depend on the thread count.
 *       Summaries over no point (e.g. normalToOwnSurfel when S has no normals) have count 0
 *       and NaN figures; normalizedDistance is NaN when S has a zero diagonal.
 */
template <class OriginalMesh, class SimplifiedMesh>
SurfelErrorStats ComputeSurfelError(const OriginalMesh& original, const SimplifiedMesh& simplified,
                                    const SurfelErrorParams& params = SurfelErrorParams(),
                                    const SurfelErrorAttributes& attributes = SurfelErrorAttributes(),
                                    std::vector<float>* perPointDistance = nullptr,
                                    vcg::CallBackPos* cb = nullptr)
{
    using namespace surfel_error_detail;
    CheckParams(params);
    CheckAttributes(attributes, original.vert.size(), simplified.vert.size());

    SurfelErrorStats stats;
    stats.diagonal = OriginalDiagonal(original, stats.originalPointCount);

    if (cb)
        cb(0, "Surfel error: preparing the surfels");
    std::vector<int> surfelOfVertex;
    const SurfelSurface surface =
        MakeSurfelSurface(simplified, attributes, params, surfelOfVertex, stats.surfelCount);
    stats.usableSurfelCount =
        std::size_t(std::count_if(surfelOfVertex.begin(), surfelOfVertex.end(), [](int s) {
            return s >= 0;
        }));

    PointErrors errors(original.vert.size());
    const double tolerance = params.convergenceTolerance * stats.diagonal;
    ProjectOriginal(original, surface, surfelOfVertex, attributes, params, tolerance, cb, errors);
    SummarizeErrors(errors, stats);

    if (perPointDistance)
        perPointDistance->assign(errors.distance.begin(), errors.distance.end());
    if (cb)
        cb(100, "Surfel error: done");
    return stats;
}

} // namespace metric
} // namespace gaussphere
} // namespace vcg

#endif // VCG_EXT_SURFEL_ERROR_SURFEL_ERROR_H
