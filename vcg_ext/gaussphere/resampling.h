// Feature-sensitive resampling of an oriented point set with a subdivided Gaussian sphere: the
// whole pipeline of the paper's section 3, templated on the vcg mesh type. docs/algorithm.md maps
// the paper's sections to the headers and gives the reason for each choice where it is silent.
//
//   input: the usable points at a unit scale                       usable_points.h
//   1. adaptive neighbours (k nearest inside the cone of normals)  neighbors/
//   2. naive sampling by index propagation                         clustering/index_propagation.h
//      and singleton rejoining                                      clustering/singleton_rejoining.h
//   3. cluster normalization + singleton rejoining, in rounds until
//      a round splits nothing                                       clustering/cluster_normalization.h
//   4. one elliptical surfel per cluster                            surfels/surfel_generation.h
//   size control beyond the paper, one mode a run (SizeControl):    size_control/
//      Level: the clustering of step 3 as it is
//      TargetCount: level search,                                   size_control/level_search.h
//                   splits or merges                                size_control/cluster_refinement.h
//                   and exchanges for the largest error             size_control/max_error_exchange.h
//                   (their distances measured where changes reach)  size_control/blended_distances.h
//      ErrorBound: splits until every point is within the bound    size_control/surface_error_bound.h
//   surfels fitted to the blended surface                           surfels/surfel_offset.h
//   with narrower blends around creases                             surfels/crease_blend.h
//   the blended surface itself                                      vcg_ext/surfel/blended_surface.h
//   buffers, sorting and CPU dispatch                               support/
//
// Usage:
//   vcg::gaussphere::ResamplingParams param;          // the paper's defaults (resampling_params.h)
//   auto result = vcg::gaussphere::ResamplePointSet(mesh, param, cb);
//   // result.surfels, result.representative[i] = surfel of input vertex i
#ifndef VCG_EXT_GAUSSPHERE_RESAMPLING_H
#define VCG_EXT_GAUSSPHERE_RESAMPLING_H

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <omp.h>

#include <vcg/complex/complex.h>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>
#include <vcg_ext/gaussphere/neighbors/boundary_points.h>
#include <vcg_ext/gaussphere/clustering/stray_members.h>
#include <vcg_ext/gaussphere/clustering/cluster_normalization.h>
#include <vcg_ext/gaussphere/size_control/cluster_refinement.h>
#include <vcg_ext/gaussphere/size_control/level_search.h>
#include <vcg_ext/gaussphere/clustering/clustering.h>
#include <vcg_ext/gaussphere/surfels/crease_blend.h>
#include <vcg_ext/gaussphere/support/flat_vector.h>
#include <vcg_ext/gaussphere/clustering/gaussian_sphere.h>
#include <vcg_ext/gaussphere/clustering/index_propagation.h>
#include <vcg_ext/gaussphere/clustering/seed_order.h>
#include <vcg_ext/gaussphere/size_control/max_error_exchange.h>
#include <vcg_ext/gaussphere/neighbors/morton_order.h>
#include <vcg_ext/gaussphere/neighbors/point_grid.h>
#include <vcg_ext/gaussphere/resampling_params.h>
#include <vcg_ext/gaussphere/clustering/singleton_rejoining.h>
#include <vcg_ext/gaussphere/size_control/surface_error_bound.h>
#include <vcg_ext/gaussphere/surfels/surfel_generation.h>
#include <vcg_ext/gaussphere/surfels/surfel_offset.h>
#include <vcg_ext/gaussphere/surfels/surfel_recipe.h>
#include <vcg_ext/gaussphere/usable_points.h>

namespace vcg {
namespace gaussphere {

/// Cap on the projections of every point onto the blended surface in ErrorBound mode; the
/// models of bench/ need at most 5.
constexpr int kSurfaceBoundRounds = 16;

struct ResamplingStats
{
    int inputCount = 0;            ///< vertices examined (deleted ones excluded)
    int coincidentPoints = 0;      ///< usable points at the exact position of another: each set counts once
    int skippedCount = 0;          ///< vertices without a usable normal or position: the sum of
    int skippedPositions = 0;      ///< ... those whose position is not finite in float
    int skippedNormals = 0;        ///< ... and those with a finite position and a zero or non-finite normal
    int outputCount = 0;
    int naiveCount = 0;            ///< clusters after naive sampling and rejoining
    int iterations = 0;            ///< normalization rounds run
    int levelUsed = 0;             ///< Gaussian sphere level of the final clustering
    SizeControl sizeMode = SizeControl::Level; ///< what set the count (ResamplingParams::SizeMode)
    int targetCount = 0;           ///< the count asked for (SizeControl::TargetCount), from the count or the percentage
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
    double farthestCoordinate = 0; ///< largest magnitude of a usable point's coordinate, in the model's units
    int surfelsNarrowedAtCreases = 0; ///< surfels whose blend creaseBlendScale narrowed
    int surfelsFitted = 0;         ///< surfels moved to fit the blended surface (fitOffsets)
    int boundaryPoints = 0;        ///< points on or beside the rim of an open surface (spreadEvenly; BoundaryBand)
    int rimPoints = 0;             ///< points on the rim of an open surface, kept in small clusters (with a crease angle)
    int straySplits = 0;           ///< clusters split for a stray member beside a crease (stray_members.h)
    double largestFitMove = 0;     ///< ... the longest move, over `diagonal`
    int exchangesForMaxError = 0;  ///< cluster exchanges kept at targetCount (maxErrorExchanges)
    int exchangeTrials = 0;        ///< ... surfel sets measured for them
    int creaseFitsForMaxError = 0; ///< ... surfels fitted by the crease fit after them (max_error_exchange.h)
    double exchangeMaxBefore = 0, exchangeMaxAfter = 0; ///< ... largest distance to the blended
                                                        ///< surface before and after, over `diagonal`
    /// Seam rounds beside ResamplingParams::surroundingSurfels: exchanges kept, points set aside
    /// (no exchange of the run lowered them), the largest distance of the points that count
    /// measured there before and after them, over `diagonal`
    int seamExchanges = 0;
    int seamSetAside = 0;
    double seamMaxBefore = 0, seamMaxAfter = 0;
    int threadsUsed = 0;           ///< OpenMP threads the run could take (the host's setting)
    double meanAdaptiveNeighbors = 0;
    double normalErrorRms = 0;     ///< L2,1 error |n_i - n_surfel| of each point against its own surfel: RMS
    double normalErrorMax = 0;     ///< ... and maximum
    double secondsNeighbors = 0, secondsPropagation = 0, secondsNormalization = 0, secondsRefinement = 0,
           secondsSurfels = 0, secondsExchanges = 0;
    /// Why a TargetCount run gave another count than asked, or empty when it gave that count.
    std::string TargetMissReason() const
    {
        if (sizeMode != SizeControl::TargetCount || outputCount == targetCount) return std::string();
        const int distinct = inputCount - skippedCount - coincidentPoints;
        if (outputCount < targetCount && targetCount > distinct)
            return "the input has only " + std::to_string(distinct) + " usable point(s)" +
                   (coincidentPoints > 0 ? " at distinct positions" : "");
        return outputCount < targetCount ? "no cluster left to split" : "no neighbouring clusters left to merge";
    }
    /// The round cap, not a lack of clusters left to split, left points beyond the bound.
    bool SurfaceBoundCapped() const { return pointsAboveErrorBound > 0 && surfaceBoundRounds >= kSurfaceBoundRounds; }
    /// ErrorBound: why points remain beyond the bound; empty when none does.
    std::string ErrorBoundMissReason() const
    {
        if (sizeMode != SizeControl::ErrorBound || pointsAboveErrorBound == 0) return std::string();
        return SurfaceBoundCapped() ? "the refinement stopped at its cap of projection rounds"
                                    : "the surfels around them are split and narrowed as far as they go";
    }
    /// When the input's float coordinates are coarse (CoarseFloatStep): what that does and what to
    /// do; empty otherwise.
    std::string CoarsePositionsReason() const
    {
        const double step = CoarseFloatStep(farthestCoordinate, diagonal);
        if (step == 0) return std::string();
        char text[400];
        std::snprintf(text, sizeof text,
                      "the points lie up to %.7g units from the origin, %.0f times their bounding-box diagonal: float "
                      "coordinates there are held in steps of %.3g (%.2g of the diagonal), which rounds positions and "
                      "merges close points; move the points towards the origin before they are read as float "
                      "(gsresample does so itself for double-precision PLY files)",
                      farthestCoordinate, farthestCoordinate / diagonal, step, step / diagonal);
        return text;
    }
    double TotalSeconds() const
    {
        return secondsNeighbors + secondsPropagation + secondsNormalization + secondsRefinement + secondsSurfels +
               secondsExchanges;
    }
};

/// The steps from a level's clusters to a target count (SplitToCount or MergeToCount).
struct CountRecord
{
    /// The splits, as surfel indices (the clusters keep their index from the split to the surfels).
    std::vector<CountSplit> splits;
    /// The merges, as numbered at the level ...
    std::vector<CountMerge> merges;
    /// ... and with them, per input vertex, its cluster at the level (-1 if skipped).
    IndexArray levelRepresentative;
};

struct ResamplingResult
{
    std::vector<Surfel> surfels;
    IndexArray representative;       ///< per input vertex: its surfel, or -1 if skipped
    /// TargetCount without exchanges, with recordCountSteps: how the level's clusters came to the count.
    CountRecord targetRecord;
    /// TargetCount with exchanges: the largest distance to the blended surface before them and after
    /// each kept one, in the model's units, over the points that count (countedVertices).
    std::vector<double> exchangeMaxima;
    /// TargetCount with exchanges and ResamplingParams::reportHighestAtCreaseFit: the highest figures
    /// of the points that count on entry to the crease fit, the distances in the model's units.
    CreaseFitEntry creaseFitEntry;
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

/// values[i] = old values[order[i]], written into `spare`, which then holds the old values: one
/// spare passed from array to array of the same size reuses memory already in use, where a fresh
/// buffer per array would be first touched page by page (no zeroing pass either way).
template <class Vector>
void Permute(const IndexArray &order, Vector &values, Vector &spare)
{
    assert(order.size() == values.size());
    spare.resize(values.size());
#pragma omp parallel for schedule(static)
    for (int i = 0; i < int(order.size()); ++i) spare[i] = values[order[i]];
    values.swap(spare);
}

inline std::string TooFewPointsMessage(const UsablePointCounts &counts)
{
    std::string message = "the layer has " + std::to_string(counts.usable) + " usable point(s); at least 2 are needed";
    if (counts.badPosition > 0 || counts.badNormal > 0)
        message += " (" + std::to_string(counts.badPosition) + " with a non-finite position, " +
                   std::to_string(counts.badNormal) + " with a zero or non-finite normal)";
    return message;
}

/// Why the surfels do not fit in float at the model's scale: the model's size, or its distance
/// from the origin (`farthest`, the largest coordinate's magnitude) when that is what is large.
inline std::string OverflowMessage(double diagonal, double farthest)
{
    char text[200];
    if (farthest > 1e3 * diagonal)
        std::snprintf(text, sizeof text,
                      "the surfels of this model do not fit in float coordinates (a coordinate of %.3g, bounding-box "
                      "diagonal %.3g): move the model towards the origin", farthest, diagonal);
    else
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

/// The state of one run, shared by its stages: the usable points at unit scale in Morton order
/// (`source` maps them back to the mesh's vertices), their neighbour graph, the clusters.
struct Run
{
    const ResamplingParams &param;
    vcg::CallBackPos *cb;
    ResamplingStats &stats;
    StageTimer timer;
    PointArray points, normals;
    IndexArray source;
    /// (vertex, point) per usable vertex at the position of a point that stands for it
    /// (MergeCoincidentPoints); the vertex joins that point's surfel.
    std::vector<std::pair<int, int>> coincident;
    NeighborGraph graph;
    IndexArray seedOrder;   ///< of index propagation (seed_order.h)
    FlatVector<char> limited; ///< per point: at a crease or on the rim, where clusters are kept small
    double scale = 1;       ///< unit scale = scale x the model's
    double diagonal = 0;    ///< of the points, at unit scale
    double weightWidth = 0; ///< h of the surfel normal weights, at unit scale
    ClusterNormalizationParams normalization;
    Clustering clusters;

    Run(const ResamplingParams &p, vcg::CallBackPos *callback, ResamplingStats &s) : param(p), cb(callback), stats(s) {}
    bool Progress(int percent, const char *what) const { return cb == nullptr || cb(percent, what); }
    SurfelGenerationParams Generation() const
    {
        SurfelGenerationParams generation;
        generation.weightWidth = weightWidth;
        generation.coverageMargin = param.tuning.coverageMargin;
        return generation;
    }
    /// The spread term of every merge of the run, to the count and in the exchanges alike.
    MergeSpread MergeSpreadTerm() const { return param.spreadEvenly ? MergeSpread::Extent : MergeSpread::Ward; }
    SurfelRecipe Recipe() const
    {
        SurfelRecipe recipe;
        recipe.generation = Generation();
        recipe.creaseBlendScale = param.tuning.creaseBlendScale;
        recipe.fitOffsets = param.fitOffsets;
        recipe.pinnedPoints = normalization.creasePoints;
        return recipe;
    }
};

/// The usable points of `mesh` at unit scale (usable_points.h).
template <class MeshType>
void ReadPoints(const MeshType &mesh, Run &run)
{
    ResamplingStats &stats = run.stats;
    const UsablePointCounts counts = ReadUsablePoints(mesh, run.points, run.normals, run.source);
    stats.inputCount = counts.Live();
    stats.skippedPositions = counts.badPosition;
    stats.skippedNormals = counts.badNormal;
    stats.skippedCount = counts.badPosition + counts.badNormal;
    if (counts.usable < 2) throw std::invalid_argument(TooFewPointsMessage(counts));
    vcg::Box3f box;
    for (const auto &p : run.points) box.Add(p);
    for (int d = 0; d < 3; ++d)
        stats.farthestCoordinate = std::max({stats.farthestCoordinate, std::abs(double(box.min[d])),
                                             std::abs(double(box.max[d]))});
    const UnitScaleBox unit = MeasureUnitScale(box);
    run.scale = unit.scale;
    ScalePoints(run.scale, run.points);
    run.diagonal = unit.diagonal;
    stats.diagonal = run.diagonal / run.scale;
    run.weightWidth = run.param.weightWidth > 0 ? run.param.weightWidth * run.scale : 0.01 * run.diagonal;
}

/// True when two points have the same coordinates, bit for bit (as the Morton order compares them).
inline bool SamePosition(const vcg::Point3f &a, const vcg::Point3f &b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Coincident points facing one side count once. Copies of a point (merged scans, repeated
/// exports) would fill each other's k nearest neighbours and keep apart the clusters that one copy
/// of each would join, so the result would depend on how often a point was copied. In Morton order
/// the copies of a position are consecutive, by vertex index. Each copy joins the first preceding
/// copy whose normal is less than 90 degrees from its own (opposite normals at one position are two
/// sides of a thin part, and stay apart); the point kept takes the normalized sum of its copies'
/// normals, and the others are listed in run.coincident, to join its surfel at the end (Finish).
/// When every point lies at one position there is nothing to merge them into: they stay as they
/// are, and make one surfel.
inline void MergeCoincidentPoints(Run &run)
{
    const int n = int(run.points.size());
    int copies = 0;
#pragma omp parallel for schedule(static) reduction(+ : copies)
    for (int i = 1; i < n; ++i) copies += SamePosition(run.points[i], run.points[i - 1]);
    if (copies == 0 || copies == n - 1) return;
    int kept = 0;
    struct Head
    {
        int point;           ///< the index it is kept at
        vcg::Point3f normal; ///< its own normal
        vcg::Point3d sum;    ///< the sum of its copies' normals, its own included
        bool mixed;          ///< some copy's normal differs from its own
    };
    std::vector<Head> heads; // the points kept at one position
    for (int first = 0, end = 0; first < n; first = end) {
        heads.clear();
        for (end = first; end < n && SamePosition(run.points[end], run.points[first]); ++end) {
            const vcg::Point3f normal = run.normals[end];
            auto head = std::find_if(heads.begin(), heads.end(), [&](const Head &h) { return h.normal.dot(normal) > 0; });
            if (head != heads.end()) {
                head->sum += vcg::Point3d::Construct(normal);
                head->mixed = head->mixed || !(normal == head->normal);
                run.coincident.emplace_back(run.source[end], head->point);
                continue;
            }
            heads.push_back(Head{kept, normal, vcg::Point3d::Construct(normal), false});
            run.points[kept] = run.points[end];
            run.source[kept] = run.source[end];
            ++kept;
        }
        for (const Head &head : heads)
            run.normals[head.point] = head.mixed ? vcg::Point3f::Construct(head.sum / head.sum.Norm()) : head.normal;
    }
    run.points.resize(kept);
    run.normals.resize(kept);
    run.source.resize(kept);
    run.stats.coincidentPoints = n - kept;
}

/// Step 1: the points renumbered along the Morton curve of their own coordinates
/// (morton_order.h: points close in space become close in memory, which makes every later pass
/// cache-friendly; the order breaks every tie, and it is the same for a part of an input
/// whatever else the input holds), the seed order of index propagation, then their k nearest
/// neighbours and crease points.
inline void FindNeighbors(Run &run)
{
    const char *sorting = "Gaussian sphere resampling: sorting the points in space";
    Report(run.cb, 1, sorting);
    IndexArray order = MortonOrder(run.points);
    Report(run.cb, 1, sorting);
    {
        PointArray spare;
        Permute(order, run.points, spare);
        Permute(order, run.normals, spare);
    }
    // The order becomes the permuted source: each entry is read once, then overwritten.
#pragma omp parallel for schedule(static)
    for (int i = 0; i < int(order.size()); ++i) order[i] = run.source[order[i]];
    run.source.swap(order);
    MergeCoincidentPoints(run);
    run.seedOrder = SeedOrder(run.points, run.param.tuning.seedSalt);
    vcg::CallBackPos *cb = run.cb;
    std::unique_ptr<PointGrid> grid(
        new PointGrid(run.points, PointGrid::kPointsPerCell, [cb, sorting]() { Report(cb, 1, sorting); }));
    Report(run.cb, 2, "Gaussian sphere resampling: neighbour search");
    AdaptiveNeighborParams neighborParam;
    neighborParam.k = run.param.neighborCount;
    neighborParam.coneChord = GaussianSphere::PaperMaxEdgeLength(run.param.subdivisionLevel);
    neighborParam.creaseAngle = run.param.creaseAngle;
    if (run.param.creaseAngle > 0 || run.param.spreadEvenly) neighborParam.boundaryGapDegrees = kBoundaryGapDegrees;
    run.graph = BuildAdaptiveNeighbors(run.points, run.normals, neighborParam, *grid, [&run](double done) {
        return run.Progress(2 + int(40 * done), "Gaussian sphere resampling: neighbour search");
    });
    if (run.graph.Size() != int(run.points.size())) throw ResamplingCancelled();

    const ResamplingTuning &tuning = run.param.tuning;
    run.normalization.threshold = run.param.normalizationThreshold;
    run.normalization.minSplitSize = tuning.minSplitSize;
    run.normalization.maxClusterSize = tuning.maxClusterSize;
    if (run.param.creaseAngle > 0) {
        // Rim points get the crease points' cluster limits (boundary_points.h).
        run.limited = run.graph.crease;
        const FlatVector<char> &rim = run.graph.boundary;
        for (size_t i = 0; i < run.limited.size(); ++i) run.limited[i] = char(run.limited[i] | rim[i]);
        run.stats.rimPoints = int(std::count(rim.begin(), rim.end(), char(1)));
        run.normalization.creasePoints = &run.limited;
        run.normalization.creaseClusterSize = tuning.creaseClusterSize;
        run.normalization.creaseMinSplitSize = tuning.creaseMinSplitSize;
    }
    run.stats.secondsNeighbors = run.timer.Lap();
}

struct LevelClustering
{
    Clustering clusters;
    int level = 0, naiveCount = 0, iterations = 0, straySplits = 0;
    double meanAdaptiveNeighbors = 0;
};

/// Steps 2 and 3 at one level: naive sampling, normalization rounds, then the split of clusters
/// with a stray member beside a crease (stray_members.h). A report after each
/// step: at 20 M points a round takes seconds, and a MeshLab user must see it move and can cancel.
inline LevelClustering ClusterAtLevel(Run &run, int level)
{
    const int n = int(run.points.size());
    LevelClustering r;
    r.level = level;
    const GaussianSphere sphere(level);
    const double inscribedRadius = sphere.PaperMaxEdgeLength() / (2.0 * std::sqrt(3.0));
    RestrictToCone(run.points, run.normals, sphere.PaperMaxEdgeLength(), run.graph);
    long long kept = 0;
    for (int i = 0; i < n; ++i) kept += run.graph.count[i];
    r.meanAdaptiveNeighbors = double(kept) / n;
    IndexArray triangle(n);
    const int lookupBlock = 4096;
#pragma omp parallel for schedule(static)
    for (int b = 0; b < n; b += lookupBlock)
        sphere.TrianglesOf(&run.normals[b], std::min(lookupBlock, n - b), &triangle[b]);
    Clustering &c = r.clusters;
    c.label.assign(n, 0);
    IndexPropagationParams propagation;
    propagation.maxDepth = run.param.propagationDepth;
    propagation.inscribedRadius = inscribedRadius;
    if (!PropagateIndices(run.normals, triangle, run.graph, run.seedOrder, propagation, c, [&run](double done) {
            return run.Progress(45 + int(10 * done), "Gaussian sphere resampling: index propagation");
        }))
        throw ResamplingCancelled();
    RejoinSingletons(run.normals, run.graph, inscribedRadius, c);
    c.Compact();
    r.naiveCount = c.clusterCount;
    run.stats.secondsPropagation += run.timer.Lap();

    int percent = 56;
    const auto report = [&]() {
        percent = std::min(75, percent + 2);
        Report(run.cb, percent, "Gaussian sphere resampling: cluster normalization");
    };
    report();
    r.iterations = NormalizeClusters(run.points, run.normals, run.graph, run.normalization, inscribedRadius,
                                     run.param.tuning.maxIterations, c, report);
    r.straySplits = SplitClustersWithStrayMembers(run.points, run.normals, run.graph, run.normalization,
                                                  inscribedRadius, c);
    ++run.stats.levelsTried;
    run.stats.secondsNormalization += run.timer.Lap();
    return r;
}

/// The clustering a run continues from: its clusters and the figures of its level.
inline void Adopt(LevelClustering &&chosen, Run &run)
{
    run.clusters = std::move(chosen.clusters);
    run.stats.levelUsed = chosen.level;
    run.stats.naiveCount = chosen.naiveCount;
    run.stats.iterations = chosen.iterations;
    run.stats.straySplits = chosen.straySplits;
    run.stats.meanAdaptiveNeighbors = chosen.meanAdaptiveNeighbors;
}

/// The clusters of the level LevelSearch chooses for `target` (size_control/level_search.h).
inline LevelClustering SearchLevel(Run &run, int target)
{
    LevelSearch search(std::uint64_t(target), run.param.subdivisionLevel);
    LevelClustering fitting, coarsestTooMany;
    while (const int level = search.Next()) {
        if (run.stats.levelsTried > 0)
            Report(run.cb, std::min(75, 45 + 4 * run.stats.levelsTried), "Gaussian sphere resampling: searching the level");
        LevelClustering r = ClusterAtLevel(run, level);
        (search.Tell(std::uint64_t(r.clusters.clusterCount)) ? fitting : coarsestTooMany) = std::move(r);
    }
    return std::move(search.Merges(run.param.tuning.mergeWithin) ? coarsestTooMany : fitting);
}

/// The surfels whose blend is narrowed, read off the surfels (counted where they were made).
inline int CountNarrowed(const std::vector<Surfel> &surfels)
{
    return int(std::count_if(surfels.begin(), surfels.end(), [](const Surfel &s) { return s.blendScale < 1; }));
}

/// SizeControl::Level: one surfel per cluster of the parameter's level.
inline std::vector<Surfel> ResampleAtLevel(Run &run)
{
    Adopt(ClusterAtLevel(run, run.param.subdivisionLevel), run);
    run.stats.secondsRefinement = run.timer.Lap();
    Report(run.cb, 90, "Gaussian sphere resampling: surfels");
    const SurfelMaker maker(run.points, run.normals, run.graph, run.Recipe());
    std::vector<Surfel> surfels = maker.MakeFitted(run.clusters, [&run]() {
        Report(run.cb, 95, "Gaussian sphere resampling: fitting the surfels to their blend");
    });
    run.stats.surfelsNarrowedAtCreases = CountNarrowed(surfels);
    return surfels;
}

/// Merges the most similar neighbouring clusters down to `target`; returns the merged clusters'
/// links, which the exchanges read. From here on the surfels' fit reads the graph's first
/// kOffsetNeighbors slots only: the rest goes before the merge's queue exists (32 B a point at k = 16).
inline std::vector<std::vector<int>> MergeClustersToCount(Run &run, int target, std::vector<CountMerge> *record)
{
    const auto merging = [&run](double done) {
        return run.Progress(80 + int(9 * done), "Gaussian sphere resampling: merging clusters");
    };
    const std::unique_ptr<MergeBasis> basis = BuildMergeBasis(run.points, run.normals, run.graph, run.clusters,
                                                              run.weightWidth,
                                                              [&merging](double done) { return merging(0.2 * done); },
                                                              run.MergeSpreadTerm());
    if (!basis) throw ResamplingCancelled();
    KeepFirstSlots(run.graph, kOffsetNeighbors);
    run.stats.mergesForTarget =
        MergeToCount(*basis, target, run.clusters, [&merging](double done) { return merging(0.2 + 0.8 * done); }, record);
    if (run.stats.mergesForTarget == kRefinementCancelled) throw ResamplingCancelled();
    return std::move(basis->adjacent);
}

/// ResamplingParams::surroundingSurfels at unit scale, and the anchor keys of run's points
/// (ResamplingParams::anchorKeys, else the vertex indices).
inline FixedSurround Surround(const Run &run)
{
    FixedSurround surround;
    surround.surfels = run.param.surroundingSurfels;
    if (!ScaleSurfels(run.scale, surround.surfels)) throw std::overflow_error("a surrounding surfel overflows at unit scale");
    const std::vector<std::uint64_t> &keys = run.param.anchorKeys;
    surround.anchorKeys.resize(run.points.size());
    for (size_t i = 0; i < run.points.size(); ++i)
        surround.anchorKeys[i] = keys.empty() ? std::uint64_t(run.source[i]) : keys[size_t(run.source[i])];
    return surround;
}

/// The exchanges of clusters for the largest error (max_error_exchange.h); `surfels` receives
/// the kept set, `result` the largest distance before them and after each kept one, and the
/// crease fit's report.
inline void ExchangeClusters(Run &run, const SurfelMaker &maker, std::vector<std::vector<int>> *mergedLinks,
                             std::vector<Surfel> &surfels, ResamplingResult &result)
{
    MaxErrorExchangeParams exchangeParam;
    exchangeParam.mergeSpread = run.MergeSpreadTerm();
    exchangeParam.maxRounds = run.param.exchangeRounds >= 0
                                  ? std::min(run.param.exchangeRounds, run.param.maxErrorExchanges)
                                  : run.param.maxErrorExchanges;
    if (run.param.countedVertices > 0) {
        exchangeParam.counted.resize(run.points.size());
        for (size_t i = 0; i < run.points.size(); ++i)
            exchangeParam.counted[i] = run.source[i] < run.param.countedVertices;
    }
    exchangeParam.creaseFitLimits = run.param.creaseFitLimits;
    exchangeParam.creaseFitLimits.distance *= run.scale;
    exchangeParam.reportHighest = run.param.reportHighestAtCreaseFit;
    if (!run.param.surroundingSurfels.empty()) exchangeParam.surround = Surround(run);
    exchangeParam.seamTarget = run.param.seamTarget * run.scale;
    exchangeParam.seamRounds = run.param.maxErrorExchanges;
    const MaxErrorExchangeResult exchange = ExchangeForMaxError(
        run.points, run.normals, run.graph, run.weightWidth, run.diagonal, exchangeParam, run.clusters, maker, surfels,
        [&run](int round) {
            return run.Progress(90 + 9 * round / run.param.maxErrorExchanges,
                                "Gaussian sphere resampling: exchanges for the largest error");
        },
        mergedLinks);
    if (exchange.cancelled) throw ResamplingCancelled();
    ResamplingStats &stats = run.stats;
    stats.exchangesForMaxError = exchange.exchanges;
    stats.seamExchanges = exchange.seamExchanges;
    stats.seamSetAside = exchange.seamSetAside;
    stats.seamMaxBefore = run.diagonal > 0 ? exchange.seamMaxBefore / run.diagonal : 0.0;
    stats.seamMaxAfter = run.diagonal > 0 ? exchange.seamMaxAfter / run.diagonal : 0.0;
    stats.exchangeTrials = exchange.trials;
    stats.creaseFitsForMaxError = exchange.creaseFits;
    stats.exchangeMaxBefore = run.diagonal > 0 ? exchange.maxBefore / run.diagonal : 0.0;
    stats.exchangeMaxAfter = run.diagonal > 0 ? exchange.maxAfter / run.diagonal : 0.0;
    result.exchangeMaxima.clear();
    for (double m : exchange.maxima) result.exchangeMaxima.push_back(m / run.scale);
    result.creaseFitEntry = exchange.creaseFitEntry;
    for (double &d : result.creaseFitEntry.distances) d /= run.scale;
    stats.secondsExchanges = run.timer.Lap();
}

/// The surfels of the clusters at their final count: through the exchanges for the largest error
/// (`mergedLinks`: the merged clusters' links, null if none merged), else fitted to their blend.
inline std::vector<Surfel> SurfelsAtCount(Run &run, const SurfelMaker &maker,
                                          std::vector<std::vector<int>> *mergedLinks, ResamplingResult &result)
{
    run.stats.secondsRefinement = run.timer.Lap();
    Report(run.cb, 90, "Gaussian sphere resampling: surfels");
    std::vector<Surfel> surfels;
    if (run.param.maxErrorExchanges > 0) {
        ExchangeClusters(run, maker, mergedLinks, surfels, result);
    } else {
        surfels = maker.MakeFitted(run.clusters, [&run]() {
            Report(run.cb, 95, "Gaussian sphere resampling: fitting the surfels to their blend");
        });
    }
    run.stats.surfelsNarrowedAtCreases = CountNarrowed(surfels); // of the kept set, not of the exchanges' trials
    return surfels;
}

/// SizeControl::TargetCount: the level found by SearchLevel (or the parameter's, searchLevel
/// off), its clusters split or merged to the count exactly, then exchanges of clusters that lower
/// the largest error at that count. result.targetRecord receives the splits or merges when there are
/// no exchanges and the parameters ask for them, result.exchangeMaxima the exchanges' maxima.
inline std::vector<Surfel> ResampleToCount(Run &run, ResamplingResult &result)
{
    CountRecord &record = result.targetRecord;
    const bool recorded = run.param.recordCountSteps && run.param.maxErrorExchanges == 0;
    ResamplingStats &stats = run.stats;
    const int target = stats.targetCount = run.param.TargetFor(int(run.points.size()));
    Adopt(run.param.searchLevel ? SearchLevel(run, target) : ClusterAtLevel(run, run.param.subdivisionLevel), run);
    if (target > run.clusters.clusterCount) {
        Report(run.cb, 80, "Gaussian sphere resampling: refining clusters");
        ClusterRefiner refiner(run.points, run.normals, run.clusters, 1.0 / (run.weightWidth * run.weightWidth));
        stats.splitsForTarget = refiner.SplitToCount(target, [&run](double done) {
            return run.Progress(80 + int(9 * done), "Gaussian sphere resampling: splitting clusters");
        }, recorded ? &record.splits : nullptr);
        if (stats.splitsForTarget == kRefinementCancelled) throw ResamplingCancelled();
    }
    // Reads the crease narrowing from every slot of the graph: made before merging cuts it.
    const SurfelMaker maker(run.points, run.normals, run.graph, run.Recipe());
    std::vector<std::vector<int>> mergedLinks; // the merged clusters' links, for the exchanges
    const bool merged = run.clusters.clusterCount > target;
    if (merged && recorded) {
        record.levelRepresentative.assign(result.representative.size(), -1);
        for (size_t i = 0; i < run.points.size(); ++i) record.levelRepresentative[run.source[i]] = run.clusters.label[i];
        for (const auto &c : run.coincident) record.levelRepresentative[c.first] = run.clusters.label[c.second];
    }
    if (merged) mergedLinks = MergeClustersToCount(run, target, recorded ? &record.merges : nullptr);
    return SurfelsAtCount(run, maker, merged ? &mergedLinks : nullptr, result);
}

/// Spreading evenly (ResamplingParams::spreadEvenly): as many surfels as the size control gives
/// (the count of the level's clusters, or the target), grown from single points by merging the
/// cheapest neighbouring pairs by MergeSpread::Extent, then exchanged for the largest error as at a
/// target. The level's clustering still restricts the graph to its cone and marks the creases;
/// clusters at creases or on a boundary are not fitted.
inline std::vector<Surfel> ResampleEvenly(Run &run, ResamplingResult &result)
{
    ResamplingStats &stats = run.stats;
    Adopt(ClusterAtLevel(run, run.param.subdivisionLevel), run);
    Clustering &clusters = run.clusters;
    const int target = stats.targetCount = run.param.SizeMode() == SizeControl::Level
                                               ? clusters.clusterCount
                                               : run.param.TargetFor(int(run.points.size()));
    clusters.clusterCount = 0;
    for (int &label : clusters.label)
        if (label >= 0) label = clusters.clusterCount++;
    // Clusters in the band along the rim of an open surface stay unfitted, as those at creases
    // do (boundary_points.h); read from every slot of the graph, before the merge cuts it.
    SurfelRecipe recipe = run.Recipe();
    FlatVector<char> boundary, pinned;
    if (recipe.fitOffsets) {
        boundary = BoundaryBand(run.graph, run.graph.boundary);
        stats.boundaryPoints = int(std::count(boundary.begin(), boundary.end(), char(1)));
        pinned = boundary;
        if (recipe.pinnedPoints)
            for (size_t i = 0; i < pinned.size(); ++i) pinned[i] = char(pinned[i] | (*recipe.pinnedPoints)[i]);
        recipe.pinnedPoints = &pinned;
        recipe.boundaryPoints = &boundary;
    }
    const SurfelMaker maker(run.points, run.normals, run.graph, recipe);
    std::vector<std::vector<int>> mergedLinks;
    const bool merged = clusters.clusterCount > target;
    if (merged) mergedLinks = MergeClustersToCount(run, target, nullptr);
    return SurfelsAtCount(run, maker, merged ? &mergedLinks : nullptr, result);
}
/// SizeControl::ErrorBound: the clusters of the parameter's level split until every point lies
/// within the bound of its own surfel's plane, then of the surfels' blended surface, whose last
/// round makes the surfels (narrowed around creases and fitted in every round, so that the bound
/// holds for the surfels returned).
inline std::vector<Surfel> ResampleToErrorBound(Run &run)
{
    ResamplingStats &stats = run.stats;
    Adopt(ClusterAtLevel(run, run.param.subdivisionLevel), run);
    Report(run.cb, 80, "Gaussian sphere resampling: refining clusters");
    ClusterRefiner refiner(run.points, run.normals, run.clusters, 1.0 / (run.weightWidth * run.weightWidth));
    const double bound = run.param.maxErrorFraction * run.diagonal;
    stats.splitsForErrorBound = refiner.SplitToErrorBound(bound);
    SurfaceErrorBoundResult surface = SplitToSurfaceErrorBound(
        run.points, run.normals, run.graph.spacing, run.Generation(), bound, run.diagonal, kSurfaceBoundRounds, refiner,
        run.clusters,
        [&run](int round, double) {
            return run.Progress(std::min(89, 80 + round), "Gaussian sphere resampling: error bound on the surface");
        },
        [&](std::vector<Surfel> &surfels) {
            stats.surfelsNarrowedAtCreases =
                NarrowBlendsAroundCreases(run.graph, run.clusters, run.param.tuning.creaseBlendScale, surfels);
            if (run.param.fitOffsets)
                FitSurfelOffsets(run.points, run.normals, run.graph, run.clusters, run.normalization.creasePoints,
                                 surfels, bound);
        });
    if (surface.cancelled) throw ResamplingCancelled();
    stats.splitsForSurfaceBound = surface.splits;
    stats.narrowingsForSurfaceBound = surface.narrowings;
    stats.surfaceBoundRounds = surface.rounds;
    stats.pointsAboveErrorBound = surface.pointsAbove;
    stats.surfaceErrorMax = run.diagonal > 0 ? surface.maxDistance / run.diagonal : 0.0;
    stats.secondsRefinement = run.timer.Lap();
    Report(run.cb, 90, "Gaussian sphere resampling: surfels");
    return std::move(surface.surfels);
}

/// The figures read off the final surfels and clusters, and the surfels back at the model's scale.
inline void Finish(Run &run, ResamplingResult &result)
{
    ResamplingStats &stats = run.stats;
    const int n = int(run.points.size());
    for (const Surfel &s : result.surfels) {
        stats.surfelsFitted += s.fitOffset != 0;
        if (run.diagonal > 0)
            stats.largestFitMove = std::max(stats.largestFitMove, std::abs(double(s.fitOffset)) / run.diagonal);
    }
    FlatVector<double> normalError(n);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
        result.representative[run.source[i]] = run.clusters.label[i];
        normalError[i] = (run.normals[i] - result.surfels[run.clusters.label[i]].normal).Norm();
    }
    for (const auto &c : run.coincident) {
        const int label = run.clusters.label[c.second];
        result.representative[c.first] = label;
        ++result.surfels[label].memberCount;
    }
    double sumSquares = 0; // summed in point order: the same figure for any thread count
    for (double e : normalError) {
        sumSquares += e * e;
        stats.normalErrorMax = std::max(stats.normalErrorMax, e);
    }
    stats.normalErrorRms = std::sqrt(sumSquares / n);
    if (!ScaleSurfels(1.0 / run.scale, result.surfels)) throw std::overflow_error(OverflowMessage(stats.diagonal, stats.farthestCoordinate));
    stats.outputCount = int(result.surfels.size());
    stats.secondsSurfels = run.timer.Lap();
}

} // namespace detail

/// Resamples the oriented point set `mesh` (vertices with normals; faces are ignored).
/// Preconditions: param.Validate() is empty. Vertices whose normal is zero or not finite,
/// or whose position is not finite, are skipped and counted (stats.skippedPositions,
/// stats.skippedNormals). The run works at a unit scale (usable_points.h): a model scaled by a
/// power of two gives the same surfels scaled by it, and any scale the same count. The number
/// of OpenMP threads is the caller's (the output is the same for any).
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
    if (!param.anchorKeys.empty() && param.anchorKeys.size() != mesh.vert.size())
        throw std::invalid_argument("anchorKeys must hold one key per vertex");
    ResamplingResult result;
    result.stats.sizeMode = param.SizeMode();
    result.stats.threadsUsed = omp_get_max_threads();
    result.representative.assign(mesh.vert.size(), -1);
    detail::Run run(param, cb, result.stats);
    detail::Report(cb, 0, "Gaussian sphere resampling: reading points");
    detail::ReadPoints(mesh, run);
    detail::FindNeighbors(run);
    detail::Report(cb, 45, "Gaussian sphere resampling: clustering");
    if (param.spreadEvenly) {
        result.surfels = detail::ResampleEvenly(run, result);
    } else {
        switch (result.stats.sizeMode) {
        case SizeControl::Level: result.surfels = detail::ResampleAtLevel(run); break;
        case SizeControl::TargetCount: result.surfels = detail::ResampleToCount(run, result); break;
        case SizeControl::ErrorBound: result.surfels = detail::ResampleToErrorBound(run); break;
        }
    }
    detail::Finish(run, result);
    detail::Report(cb, 100, "Gaussian sphere resampling: done");
    return result;
}

} // namespace gaussphere
} // namespace vcg

#endif
