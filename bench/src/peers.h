// The peer methods our resampler is compared with, each with its count-matching search:
//  - CGAL hierarchy_simplify_point_set: Pauly et al. 2002's adaptive hierarchical clustering,
//    the "adaptive hierarchical clustering [3]" row of the paper's Table 2;
//  - CGAL grid_simplify_point_set: one point per occupied cell of a regular grid;
//  - MeshLab's "Point Cloud Simplification" (Poisson-disk pruning), run through meshlabserver.
// All of them output a subset of the input points; their normals are the input normals.
#ifndef GSBENCH_PEERS_H
#define GSBENCH_PEERS_H

#include <string>
#include <utility>
#include <vector>

#include <CGAL/Simple_cartesian.h>

#include "child_process.h"
#include "match_count.h"
#include "point_sets.h"

namespace gsbench {

struct HierarchyParams
{
    int maxClusterSize = 10;         ///< CGAL's `size`: clusters larger than this are split
    double maxVariation = 1.0 / 3.0; ///< CGAL's `maximum_variation` (1/3 disables it)
    std::string ToString() const;
};

/// The input positions in CGAL's format, converted once; each run works on a copy because
/// CGAL's simplification functions reorder their range.
class CgalPointSet
{
public:
    explicit CgalPointSet(const PointMesh &mesh);
    int Size() const { return int(points_.size()); }

    /// Indices (into the input) of the points kept; `seconds` receives the time of the CGAL
    /// call alone (the copy is not timed).
    std::vector<int> Hierarchy(const HierarchyParams &param, double *seconds = nullptr) const;
    std::vector<int> Grid(double cellSize, double *seconds = nullptr) const;

private:
    using Kernel = CGAL::Simple_cartesian<double>;
    using IndexedPoint = std::pair<Kernel::Point_3, int>;
    std::vector<IndexedPoint> points_;
};

struct HierarchyMatch
{
    HierarchyParams param;
    CountMatch match; ///< of the last stage
};

/// Matches the hierarchy clustering's count to `target`. The cluster size alone moves the
/// count in steps of ~1/size (15 % around size 6), too coarse for +-2 %: so first the size is
/// searched with the variation test off, then, at the size just below the target, the
/// variation threshold is lowered until enough clusters split. Both of Pauly's criteria are
/// then active, which is the adaptive method the paper compares with.
HierarchyMatch MatchHierarchy(const CgalPointSet &points, int target, double tolerance);

/// Matches by the variation threshold alone, at a fixed maximum cluster size (which must give
/// fewer points than `target` with the variation test off).
HierarchyMatch MatchHierarchyVariation(const CgalPointSet &points, int maxClusterSize, int target, double tolerance);

/// Matches the grid's cell size to `target`; `diagonal` is the input's bounding-box diagonal.
CountMatch MatchGrid(const CgalPointSet &points, double diagonal, int target, double tolerance);

/// MeshLab's Point Cloud Simplification run by meshlabserver in a fresh process per call.
/// The filter's radius is searched rather than its SampleNum: in 2020.09 SampleNum only sets
/// the radius from the bounding box's area (a point cloud has no mesh area), and the filter's
/// own ExactNumFlag search is dead code (it runs only when the radius is 0, after the radius
/// has been set). Needs DISPLAY (scripts/bench.sh runs everything under xvfb-run).
class MeshLabPoisson
{
public:
    MeshLabPoisson(std::string meshlabserver, std::string input, double diagonal, std::string workDir);

    /// Runs the filter with `radius` (absolute), saving positions and normals to `output`.
    /// Throws std::runtime_error if meshlabserver fails.
    ChildRun Run(double radius, const std::string &output) const;

    /// Searches the radius for `target` points; each evaluation is one meshlabserver run.
    CountMatch Match(int target, double tolerance) const;

private:
    std::string WriteScript(double radius) const;
    std::string meshlabserver_, input_, workDir_;
    double diagonal_;
};

} // namespace gsbench

#endif
