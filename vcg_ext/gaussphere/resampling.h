// Feature-sensitive resampling of an oriented point set with a subdivided Gaussian
// sphere: the whole pipeline of the paper's section 3, templated on the vcg mesh type.
//
//   1. adaptive neighbours (k nearest inside the cone of normals)  adaptive_neighbors.h
//   2. naive sampling by index propagation                         index_propagation.h
//      and singleton rejoining                                      singleton_rejoining.h
//   3. cluster normalization + singleton rejoining, iterated until
//      the cluster count changes by less than a fraction of N      cluster_normalization.h
//   4. one elliptical surfel per cluster                            surfel_generation.h
//   beyond the paper: an exact size or an error bound              cluster_refinement.h,
//                                                                   surface_error_bound.h
//   at an exact size, exchanges of clusters for the largest error  max_error_exchange.h,
//                                                                   surfel_recipe.h
//   and surfels fitted to the blended surface                       surfel_offset.h
//   with narrower blends around creases                             crease_blend.h
//
// Usage:
//   vcg::gaussphere::ResamplingParams param;          // the paper's defaults
//   auto result = vcg::gaussphere::ResamplePointSet(mesh, param, cb);
//   // result.surfels, result.representative[i] = surfel of input vertex i
//
// Defaults. Level 8, k = 16, depth 6 and threshold 6.0 are the paper's. Where the paper is
// silent the defaults were measured on its own Dragon (437,645 points; paper: 18.3 % and
// an L2,1 RMS of 0.041 at level 8):
// - base icosahedron: at equal counts its smaller, rounder triangles give a lower L2,1
//   error than the octahedron's (dragon, ~21.5 %: 0.0414 against 0.0466);
// - singletons rejoin a cluster only within the propagation radius d_max / (2 sqrt 3) of
//   its normal: with the full cone d_max the L2,1 maximum reached 0.49, with the inscribed
//   radius it is 0.15;
// - clusters under 8 points are never split (their covariance is noise);
// - clusters over 32 points are split whatever their shape: on CAD parts the flat faces
//   otherwise become a few huge surfels whose blend bleeds over the creases (anchor:
//   Delta*max 0.086 -> 0.045 for 3.5 % more surfels; fandisk 0.059 -> 0.038 for 10 %);
//   scanned models hardly change (bunny +0.5 %);
// - beyond the paper, clusters that touch a crease (a neighbour's normal turned by 45 to
//   120 degrees, crease_points.h) are split above 5 points, or when elongated from 4
//   points on: wide or edge-long surfels beside a crease round it off in every blend of
//   the surfels. Measured at equal counts with bench/ (level 8, 16 models), this took
//   our Delta*max below CGAL's hierarchy clustering and MeshLab's Poisson disk sampling
//   on the CAD parts where it was above (block 0.099 -> 0.041 against Poisson's 0.067,
//   and 0.047 at the hierarchy's own count against its 0.051; anchor 0.034 -> 0.023
//   against 0.025 and 0.026) and lowered the blended L2,1 error on every model. A cap of
//   8 left block and rocker_arm above CGAL, 4 and 6 did no better than 5. The dragon
//   gains 0.5 % surfels, which the never-split size of 8 (was 7) gives back;
// together: dragon 23.5 % (102,653 surfels), L2,1 RMS 0.0405, max 0.150.
// Normalization stops when a round changes the count by less than convergenceFraction x N
// (1 %, the paper's rule); on small inputs this may leave a few elongated clusters, and
// convergenceFraction = 0 runs every round up to maxIterations.
#ifndef VCG_EXT_GAUSSPHERE_RESAMPLING_H
#define VCG_EXT_GAUSSPHERE_RESAMPLING_H

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <omp.h>

#include <vcg/complex/complex.h>

#include "adaptive_neighbors.h"
#include "cluster_normalization.h"
#include "cluster_refinement.h"
#include "clustering.h"
#include "crease_blend.h"
#include "flat_vector.h"
#include "gaussian_sphere.h"
#include "index_propagation.h"
#include "max_error_exchange.h"
#include "point_grid.h"
#include "singleton_rejoining.h"
#include "surface_error_bound.h"
#include "surfel_generation.h"
#include "surfel_offset.h"
#include "surfel_recipe.h"
#include "thread_budget.h"
#include "usable_points.h"

namespace vcg {
namespace gaussphere {

struct ResamplingParams
{
    int subdivisionLevel = 8;        ///< n: segments per base edge = n - 1 (valid: 2..256)
    BasePolyhedron base = BasePolyhedron::Icosahedron; ///< see "Defaults" above
    int neighborCount = 16;          ///< k of the k-NN search (valid: 1..255)
    int propagationDepth = 6;        ///< depth limit of index propagation; 0 = unlimited
    PropagationReference reference = PropagationReference::Seed;
    PropagationOrder order = PropagationOrder::DepthFirst;
    double normalizationThreshold = 6.0; ///< split clusters with lambda1/lambda2 above it (> 1)
    int minSplitSize = 8;            ///< clusters smaller than this are never split
    int maxClusterSize = 32;         ///< clusters with more points are split whatever their shape (0 = off)
    double creaseAngle = 45;         ///< degrees: normals turned by more mark a crease (0 = no crease limits)
    int creaseClusterSize = 5;       ///< maxClusterSize of clusters at a crease (0 = off)
    int creaseMinSplitSize = 4;      ///< minSplitSize of clusters at a crease
    float creaseBlendScale = 0.65f;  ///< blend width of the surfels around creases (crease_blend.h);
                                     ///< in (0, 1], 1 = off
    double weightWidth = -1;         ///< h of the normal weights; < 0: 0.01 x bbox diagonal
    int maxIterations = 10;          ///< cap on normalization + rejoining rounds
    double convergenceFraction = 0.01; ///< stop when the count changes by less than this x N
    double coverageMargin = 0.75;    ///< ellipse growth, in local sample spacings
    int targetCount = 0;             ///< exact output size (0 = off): see ResamplePointSet
    double mergeWithin = 1.15;       ///< targetCount: merge down from a level giving at most this x the target
    int maxErrorExchanges = 16;      ///< targetCount: exchanges of clusters that lower the largest error
                                     ///< at the same count (max_error_exchange.h; 0 = off); not with
                                     ///< maxErrorFraction, whose bound sets the count
    bool fitOffsets = true;          ///< surfels moved along their normals to fit the blended surface
                                     ///< (surfel_offset.h; with maxErrorFraction, in each round of
                                     ///< its check, so that the bound holds for the moved surfels)
    double maxErrorFraction = 0;     ///< bound on each point's distance to its surfel's plane, then
                                     ///< to the blended surface (surface_error_bound.h), as a fraction
                                     ///< of the bbox diagonal (0 = off)
    bool adaptThreads = true;        ///< fewer threads than OpenMP's maximum while other programs keep
                                     ///< CPUs busy (thread_budget.h); false: always the maximum. The
                                     ///< output is the same either way

    /// Empty when valid, else a message naming the offending parameter.
    std::string Validate() const
    {
        if (subdivisionLevel < 2 || subdivisionLevel > 256) return "SubdivisionLevel must be between 2 and 256";
        if (neighborCount < 1 || neighborCount > 255) return "NeighborCount must be between 1 and 255";
        if (propagationDepth < 0) return "PropagationDepth must be 0 (unlimited) or positive";
        if (!(normalizationThreshold > 1.0)) return "NormalizationThreshold must be greater than 1";
        if (maxIterations < 0) return "MaxIterations must not be negative";
        if (!(weightWidth < 0 || weightWidth > 0)) return "WeightWidth must be positive";
        if (!(coverageMargin >= 0)) return "CoverageMargin must not be negative";
        if (!(convergenceFraction >= 0)) return "ConvergenceFraction must not be negative";
        if (maxClusterSize < 0) return "MaxClusterSize must be 0 (off) or positive";
        if (!(creaseAngle >= 0 && creaseAngle < 120)) return "CreaseAngle must be between 0 (off) and 120 degrees";
        if (creaseClusterSize < 0 || creaseClusterSize == 1) return "CreaseClusterSize must be 0 (off) or at least 2";
        if (creaseMinSplitSize < 0) return "CreaseMinSplitSize must not be negative";
        if (!(creaseBlendScale > 0 && creaseBlendScale <= 1)) return "CreaseBlendScale must be above 0 and at most 1";
        if (targetCount < 0) return "TargetCount must not be negative";
        if (!(mergeWithin >= 1)) return "mergeWithin must be at least 1";
        if (maxErrorExchanges < 0 || maxErrorExchanges > 100000) return "MaxErrorExchanges must be between 0 (off) and 100000";
        if (!(maxErrorFraction >= 0 && maxErrorFraction < 1)) return "MaxError must be between 0 (off) and 1";
        return std::string();
    }
};

/// Cap on the projections of every point onto the blended surface for maxErrorFraction; the
/// models of bench/ need at most 5.
constexpr int kSurfaceBoundRounds = 16;

struct ResamplingStats
{
    int inputCount = 0;            ///< vertices examined (deleted ones excluded)
    int skippedCount = 0;          ///< vertices without a usable normal or position: the sum of
    int skippedPositions = 0;      ///< ... those whose position is not finite in float
    int skippedNormals = 0;        ///< ... and those with a finite position and a zero or non-finite normal
    int outputCount = 0;
    int naiveCount = 0;            ///< clusters after naive sampling and rejoining
    int iterations = 0;            ///< normalization rounds run
    int levelUsed = 0;             ///< Gaussian sphere level of the final clustering
    int levelsTried = 0;           ///< levels clustered while searching for targetCount
    int splitsForTarget = 0;       ///< clusters split to reach targetCount exactly
    int mergesForTarget = 0;       ///< cluster pairs merged to reach a targetCount below level 2's count
    int splitsForErrorBound = 0;   ///< clusters split to meet maxErrorFraction on the own surfel planes
    int splitsForSurfaceBound = 0; ///< ... and then on the blended surface (surface_error_bound.h)
    int narrowingsForSurfaceBound = 0; ///< halvings of one-point surfels' blend scales for it (same file; up to 3 each)
    int surfaceBoundRounds = 0;    ///< projections of every point onto the blended surface
    int pointsAboveErrorBound = 0; ///< points the blended surface still leaves beyond the bound
    double surfaceErrorMax = 0;    ///< largest distance of a point to it, over `diagonal`
    double diagonal = 0;           ///< bounding-box diagonal of the usable points, in the model's units
    int surfelsNarrowedAtCreases = 0; ///< surfels whose blend creaseBlendScale narrowed
    int surfelsFitted = 0;         ///< surfels moved to fit the blended surface (fitOffsets)
    double largestFitMove = 0;     ///< ... the longest move, over `diagonal`
    int exchangesForMaxError = 0;  ///< cluster exchanges kept at targetCount (maxErrorExchanges)
    int exchangeTrials = 0;        ///< ... surfel sets measured for them
    int creaseFitsForMaxError = 0; ///< ... surfels at creases fitted by their last step (max_error_exchange.h)
    double exchangeMaxBefore = 0, exchangeMaxAfter = 0; ///< ... largest distance to the blended
                                                        ///< surface before and after, over `diagonal`
    int threadsUsed = 0;           ///< OpenMP threads the run took, the fewest of its stages
                                   ///< (ResamplingParams::adaptThreads)
    double meanAdaptiveNeighbors = 0;
    double normalErrorRms = 0;     ///< L2,1 error |n_i - n_surfel| of each point against its own surfel: RMS
    double normalErrorMax = 0;     ///< ... and maximum
    double secondsNeighbors = 0, secondsPropagation = 0, secondsNormalization = 0, secondsRefinement = 0,
           secondsSurfels = 0, secondsExchanges = 0;
    /// The round cap, not a lack of clusters left to split, left points beyond the bound.
    bool SurfaceBoundCapped() const { return pointsAboveErrorBound > 0 && surfaceBoundRounds >= kSurfaceBoundRounds; }
    double TotalSeconds() const
    {
        return secondsNeighbors + secondsPropagation + secondsNormalization + secondsRefinement + secondsSurfels +
               secondsExchanges;
    }
};

struct ResamplingResult
{
    std::vector<Surfel> surfels;
    IndexArray representative;       ///< per input vertex: its surfel, or -1 if skipped
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

/// values[i] = old values[order[i]], through a fresh buffer swapped in (FlatVector: no zeroing
/// pass, huge pages).
template <class Vector>
void Permute(const IndexArray &order, Vector &values)
{
    assert(order.size() == values.size());
    Vector permuted(values.size());
#pragma omp parallel for schedule(static)
    for (int i = 0; i < int(order.size()); ++i) permuted[i] = values[order[i]];
    values.swap(permuted);
}

inline std::string TooFewPointsMessage(const UsablePointCounts &counts)
{
    std::string message = "the layer has " + std::to_string(counts.usable) + " usable point(s); at least 2 are needed";
    if (counts.badPosition > 0 || counts.badNormal > 0)
        message += " (" + std::to_string(counts.badPosition) + " with a non-finite position, " +
                   std::to_string(counts.badNormal) + " with a zero or non-finite normal)";
    return message;
}

inline std::string OverflowMessage(double diagonal)
{
    char text[160];
    std::snprintf(text, sizeof text,
                  "the surfels of this model do not fit in float coordinates (bounding-box diagonal %.3g): "
                  "scale the model down", diagonal);
    return text;
}

/// Multiplies the surfels' lengths by `scale`; false when one of them is no longer a finite float.
inline bool ScaleSurfels(double scale, std::vector<Surfel> &surfels)
{
    bool finite = true;
    const auto scaled = [scale, &finite](const vcg::Point3f &p) {
        const vcg::Point3f q = vcg::Point3f::Construct(vcg::Point3d::Construct(p) * scale);
        finite = finite && std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]);
        return q;
    };
    for (Surfel &s : surfels) {
        s.position = scaled(s.position);
        s.majorAxis = scaled(s.majorAxis);
        s.minorAxis = scaled(s.minorAxis);
        s.fitOffset = float(double(s.fitOffset) * scale);
        const float radius = float(vcg::Point3d::Construct(s.majorAxis).Norm()); // the mesh's radius
        finite = finite && std::isfinite(radius) && std::isfinite(s.fitOffset) && std::isfinite(s.normal.SquaredNorm());
    }
    return finite;
}

inline void Report(vcg::CallBackPos *cb, int percent, const char *what)
{
    if (cb && !cb(percent, what)) throw ResamplingCancelled();
}

} // namespace detail

/// Resamples the oriented point set `mesh` (vertices with normals; faces are ignored).
/// Preconditions: param.Validate() is empty. Vertices whose normal is zero or not finite,
/// or whose position is not finite, are skipped and counted (stats.skippedPositions,
/// stats.skippedNormals). The run works at a unit scale (usable_points.h): a model scaled by a
/// power of two gives the same surfels scaled by it, and any scale the same count.
/// Postconditions: one surfel per cluster; every kept vertex belongs to exactly one
/// cluster; surfel normals have unit length; ellipse axes are tangent and non-zero; every
/// surfel value is finite.
/// Throws std::invalid_argument for invalid parameters or fewer than two usable points,
/// std::overflow_error when the surfels of a model spanning nearly the float range do not fit
/// in it, ResamplingCancelled when the callback returns false.
template <class MeshType>
ResamplingResult ResamplePointSet(const MeshType &mesh, const ResamplingParams &param, vcg::CallBackPos *cb = nullptr)
{
    const std::string invalid = param.Validate();
    if (!invalid.empty()) throw std::invalid_argument(invalid);
    ResamplingResult result;
    ResamplingStats &stats = result.stats;
    RunThreads threads(param.adaptThreads);
    detail::StageTimer timer;
    detail::Report(cb, 0, "Gaussian sphere resampling: reading points");

    // Usable points, as flat float arrays; `source` maps them back to vertex indices.
    PointArray points, normals;
    IndexArray source;
    result.representative.assign(mesh.vert.size(), -1);
    const UsablePointCounts counts = ReadUsablePoints(mesh, points, normals, source);
    stats.inputCount = counts.Live();
    stats.skippedPositions = counts.badPosition;
    stats.skippedNormals = counts.badNormal;
    stats.skippedCount = counts.badPosition + counts.badNormal;
    const int n = counts.usable;
    if (n < 2)
        throw std::invalid_argument(detail::TooFewPointsMessage(counts));

    // The run works at a unit scale (usable_points.h): `diagonal` and every length below are in
    // its units, the surfels are scaled back at the end.
    const double scale = UnitScaleOf(BoxDiagonal(points));
    ScalePoints(scale, points);
    vcg::Box3f box;
    for (const auto &p : points) box.Add(p);
    const double diagonal = box.Diag();
    stats.diagonal = diagonal / scale;
    const double weightWidth = param.weightWidth > 0 ? param.weightWidth * scale : 0.01 * diagonal;

    // 1. Neighbours: one k-NN search, restricted to the cone of each level clustered.
    const char *sorting = "Gaussian sphere resampling: sorting the points in space";
    detail::Report(cb, 1, sorting);
    // Renumber the points along the grid's Morton order: points close in space become
    // close in memory, which makes every later pass cache-friendly (1.5-1.8x faster on
    // randomly ordered input).
    // The grid lives for the neighbour search only (8 B per point: cells and order); after the
    // renumbering its order is the identity, which is also the seed order of index propagation.
    std::unique_ptr<PointGrid> grid(
        new PointGrid(points, PointGrid::kPointsPerCell, [cb, sorting]() { detail::Report(cb, 1, sorting); }));
    const IndexArray &spatial = grid->Order();
    detail::Report(cb, 1, sorting);
    detail::Permute(spatial, points);
    detail::Permute(spatial, normals);
    detail::Permute(spatial, source);
    grid->PointsRenumberedToOrder();
    detail::Report(cb, 2, "Gaussian sphere resampling: neighbour search");
    AdaptiveNeighborParams neighborParam;
    neighborParam.k = param.neighborCount;
    neighborParam.coneChord = GaussianSphere::PaperMaxEdgeLength(param.subdivisionLevel);
    neighborParam.creaseAngle = param.creaseAngle;
    NeighborGraph graph = BuildAdaptiveNeighbors(points, normals, neighborParam, *grid, [cb](double done) {
        return cb == nullptr || cb(2 + int(40 * done), "Gaussian sphere resampling: neighbour search");
    });
    grid.reset();
    if (graph.Size() != n) throw ResamplingCancelled();
    threads.Recheck();
    stats.secondsNeighbors = timer.Lap();
    detail::Report(cb, 45, "Gaussian sphere resampling: clustering");

    // 2-3. Naive sampling and optimized sampling at one level.
    ClusterNormalizationParams normalization;
    normalization.threshold = param.normalizationThreshold;
    normalization.minSplitSize = param.minSplitSize;
    normalization.maxClusterSize = param.maxClusterSize;
    if (param.creaseAngle > 0) {
        normalization.creasePoints = &graph.crease;
        normalization.creaseClusterSize = param.creaseClusterSize;
        normalization.creaseMinSplitSize = param.creaseMinSplitSize;
    }
    struct LevelResult
    {
        Clustering clusters;
        int level = 0, naiveCount = 0, iterations = 0;
        double meanAdaptiveNeighbors = 0;
    };
    auto clusterAtLevel = [&](int level) {
        threads.Recheck();
        LevelResult r;
        r.level = level;
        const GaussianSphere sphere(level, param.base);
        const double dMax = sphere.PaperMaxEdgeLength();
        const double inscribedRadius = dMax / (2.0 * std::sqrt(3.0));
        RestrictToCone(points, normals, dMax, graph);
        long long kept = 0;
        for (int i = 0; i < n; ++i) kept += graph.count[i];
        r.meanAdaptiveNeighbors = double(kept) / n;
        IndexArray triangle(n);
        const int lookupBlock = 4096;
#pragma omp parallel for schedule(static)
        for (int b = 0; b < n; b += lookupBlock)
            sphere.TrianglesOf(&normals[b], std::min(lookupBlock, n - b), &triangle[b]);
        Clustering &c = r.clusters;
        c.label.assign(n, 0);
        IndexPropagationParams propagation;
        propagation.maxDepth = param.propagationDepth;
        propagation.inscribedRadius = inscribedRadius;
        propagation.reference = param.reference;
        propagation.order = param.order;
        const bool labelled = PropagateIndices(normals, triangle, graph, IndexArray(), propagation, c, [cb](double done) {
            return cb == nullptr || cb(45 + int(10 * done), "Gaussian sphere resampling: index propagation");
        });
        if (!labelled) throw ResamplingCancelled();
        RejoinSingletons(normals, graph, inscribedRadius, c);
        c.Compact();
        r.naiveCount = c.clusterCount;
        stats.secondsPropagation += timer.Lap();

        // A report after each step: at 20 M points a round takes seconds, and a MeshLab user
        // must be able to see it move and to cancel it.
        int percent = 56;
        auto reportNormalization = [&]() {
            percent = std::min(75, percent + 2);
            detail::Report(cb, percent, "Gaussian sphere resampling: cluster normalization");
        };
        reportNormalization();
        const double settled = param.convergenceFraction * n;
        for (int round = 0; round < param.maxIterations; ++round) {
            const int before = c.clusterCount;
            SplitElongatedClusters(points, normalization, c);
            reportNormalization();
            RejoinSingletons(normals, graph, inscribedRadius, c);
            reportNormalization();
            c.Compact();
            ++r.iterations;
            if (std::abs(c.clusterCount - before) < settled) break;
        }
        ++stats.levelsTried;
        stats.secondsNormalization += timer.Lap();
        return r;
    };

    LevelResult chosen = clusterAtLevel(param.subdivisionLevel);
    if (param.targetCount > 0) {
        // The count grows with the level: find the finest level in [2, 256] whose count
        // stays at or below the target (doubling, then bisection); splitting then adds the
        // rest. If the next level gives at most mergeWithin times the target, or even level
        // 2 gives more, that level's clusters are merged down to the target instead.
        const int maxLevel = 256;
        int good = 0, bad = 0; // finest level known to fit, coarsest known not to
        LevelResult fitting, coarsestTooMany;
        auto consider = [&](LevelResult &&r) {
            if (r.clusters.clusterCount <= param.targetCount) {
                if (r.level > good) { good = r.level; fitting = std::move(r); }
            } else if (!bad || r.level < bad) {
                bad = r.level;
                coarsestTooMany = std::move(r);
            }
        };
        consider(std::move(chosen));
        while (true) {
            int next;
            if (good && bad) { if (bad - good <= 1) break; next = (good + bad) / 2; }
            else if (good) { if (good == maxLevel) break; next = std::min(maxLevel, 2 * good); }
            else { if (bad == 2) break; next = std::max(2, bad / 2); }
            detail::Report(cb, std::min(75, 45 + 4 * stats.levelsTried), "Gaussian sphere resampling: searching the level");
            consider(clusterAtLevel(next));
        }
        // Just above the target, merging the finer level's most similar neighbours keeps its
        // small clusters at creases, where splitting the coarser level's would not: at CGAL
        // hierarchy's counts (bench/) Delta*max on rocker_arm 0.0077 -> 0.0053, block 0.047 ->
        // 0.041, casting 0.023 -> 0.021.
        const bool mergeDown = bad && coarsestTooMany.clusters.clusterCount <= param.mergeWithin * param.targetCount;
        chosen = std::move(good && !mergeDown ? fitting : coarsestTooMany);
    }
    Clustering &clusters = chosen.clusters;
    stats.levelUsed = chosen.level;
    stats.naiveCount = chosen.naiveCount;
    stats.iterations = chosen.iterations;
    stats.meanAdaptiveNeighbors = chosen.meanAdaptiveNeighbors;

    // Refinements beyond the paper: own-plane error bound, exact size, then the error bound on
    // the blended surface, whose last round already made the final surfels.
    const double invH2 = 1.0 / (weightWidth * weightWidth);
    SurfelGenerationParams surfelParam;
    surfelParam.weightWidth = weightWidth;
    surfelParam.coverageMargin = param.coverageMargin;
    if (param.maxErrorFraction > 0 || param.targetCount > clusters.clusterCount) {
        detail::Report(cb, 80, "Gaussian sphere resampling: refining clusters");
        ClusterRefiner refiner(points, normals, clusters, invH2);
        const double bound = param.maxErrorFraction * diagonal;
        if (param.maxErrorFraction > 0) stats.splitsForErrorBound = refiner.SplitToErrorBound(bound);
        if (param.targetCount > 0) {
            stats.splitsForTarget = refiner.SplitToCount(param.targetCount, [cb](double done) {
                return cb == nullptr || cb(80 + int(9 * done), "Gaussian sphere resampling: splitting clusters");
            });
            if (stats.splitsForTarget == kRefinementCancelled) throw ResamplingCancelled();
        }
        if (param.maxErrorFraction > 0) {
            // Last, so that its figures describe the final clusters; the target's splits may
            // have moved a half's plane away from a member: the own planes are checked again.
            if (stats.splitsForTarget > 0) stats.splitsForErrorBound += refiner.SplitToErrorBound(bound);
            SurfaceErrorBoundResult surface = SplitToSurfaceErrorBound(
                points, normals, graph.spacing, surfelParam, bound, diagonal, kSurfaceBoundRounds, refiner, clusters,
                [cb](int round, double) {
                    return cb == nullptr ||
                           cb(std::min(89, 80 + round), "Gaussian sphere resampling: error bound on the surface");
                },
                [&](std::vector<Surfel> &surfels) {
                    stats.surfelsNarrowedAtCreases = NarrowBlendsAroundCreases(graph, clusters, param.creaseBlendScale, surfels);
                    if (param.fitOffsets)
                        FitSurfelOffsets(points, normals, graph, clusters, normalization.creasePoints, surfels, bound);
                });
            if (surface.cancelled) throw ResamplingCancelled();
            stats.splitsForSurfaceBound = surface.splits;
            stats.narrowingsForSurfaceBound = surface.narrowings;
            stats.surfaceBoundRounds = surface.rounds;
            stats.pointsAboveErrorBound = surface.pointsAbove;
            stats.surfaceErrorMax = diagonal > 0 ? surface.maxDistance / diagonal : 0.0;
            result.surfels = std::move(surface.surfels);
        }
    }
    threads.Recheck();
    SurfelRecipe recipe;
    recipe.generation = surfelParam;
    recipe.creaseBlendScale = param.creaseBlendScale;
    recipe.fitOffsets = param.fitOffsets;
    recipe.creasePoints = normalization.creasePoints;
    // Takes the crease narrowing from every slot of the graph: made before merging cuts it.
    std::unique_ptr<const SurfelMaker> maker;
    if (result.surfels.empty()) maker.reset(new SurfelMaker(points, normals, graph, recipe));
    std::vector<std::vector<int>> mergedLinks; // the merged clusters' links, for the exchanges
    bool merged = false;                       // and then the graph holds the fit's slots only
    if (param.targetCount > 0 && clusters.clusterCount > param.targetCount && param.maxErrorFraction <= 0) {
        const auto merging = [cb](double done) {
            return cb == nullptr || cb(80 + int(9 * done), "Gaussian sphere resampling: merging clusters");
        };
        const std::unique_ptr<MergeBasis> basis =
            BuildMergeBasis(points, normals, graph, clusters, weightWidth, [&merging](double done) { return merging(0.2 * done); });
        if (!basis) throw ResamplingCancelled();
        // From here on the surfels' fit reads the graph's first kOffsetNeighbors slots only, and the
        // exchanges take the links from the merge: the rest goes before the merge's queue exists
        // (32 B a point at k = 16).
        KeepFirstSlots(graph, kOffsetNeighbors);
        stats.mergesForTarget = MergeToCount(*basis, param.targetCount, clusters,
                                             [&merging](double done) { return merging(0.2 + 0.8 * done); });
        if (stats.mergesForTarget == kRefinementCancelled) throw ResamplingCancelled();
        mergedLinks.swap(basis->adjacent);
        merged = true;
    }
    stats.secondsRefinement = timer.Lap();

    // 4. Surfels.
    threads.Recheck();
    detail::Report(cb, 90, "Gaussian sphere resampling: surfels");
    if (result.surfels.empty()) {
        if (param.targetCount > 0 && param.maxErrorExchanges > 0) {
            MaxErrorExchangeParams exchangeParam;
            exchangeParam.maxRounds = param.maxErrorExchanges;
            const MaxErrorExchangeResult exchange = ExchangeForMaxError(
                points, normals, graph, weightWidth, diagonal, exchangeParam, clusters, *maker, result.surfels,
                [cb, &param](int round) {
                    return cb == nullptr ||
                           cb(90 + 9 * round / param.maxErrorExchanges, "Gaussian sphere resampling: exchanges for the largest error");
                },
                merged ? &mergedLinks : nullptr);
            if (exchange.cancelled) throw ResamplingCancelled();
            stats.exchangesForMaxError = exchange.exchanges;
            stats.exchangeTrials = exchange.trials;
            stats.creaseFitsForMaxError = exchange.creaseFits;
            stats.exchangeMaxBefore = diagonal > 0 ? exchange.maxBefore / diagonal : 0.0;
            stats.exchangeMaxAfter = diagonal > 0 ? exchange.maxAfter / diagonal : 0.0;
            stats.secondsExchanges = timer.Lap();
        } else {
            result.surfels = maker->MakeFitted(clusters, [cb]() {
                detail::Report(cb, 95, "Gaussian sphere resampling: fitting the surfels to their blend");
            });
        }
        // Read off the surfels: the exchange made many sets, the figures describe the kept one.
        // (With maxErrorFraction blend scales below 1 also come from the bound: counted there.)
        stats.surfelsNarrowedAtCreases = 0;
        for (const Surfel &s : result.surfels) stats.surfelsNarrowedAtCreases += s.blendScale < 1;
    }
    // Whichever path fitted them, the moves are in the surfels.
    for (const Surfel &s : result.surfels) {
        stats.surfelsFitted += s.fitOffset != 0;
        if (diagonal > 0)
            stats.largestFitMove = std::max(stats.largestFitMove, std::abs(double(s.fitOffset)) / diagonal);
    }
    FlatVector<double> normalError(n);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
        result.representative[source[i]] = clusters.label[i];
        normalError[i] = (normals[i] - result.surfels[clusters.label[i]].normal).Norm();
    }
    double sumSquares = 0; // summed in point order: the same figure for any thread count
    for (double e : normalError) {
        sumSquares += e * e;
        stats.normalErrorMax = std::max(stats.normalErrorMax, e);
    }
    stats.normalErrorRms = std::sqrt(sumSquares / n);
    if (!detail::ScaleSurfels(1.0 / scale, result.surfels))
        throw std::overflow_error(detail::OverflowMessage(stats.diagonal));
    stats.outputCount = int(result.surfels.size());
    stats.threadsUsed = threads.Fewest();
    stats.secondsSurfels = timer.Lap();
    detail::Report(cb, 100, "Gaussian sphere resampling: done");
    return result;
}

} // namespace gaussphere
} // namespace vcg

#endif
