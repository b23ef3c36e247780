// Feature-sensitive resampling of an oriented point set with a subdivided Gaussian
// sphere: the whole pipeline of the paper's section 3, templated on the vcg mesh type.
//
//   1. adaptive neighbours (k nearest inside the cone of normals)  adaptive_neighbors.h
//   2. naive sampling by index propagation                         index_propagation.h
//      and singleton rejoining                                      singleton_rejoining.h
//   3. cluster normalization + singleton rejoining, iterated until
//      the cluster count changes by less than a fraction of N      cluster_normalization.h
//   4. one elliptical surfel per cluster                            surfel_generation.h
//
// Usage:
//   vcg::gaussphere::ResamplingParams param;          // the paper's defaults
//   auto result = vcg::gaussphere::ResamplePointSet(mesh, param, cb);
//   // result.surfels, result.representative[i] = surfel of input vertex i
#ifndef VCG_EXT_GAUSSPHERE_RESAMPLING_H
#define VCG_EXT_GAUSSPHERE_RESAMPLING_H

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <vcg/complex/complex.h>

#include "adaptive_neighbors.h"
#include "cluster_normalization.h"
#include "clustering.h"
#include "gaussian_sphere.h"
#include "index_propagation.h"
#include "point_kdtree.h"
#include "singleton_rejoining.h"
#include "surfel_generation.h"

namespace vcg {
namespace gaussphere {

struct ResamplingParams
{
    int subdivisionLevel = 8;        ///< n: segments per base edge = n - 1 (valid: 2..256)
    BasePolyhedron base = BasePolyhedron::Octahedron;
    int neighborCount = 16;          ///< k of the k-NN search (valid: 1..255)
    int propagationDepth = 6;        ///< depth limit of index propagation; 0 = unlimited
    PropagationReference reference = PropagationReference::Seed;
    PropagationOrder order = PropagationOrder::DepthFirst;
    double normalizationThreshold = 6.0; ///< split clusters with lambda1/lambda2 above it (> 1)
    int minSplitSize = 6;            ///< clusters smaller than this are never split
    double weightWidth = -1;         ///< h of the normal weights; < 0: 0.01 x bbox diagonal
    int maxIterations = 10;          ///< cap on normalization + rejoining rounds
    double convergenceFraction = 0.01; ///< stop when the count changes by less than this x N
    double coverageMargin = 0.75;    ///< ellipse growth, in local sample spacings

    /// Empty when valid, else a message naming the offending parameter.
    std::string Validate() const
    {
        if (subdivisionLevel < 2 || subdivisionLevel > 256) return "SubdivisionLevel must be between 2 and 256";
        if (neighborCount < 1 || neighborCount > 255) return "NeighborCount must be between 1 and 255";
        if (propagationDepth < 0) return "PropagationDepth must be 0 (unlimited) or positive";
        if (!(normalizationThreshold > 1.0)) return "NormalizationThreshold must be greater than 1";
        if (maxIterations < 0) return "MaxIterations must not be negative";
        if (!(weightWidth < 0 || weightWidth > 0)) return "WeightWidth must be positive";
        if (!(coverageMargin >= 0)) return "coverage margin must not be negative";
        return std::string();
    }
};

struct ResamplingStats
{
    int inputCount = 0;            ///< vertices examined (deleted ones excluded)
    int skippedCount = 0;          ///< vertices without a usable normal or position
    int outputCount = 0;
    int naiveCount = 0;            ///< clusters after naive sampling and rejoining
    int iterations = 0;            ///< normalization rounds run
    double meanAdaptiveNeighbors = 0;
    double secondsNeighbors = 0, secondsPropagation = 0, secondsNormalization = 0, secondsSurfels = 0;
    double TotalSeconds() const { return secondsNeighbors + secondsPropagation + secondsNormalization + secondsSurfels; }
};

struct ResamplingResult
{
    std::vector<Surfel> surfels;
    std::vector<int> representative; ///< per input vertex: its surfel, or -1 if skipped
    ResamplingStats stats;
};

/// Thrown when the callback asks to stop (returns false).
struct ResamplingCancelled : std::runtime_error
{
    ResamplingCancelled() : std::runtime_error("resampling cancelled") {}
};

namespace detail {

class StageTimer
{
public:
    double Lap()
    {
        const auto now = std::chrono::steady_clock::now();
        const double s = std::chrono::duration<double>(now - last_).count();
        last_ = now;
        return s;
    }
private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

inline void Report(vcg::CallBackPos *cb, int percent, const char *what)
{
    if (cb && !cb(percent, what)) throw ResamplingCancelled();
}

} // namespace detail

/// Resamples the oriented point set `mesh` (vertices with normals; faces are ignored).
/// Preconditions: param.Validate() is empty. Vertices whose normal is zero or not finite,
/// or whose position is not finite, are skipped and counted in stats.skippedCount.
/// Postconditions: one surfel per cluster; every kept vertex belongs to exactly one
/// cluster; surfel normals have unit length; ellipse axes are tangent and non-zero.
/// Throws std::invalid_argument for invalid parameters or fewer than two usable points,
/// ResamplingCancelled when the callback returns false.
template <class MeshType>
ResamplingResult ResamplePointSet(const MeshType &mesh, const ResamplingParams &param, vcg::CallBackPos *cb = nullptr)
{
    const std::string invalid = param.Validate();
    if (!invalid.empty()) throw std::invalid_argument(invalid);
    ResamplingResult result;
    ResamplingStats &stats = result.stats;
    detail::StageTimer timer;
    detail::Report(cb, 0, "Gaussian sphere resampling: reading points");

    // Usable points, as flat float arrays; `source` maps them back to vertex indices.
    std::vector<vcg::Point3f> points, normals;
    std::vector<int> source;
    result.representative.assign(mesh.vert.size(), -1);
    points.reserve(mesh.vn);
    normals.reserve(mesh.vn);
    source.reserve(mesh.vn);
    for (size_t vi = 0; vi < mesh.vert.size(); ++vi) {
        const auto &v = mesh.vert[vi];
        if (v.IsD()) continue;
        ++stats.inputCount;
        const vcg::Point3f p = vcg::Point3f::Construct(v.cP());
        vcg::Point3f n = vcg::Point3f::Construct(v.cN());
        const float len = n.Norm();
        const bool finite = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]) && std::isfinite(len);
        if (!finite || !(len > 1e-20f)) { ++stats.skippedCount; continue; }
        points.push_back(p);
        normals.push_back(n / len);
        source.push_back(int(vi));
    }
    const int n = int(points.size());
    if (n < 2)
        throw std::invalid_argument("the layer has " + std::to_string(n) +
                                    " point(s) with a usable normal; at least 2 are needed");

    vcg::Box3f box;
    for (const auto &p : points) box.Add(p);
    const double weightWidth = param.weightWidth > 0 ? param.weightWidth : 0.01 * box.Diag();

    // 1. Adaptive neighbours.
    detail::Report(cb, 2, "Gaussian sphere resampling: neighbour search");
    const GaussianSphere sphere(param.subdivisionLevel, param.base);
    const double dMax = sphere.PaperMaxEdgeLength();
    const PointKdTree tree(points);
    AdaptiveNeighborParams neighborParam;
    neighborParam.k = param.neighborCount;
    neighborParam.coneChord = dMax;
    const NeighborGraph graph = BuildAdaptiveNeighbors(points, normals, neighborParam, tree);
    long long kept = 0;
    for (int i = 0; i < n; ++i) kept += graph.count[i];
    stats.meanAdaptiveNeighbors = double(kept) / n;
    stats.secondsNeighbors = timer.Lap();

    // 2. Naive sampling.
    detail::Report(cb, 45, "Gaussian sphere resampling: index propagation");
    std::vector<int> triangle(n);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) triangle[i] = sphere.TriangleOf(normals[i]);
    Clustering clusters;
    clusters.label.assign(n, 0);
    IndexPropagationParams propagation;
    propagation.maxDepth = param.propagationDepth;
    propagation.inscribedRadius = dMax / (2.0 * std::sqrt(3.0));
    propagation.reference = param.reference;
    propagation.order = param.order;
    PropagateIndices(normals, triangle, graph, tree.LeafOrder(), propagation, clusters);
    RejoinSingletons(normals, graph, dMax, clusters);
    clusters.Compact();
    stats.naiveCount = clusters.clusterCount;
    stats.secondsPropagation = timer.Lap();

    // 3. Optimized sampling: normalization and rejoining until the count settles.
    ClusterNormalizationParams normalization;
    normalization.threshold = param.normalizationThreshold;
    normalization.minSplitSize = param.minSplitSize;
    const double settled = param.convergenceFraction * n;
    for (int round = 0; round < param.maxIterations; ++round) {
        detail::Report(cb, 60 + 25 * round / std::max(1, param.maxIterations),
                       "Gaussian sphere resampling: cluster normalization");
        const int before = clusters.clusterCount;
        SplitElongatedClusters(points, normalization, clusters);
        RejoinSingletons(normals, graph, dMax, clusters);
        clusters.Compact();
        ++stats.iterations;
        if (std::abs(clusters.clusterCount - before) < settled) break;
    }
    stats.secondsNormalization = timer.Lap();

    // 4. Surfels.
    detail::Report(cb, 90, "Gaussian sphere resampling: surfels");
    SurfelGenerationParams surfelParam;
    surfelParam.weightWidth = weightWidth;
    surfelParam.coverageMargin = param.coverageMargin;
    result.surfels = GenerateSurfels(points, normals, graph.spacing, clusters, surfelParam);
    for (int i = 0; i < n; ++i) result.representative[source[i]] = clusters.label[i];
    stats.outputCount = int(result.surfels.size());
    stats.secondsSurfels = timer.Lap();
    detail::Report(cb, 100, "Gaussian sphere resampling: done");
    return result;
}

} // namespace gaussphere
} // namespace vcg

#endif
