// Representative surfels (paper, sections 3.5 and 4): one elliptical surfel per cluster.
//
// - Position: on the sampled surface above the members' centroid. A curved cluster's
//   centroid lies inside the surface by about half its sagitta, and every blend of the
//   surfels inherits that bias; the surfel is moved along its normal by the Gaussian-weighted
//   mean height of the members around the centroid (width 0.3 of the cluster's radius, so
//   the nearest members dominate; clusters of 6 points or more); the plain mean height is zero
//   by definition of the centroid. The lift matters most at low counts, where clusters are
//   large and curved.
// - Normal: the L2,1-optimal normal, the normalized average of the members' normals
//   weighted by theta(r) = exp(-r^2 / h^2) of their distance r to the centroid. When all
//   weights underflow (a cluster much wider than h) the plain average is used.
// - Axis directions: the eigenvectors of the covariance of the members' normals about
//   that normal, sum (n_i - n')(n_i - n')^T, projected into the tangent plane, as in the
//   paper. Where that covariance is degenerate (a flat cluster whose normals all agree,
//   or fewer than three members) the directions come from the covariance of the members'
//   positions instead, and a single point gets an arbitrary tangent frame.
// - Axis lengths: the paper scales the major axis to the sampling density and sets the
//   aspect to lambda2/lambda1 of the normal covariance, a ratio of normal variations
//   rather than of lengths. Here the ellipse is fitted to the members instead: the aspect
//   is the ratio of the members' spreads along the two directions (the longer one becomes
//   the major axis), the ellipse is scaled until it contains every member's projection,
//   and both semi-axes grow by `coverageMargin` times the local sample spacing so that
//   the ellipses of neighbouring clusters overlap and leave no holes.
#ifndef VCG_EXT_GAUSSPHERE_SURFEL_GENERATION_H
#define VCG_EXT_GAUSSPHERE_SURFEL_GENERATION_H

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <vcg/space/point3.h>

#include <vcg_ext/surfel/surfel.h>

#include <vcg_ext/gaussphere/clustering/clustering.h>
#include <vcg_ext/gaussphere/support/flat_vector.h>
#include <vcg_ext/gaussphere/clustering/principal_axes.h>

namespace vcg {
namespace gaussphere {


struct SurfelGenerationParams
{
    double weightWidth = 0.01;     ///< h of theta(r) = exp(-r^2/h^2), in model units
    double coverageMargin = 0.75;  ///< semi-axes grow by this times the mean local spacing
    double minAspect = 0.1;        ///< lower bound of minor/major, avoids needle ellipses
    /// Per cluster: Surfel::blendScale (SplitToSurfaceErrorBound narrows the blend of one-point
    /// surfels at creases); null, or clusters beyond its size: 1.
    const std::vector<float> *blendScale = nullptr;
};

namespace detail {

inline Eigen::Vector3d ToEigen(const vcg::Point3f &p) { return Eigen::Vector3d(p[0], p[1], p[2]); }
inline vcg::Point3f ToPoint(const Eigen::Vector3d &v) { return vcg::Point3f(float(v[0]), float(v[1]), float(v[2])); }

/// Unit tangent direction from `dir` projected off `normal`, or zero if `dir` is (nearly) normal.
inline Eigen::Vector3d TangentPart(const Eigen::Vector3d &dir, const Eigen::Vector3d &normal)
{
    const Eigen::Vector3d t = dir - dir.dot(normal) * normal;
    const double len = t.norm();
    return len > 1e-6 ? Eigen::Vector3d(t / len) : Eigen::Vector3d::Zero();
}

inline Eigen::Vector3d AnyTangent(const Eigen::Vector3d &normal)
{
    const Eigen::Vector3d helper = std::abs(normal[0]) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    return normal.cross(helper).normalized();
}

} // namespace detail

/// Width of the weights that read the surface height above a cluster's centroid, in units
/// of the cluster's radius: narrow enough that the members nearest the centroid decide, wide
/// enough that a few points at a crease do not (a narrower width raises the largest error on
/// CAD parts).
constexpr double kSurfaceHeightWidth = 0.3;
/// Clusters with fewer members keep their centroid: too few points to read a height from, and
/// a negligible sagitta (at level 8 most clusters are this small).
constexpr int kSurfaceHeightMinMembers = 6;

/// Centroid, surfel centre and normal, and tangent frame of a set of points (a cluster or part
/// of one).
struct ClusterFrame
{
    Eigen::Vector3d centroid;
    Eigen::Vector3d center;  ///< on the surface: centroid moved along the normal (file header)
    Eigen::Vector3d normal;  ///< unit: the Gaussian-weighted average normal
    Eigen::Vector3d u, v;    ///< unit tangents; u: largest normal variation (or positional spread)
};

/// The frame of the points index[begin, end) (non-empty). invH2 = 1/h^2 of the weights.
inline ClusterFrame ComputeClusterFrame(const PointArray &points,
                                        const PointArray &normals, const int *begin,
                                        const int *end, double invH2)
{
    using detail::ToEigen;
    const int size = int(end - begin);
    ClusterFrame f;
    f.centroid = Eigen::Vector3d::Zero();
    for (const int *i = begin; i != end; ++i) f.centroid += ToEigen(points[*i]);
    f.centroid /= size;

    Eigen::Vector3d weighted = Eigen::Vector3d::Zero(), plain = Eigen::Vector3d::Zero();
    for (const int *i = begin; i != end; ++i) {
        const double r2 = (ToEigen(points[*i]) - f.centroid).squaredNorm();
        weighted += std::exp(-r2 * invH2) * ToEigen(normals[*i]);
        plain += ToEigen(normals[*i]);
    }
    f.normal = weighted.norm() > 1e-12 ? weighted.normalized()
             : plain.norm() > 1e-12   ? plain.normalized()
                                      : ToEigen(normals[*begin]);

    CovarianceAccumulator normalCov, positionCov;
    for (const int *i = begin; i != end; ++i) {
        normalCov.Add(ToEigen(normals[*i]) - f.normal);
        positionCov.Add(ToEigen(points[*i]) - f.centroid);
    }
    f.u = Eigen::Vector3d::Zero();
    if (size >= 3) {
        const PrincipalAxes byNormals = ComputePrincipalAxes(normalCov.Covariance());
        if (byNormals.value[0] > 1e-8) // otherwise the normals agree: no direction to read
            f.u = detail::TangentPart(byNormals.axis.col(0), f.normal);
    }
    if (f.u.isZero() && size >= 2)
        f.u = detail::TangentPart(ComputePrincipalAxes(positionCov.Covariance()).axis.col(0), f.normal);
    if (f.u.isZero()) f.u = detail::AnyTangent(f.normal);
    f.v = f.normal.cross(f.u);

    // Squared tangential distance and height (along the normal) of a member from the centroid.
    auto offsets = [&](int i, double &tangential2, double &height) {
        const Eigen::Vector3d d = ToEigen(points[i]) - f.centroid;
        height = d.dot(f.normal);
        tangential2 = d.squaredNorm() - height * height;
    };
    double radius2 = 0, nearest2 = std::numeric_limits<double>::max(), t2, h;
    for (const int *i = begin; i != end; ++i) {
        offsets(*i, t2, h);
        radius2 = std::max(radius2, t2);
        nearest2 = std::min(nearest2, t2);
    }
    double weights = 0, height = 0;
    if (radius2 > 0 && end - begin >= kSurfaceHeightMinMembers) {
        const double invWidth2 = 1.0 / (kSurfaceHeightWidth * kSurfaceHeightWidth * radius2);
        for (const int *i = begin; i != end; ++i) {
            offsets(*i, t2, h);
            // Relative to the nearest member's weight, which therefore never underflows.
            const double w = std::exp(-(t2 - nearest2) * invWidth2);
            weights += w;
            height += w * h;
        }
    }
    f.center = weights > 0 ? Eigen::Vector3d(f.centroid + f.normal * (height / weights)) : f.centroid;
    return f;
}

/// The surfel of one cluster, members [begin, end) (non-empty, in increasing order), as
/// GenerateSurfels makes it; blendScale left at 1.
inline Surfel MakeSurfel(const PointArray &points, const PointArray &normals, const FlatVector<float> &spacing,
                         const int *begin, const int *end, const SurfelGenerationParams &param)
{
    using detail::ToEigen;
    const int size = int(end - begin);
    const double invH2 = param.weightWidth > 0 ? 1.0 / (param.weightWidth * param.weightWidth) : 0.0;
    const ClusterFrame frame = ComputeClusterFrame(points, normals, begin, end, invH2);
    const Eigen::Vector3d &centroid = frame.centroid, &normal = frame.normal;
    Eigen::Vector3d u = frame.u, v = frame.v;
    double meanSpacing = 0;
    for (const int *i = begin; i != end; ++i) meanSpacing += spacing[*i];
    meanSpacing /= size;

    // Spread along u and v; the longer direction becomes the major axis.
    double sxx = 0, syy = 0;
    for (const int *i = begin; i != end; ++i) {
        const Eigen::Vector3d d = ToEigen(points[*i]) - centroid;
        sxx += d.dot(u) * d.dot(u);
        syy += d.dot(v) * d.dot(v);
    }
    if (syy > sxx) { std::swap(sxx, syy); const Eigen::Vector3d t = u; u = v; v = -t; }
    const double aspect = sxx > 0 ? std::max(param.minAspect, std::sqrt(syy / sxx)) : 1.0;
    double scale = 0; // smallest major semi-axis whose ellipse (aspect fixed) holds every member
    for (const int *i = begin; i != end; ++i) {
        const Eigen::Vector3d d = ToEigen(points[*i]) - centroid;
        const double x = d.dot(u), y = d.dot(v) / aspect;
        scale = std::max(scale, x * x + y * y);
    }
    scale = std::sqrt(scale);
    const double margin = param.coverageMargin * meanSpacing;
    Surfel s;
    s.position = detail::ToPoint(frame.center);
    s.normal = detail::ToPoint(normal);
    s.majorAxis = detail::ToPoint(u * (scale + margin));
    s.minorAxis = detail::ToPoint(v * (aspect * scale + margin));
    s.memberCount = size;
    return s;
}

/// One surfel per cluster, in cluster order. `spacing` is the per-point local sample
/// spacing (NeighborGraph::spacing); members = ClusterMembers(clusters). Preconditions: unit
/// normals for all clustered points.
inline std::vector<Surfel> GenerateSurfels(const PointArray &points, const PointArray &normals,
                                           const FlatVector<float> &spacing, const Clustering &clusters,
                                           const ClusterMembers &members, const SurfelGenerationParams &param)
{
    std::vector<Surfel> surfels(clusters.clusterCount);
#pragma omp parallel for schedule(dynamic, 256)
    for (int c = 0; c < clusters.clusterCount; ++c) {
        surfels[c] = MakeSurfel(points, normals, spacing, members.begin(c), members.end(c), param);
        if (param.blendScale && c < int(param.blendScale->size())) surfels[c].blendScale = (*param.blendScale)[c];
    }
    return surfels;
}
/// The same, the member lists built here.
inline std::vector<Surfel> GenerateSurfels(const PointArray &points, const PointArray &normals,
                                           const FlatVector<float> &spacing, const Clustering &clusters,
                                           const SurfelGenerationParams &param)
{
    return GenerateSurfels(points, normals, spacing, clusters, ClusterMembers(clusters), param);
}

} // namespace gaussphere
} // namespace vcg

#endif
