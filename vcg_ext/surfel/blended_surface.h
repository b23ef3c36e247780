// The blended surface of elliptical surfels: each surfel's anisotropic Gaussian weight, the
// blend of the nearest surfels' positions and normals, and the almost-orthogonal MLS projection
// onto it (Alexa & Adamson 2004). One definition for everything that reads a surfel set as a
// surface: the resampler's fit and error bound, and the paper's error metric
// (vcg_ext/surfel_error/surfel_error.h, whose header documents the operator in full).
#ifndef VCG_EXT_SURFEL_BLENDED_SURFACE_H
#define VCG_EXT_SURFEL_BLENDED_SURFACE_H

#include <vcg/space/box3.h>
#include <vcg/space/index/kdtree/kdtree.h>
#include <vcg/space/point3.h>
#include <vcg_ext/surfel/surfel.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <vector>

namespace vcg {
namespace gaussphere {

/// sigma: Gaussian width of the blend, in units of each surfel's semi-axes. At 1.5 a plain point
/// weighs in as far as one and a half of its spacings, enough for neighbours to overlap.
constexpr double kBlendWidthFactor = 1.5;

/// How the surface is blended and a point projected onto it.
struct BlendParams
{
    int neighborCount = 8;                    ///< k: surfels (nearest centers) blended at each evaluation
    double widthFactor = kBlendWidthFactor;   ///< sigma
    int maxIterations = 10;                   ///< projection steps per point at most
    /// A projection has converged when its last step is at most this fraction of the bounding-box
    /// diagonal of the measured points: far below any error worth reporting.
    double convergenceTolerance = 1e-7;
};

/// Throws std::invalid_argument for parameters the blend cannot use.
inline void CheckBlendParams(const BlendParams& p)
{
    if (p.neighborCount < 1 || p.maxIterations < 1)
        throw std::invalid_argument("surfel surface: neighborCount and maxIterations must be at least 1");
    if (!(p.widthFactor > 0) || !std::isfinite(p.widthFactor))
        throw std::invalid_argument("surfel surface: widthFactor must be positive");
    if (!(p.convergenceTolerance >= 0))
        throw std::invalid_argument("surfel surface: convergenceTolerance must not be negative");
}

/// The unit vector along `n`, or the zero vector when `n` is zero or not finite.
inline Point3d UnitOrZero(const Point3d& n)
{
    const double length = n.Norm();
    if (!std::isfinite(length) || length == 0)
        return Point3d(0, 0, 0);
    return n / length;
}

/// One usable surfel of S', in double precision, with its Gaussian weight.
struct BlendingSurfel
{
    Point3d center;
    Point3d normal;                  ///< unit
    Point3d minorDirection{0, 0, 0}; ///< unit tangent along the minor axis; zero if circular
    double majorInverseWidth2 = 0;   ///< 1 / (σ a)², also applied along the normal
    double minorInverseWidth2 = 0;   ///< 1 / (σ b)²

    /// Weight exponent at x: w(x) = exp(−WeightExponent(x)).
    double WeightExponent(const Point3d& x) const
    {
        const Point3d offset = x - center;
        const double alongMinor = offset.dot(minorDirection);
        return offset.SquaredNorm() * majorInverseWidth2 +
               alongMinor * alongMinor * (minorInverseWidth2 - majorInverseWidth2);
    }
};

/// The same weight in single precision, set up for repeated evaluation at a small size (20 bytes
/// a surfel: the resampler's fit holds one per surfel where its memory peaks): the major width
/// across the tangent plane and along the normal, the minor width along the minor axis.
struct BlendWeight
{
    vcg::Point3f minorDirection{0, 0, 0};
    float inverseMajor2 = 0;  ///< 1 / (sigma a)^2
    float minorExcess = 0;    ///< 1 / (sigma b)^2 - 1 / (sigma a)^2

    BlendWeight() = default;
    explicit BlendWeight(const Surfel &s)
    {
        const float sigma2 = float(kBlendWidthFactor * kBlendWidthFactor);
        const float scale2 = s.blendScale * s.blendScale; // the blend's widths only (Surfel::blendScale)
        const float major2 = scale2 * s.majorAxis.SquaredNorm(), minor2 = scale2 * s.minorAxis.SquaredNorm();
        // GenerateSurfels' axes are never zero; should one be, the surfel weighs 1 everywhere.
        if (!(major2 > 0) || !(minor2 > 0)) return;
        minorDirection = s.minorAxis / s.minorAxis.Norm();
        inverseMajor2 = 1.f / (sigma2 * major2);
        minorExcess = 1.f / (sigma2 * minor2) - inverseMajor2;
    }
    /// The exponent at x of the surfel centred at `centre`.
    float Exponent(const vcg::Point3f &centre, const vcg::Point3f &x) const
    {
        const vcg::Point3f d = x - centre;
        const float alongMinor = d.dot(minorDirection);
        return d.SquaredNorm() * inverseMajor2 + alongMinor * alongMinor * minorExcess;
    }
};


/// k-nearest queries on the surfel centers (vcg::KdTree in single precision).
class CenterTree
{
public:
    using Queue = KdTree<float>::PriorityQueue;

    /// \pre `centers` is non-empty.
    explicit CenterTree(const std::vector<Point3d>& centers)
    {
        std::vector<Point3f> singlePrecision;
        singlePrecision.reserve(centers.size());
        for (const Point3d& c : centers)
            singlePrecision.push_back(Point3f::Construct(c));
        tree_.reset(new KdTree<float>(
            ConstDataWrapper<Point3f>(singlePrecision.data(), int(singlePrecision.size()))));
    }

    /// Fills `queue` with the (at most) k centers nearest to x; the queue is a heap, not sorted.
    void Nearest(const Point3d& x, int k, Queue& queue) const
    {
        // vcg's queries are thread-safe but not declared const.
        tree_->doQueryK(Point3f::Construct(x), k, queue);
    }

    /// Appends to `indices` the centers closer to x than `radius` in single precision (callers
    /// widen the radius by the rounding they must cover); `scratch` receives their squared distances.
    void Within(const Point3d& x, double radius, std::vector<unsigned>& indices, std::vector<float>& scratch) const
    {
        tree_->doQueryDist(Point3f::Construct(x), float(radius), indices, scratch);
    }

private:
    std::unique_ptr<KdTree<float>> tree_;
};

/// The surface defined by the surfels of S' through the almost-orthogonal MLS projection.
class SurfelSurface
{
public:
    struct Projection
    {
        Point3d foot;      ///< q0
        Point3d normal;    ///< n(q0), unit
        int nearestSurfel; ///< surfel whose center is nearest to q
        bool converged;
    };

    /// \pre `surfels` is non-empty and `tree` indexes their centers in the same order.
    SurfelSurface(std::vector<BlendingSurfel> surfels, CenterTree tree, int neighborCount)
        : surfels_(std::move(surfels)), tree_(std::move(tree)), neighborCount_(neighborCount)
    {}

    const BlendingSurfel& operator[](int i) const { return surfels_[i]; }

    /// Appends the surfels whose centers lie within `radius` of x (CenterTree::Within).
    void SurfelsWithin(const Point3d& x, double radius, std::vector<unsigned>& indices, std::vector<float>& scratch) const
    {
        tree_.Within(x, radius, indices, scratch);
    }

    /// The tree of the centers, the surface given up (for a caller that only queries centers
    /// afterwards: the blending data is ~3/4 of a surface's memory).
    CenterTree ReleaseTree() && { return std::move(tree_); }

    /// Per-thread working memory of Project().
    struct Scratch
    {
        CenterTree::Queue queue;
        std::vector<double> exponents;
    };

    /// Projects q; `tolerance` is an absolute step length. `side` (unit, or zero for none) picks
    /// the sheet on thin parts: only surfels with n_i · side > 0 are blended, unless none of the
    /// k nearest is, in which case the side of the heaviest surfel is used.
    /// `reach`, if given, receives a distance from q beyond which no surfel took part in the
    /// projection: adding, removing or changing only surfels whose centres lie farther than
    /// that from q leaves its result unchanged, up to the order in which a rebuilt tree sums the
    /// weights and to which of several centres tied at the k-th distance it returns (infinite
    /// when fewer than k surfels exist).
    Projection Project(const Point3d& q, const Point3d& side, int maxIterations, double tolerance,
                       Scratch& scratch, double* reach = nullptr) const
    {
        Projection result;
        result.foot = q;
        result.converged = false;
        if (reach) *reach = 0;
        for (int step = 0; step < maxIterations && !result.converged; ++step) {
            tree_.Nearest(result.foot, neighborCount_, scratch.queue);
            if (reach) {
                // The k-th nearest centre bounds this step's neighbourhood: a centre farther than
                // that from the foot cannot enter it. The tree works in floats: a margin of 1e-6
                // of the coordinates' magnitude covers their rounding.
                const double kth = scratch.queue.getNofElements() < neighborCount_
                                       ? std::numeric_limits<double>::infinity()
                                       : std::sqrt(double(scratch.queue.getTopWeight()));
                const double stepReach = (result.foot - q).Norm() + kth;
                *reach = std::max(*reach, stepReach + 1e-6 * (stepReach + q.Norm()));
            }
            if (step == 0)
                result.nearestSurfel = NearestInQueue(scratch.queue);
            Point3d average;
            BlendAt(result.foot, side, scratch.queue, scratch.exponents, average, result.normal);
            const double offset = (result.foot - average).dot(result.normal);
            result.foot -= result.normal * offset;
            result.converged = std::abs(offset) <= tolerance;
        }
        return result;
    }

private:
    static int NearestInQueue(const CenterTree::Queue& queue)
    {
        int nearest = 0;
        for (int j = 1; j < queue.getNofElements(); ++j)
            if (queue.getWeight(j) < queue.getWeight(nearest))
                nearest = j;
        return queue.getIndex(nearest);
    }

    /// a(x) and n(x) over the surfels in `queue` that face `side` (see Project());
    /// `exponents` is scratch space.
    void BlendAt(const Point3d& x, const Point3d& side, const CenterTree::Queue& queue,
                 std::vector<double>& exponents, Point3d& average, Point3d& normal) const
    {
        const int count = queue.getNofElements();
        exponents.resize(count);
        int heaviest = -1, heaviestFacing = -1;
        for (int j = 0; j < count; ++j) {
            const BlendingSurfel& s = surfels_[queue.getIndex(j)];
            exponents[j] = s.WeightExponent(x);
            if (heaviest < 0 || exponents[j] < exponents[heaviest])
                heaviest = j;
            if (s.normal.dot(side) > 0 && (heaviestFacing < 0 || exponents[j] < exponents[heaviestFacing]))
                heaviestFacing = j;
        }
        const int reference = heaviestFacing >= 0 ? heaviestFacing : heaviest;
        const Point3d& facing = heaviestFacing >= 0 ? side : surfels_[queue.getIndex(heaviest)].normal;
        double weightSum = 0;
        Point3d weightedCenters(0, 0, 0), weightedNormals(0, 0, 0);
        for (int j = 0; j < count; ++j) {
            const BlendingSurfel& s = surfels_[queue.getIndex(j)];
            // Surfels facing away belong to the other side of a thin part; blending them would
            // pull a(x) between the two sheets and cancel n(x).
            if (s.normal.dot(facing) <= 0)
                continue;
            // Relative to the heaviest blended weight, so the weights never all underflow.
            const double w = std::exp(exponents[reference] - exponents[j]);
            weightSum += w;
            weightedCenters += s.center * w;
            weightedNormals += s.normal * w;
        }
        average = weightedCenters / weightSum;
        // Every blended normal lies in the open hemisphere around `facing`, so the sum is not zero.
        normal = weightedNormals / weightedNormals.Norm();
    }

    std::vector<BlendingSurfel> surfels_;
    CenterTree tree_;
    int neighborCount_;
};

/// Floor on the surfel sizes for centers spanning `box`, so that duplicates or degenerate
/// ellipses keep finite weights; any positive value does when all centers coincide.
inline double SmallestSurfelSize(const Box3d& box) { return box.Diag() > 0 ? 1e-6 * box.Diag() : 1.0; }

/// The Gaussian widths of a surfel with semi-axes (major, minor), floored at smallestSize.
inline void SetWidths(double major, double minor, double sigma, double smallestSize, BlendingSurfel& s)
{
    major = std::max(major, smallestSize);
    minor = std::max(minor, smallestSize);
    s.majorInverseWidth2 = 1.0 / (sigma * major * sigma * major);
    s.minorInverseWidth2 = 1.0 / (sigma * minor * sigma * minor);
}

/// Semi-axes (a, b), the lengths of the semi-axis vectors `majorAxis`, `minorAxis`, and the minor
/// direction of the ellipse about `normal`; false, leaving the direction, when the major axis is
/// not tangent or the minor one not finite (the ellipse is then circular).
inline bool EllipseWidths(const Point3f& majorAxis, const Point3f& minorAxis, const Point3d& normal, double& major,
                          double& minor, Point3d& minorDirection)
{
    const Point3d majorD = Point3d::Construct(majorAxis);
    const Point3d tangentMajor = UnitOrZero(majorD - normal * majorD.dot(normal));
    major = majorD.Norm();
    minor = Point3d::Construct(minorAxis).Norm();
    if (tangentMajor == Point3d(0, 0, 0) || !std::isfinite(minor))
        return false;
    minorDirection = normal ^ tangentMajor;
    return true;
}

/// A surfel's blend scale (Surfel::blendScale), 1 outside (0, 1].
inline double UsableBlendScale(float scale) { return scale > 0 && scale <= 1 ? double(scale) : 1.0; }

/** The surface of elliptical surfels given as arrays (what a resampler has before any mesh is
 * written), with the blend and projection below: project a point q with
 * surface.Project(q, n_q, params.maxIterations, params.convergenceTolerance × diagonal, scratch);
 * afterwards scratch.queue holds the surfels blended at the last step.
 * \pre the four arrays have the same non-zero size; centers finite, normals of unit length,
 *      majorAxes[i] and minorAxes[i] tangent semi-axis vectors, the major one non-zero;
 *      blendScale, if given, of the same size (UsableBlendScale).
 * smallestSize > 0 sets the floor on the surfel sizes (SmallestSurfelSize) instead of the
 * centers' box: a surface of some of a set's surfels then blends them as the whole set's does.
 */
inline SurfelSurface MakeEllipseSurfelSurface(const std::vector<Point3f>& centers,
                                              const std::vector<Point3f>& normals,
                                              const std::vector<Point3f>& majorAxes,
                                              const std::vector<Point3f>& minorAxes,
                                              const BlendParams& params = BlendParams(),
                                              const std::vector<float>* blendScale = nullptr,
                                              double smallestSize = 0)
{
    CheckBlendParams(params);
    const std::size_t count = centers.size();
    if (count == 0 || normals.size() != count || majorAxes.size() != count || minorAxes.size() != count ||
        (blendScale && blendScale->size() != count))
        throw std::invalid_argument("surfel surface: give one center, normal and pair of axes per surfel");
    std::vector<BlendingSurfel> surfels(count);
    std::vector<Point3d> centersD(count);
    Box3d box;
    for (std::size_t i = 0; i < count; ++i) {
        centersD[i] = Point3d::Construct(centers[i]);
        box.Add(centersD[i]);
    }
    if (!(smallestSize > 0))
        smallestSize = SmallestSurfelSize(box);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < long(count); ++i) {
        BlendingSurfel& s = surfels[i];
        s.center = centersD[i];
        s.normal = UnitOrZero(Point3d::Construct(normals[i]));
        double major = 0, minor = 0;
        EllipseWidths(majorAxes[i], minorAxes[i], s.normal, major, minor, s.minorDirection);
        const double scale = UsableBlendScale(blendScale ? (*blendScale)[i] : 1.f);
        SetWidths(scale * major, scale * minor, params.widthFactor, smallestSize, s);
    }
    return SurfelSurface(std::move(surfels), CenterTree(centersD), params.neighborCount);
}

} // namespace gaussphere
} // namespace vcg

#endif
