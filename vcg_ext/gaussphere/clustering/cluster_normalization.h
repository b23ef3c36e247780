// Cluster normalization (paper, section 3.4): a cluster whose positions are elongated,
// lambda1 / lambda2 > threshold for the two largest eigenvalues of their covariance,
// is split in two by the plane through its centroid perpendicular to the major axis.
//
// Clusters smaller than `minSplitSize` are left alone: the covariance of two to five
// points is dominated by sampling noise, and splitting them mostly makes singletons
// that rejoining merges back, inflating the count without improving the shape.
// Clusters larger than `maxClusterSize` are split along their major axis whatever their
// shape and size, so that flat regions keep surfels of bounded size (a cap below
// `minSplitSize` holds too).
// Clusters holding a crease point (crease_points.h) get tighter limits of their own,
// `creaseClusterSize` and `creaseMinSplitSize` (used where smaller than the general ones):
// beside a crease a wide surfel rounds the edge off, and an elongated one lying along the
// edge reaches far across it.
//
// As in the paper, normalization and rejoining repeat until the clusters meet the criterion: a
// round splits nothing. The rounds stop at maxRounds too (the resampler's 6: on its benchmark
// models the count no longer changes after that, and the later rounds only split clusters whose
// lone split-off point rejoins them).
#ifndef VCG_EXT_GAUSSPHERE_CLUSTER_NORMALIZATION_H
#define VCG_EXT_GAUSSPHERE_CLUSTER_NORMALIZATION_H

#include <algorithm>
#include <atomic>
#include <vector>

#include <vcg/space/point3.h>

#include <vcg_ext/gaussphere/clustering/clustering.h>
#include <vcg_ext/gaussphere/clustering/singleton_rejoining.h>
#include <vcg_ext/gaussphere/support/flat_vector.h>
#include <vcg_ext/gaussphere/clustering/principal_axes.h>

namespace vcg {
namespace gaussphere {

struct ClusterNormalizationParams
{
    double threshold = 6.0;  ///< split when lambda1 / lambda2 exceeds it (the paper's 6.0)
    int minSplitSize = 6;    ///< clusters with fewer points are never split
    int maxClusterSize = 0;  ///< clusters with more points are split whatever their shape (0 = off)
    /// Per point: at a crease (NeighborGraph::crease); null: no crease limits.
    const FlatVector<char> *creasePoints = nullptr;
    int creaseClusterSize = 5;   ///< maxClusterSize of clusters holding a crease point (0 = off)
    int creaseMinSplitSize = 4;  ///< minSplitSize of clusters holding a crease point
};

/// One splitting pass over the clusters flagged in `examine` (every cluster when null; a
/// cluster's decision depends on its members alone, so one unchanged since it was last
/// examined need not be examined again); those flagged in `forced` (null: none) are split
/// whatever their shape and size. Returns the number of clusters split; `changed`, if
/// given, becomes a flag per cluster of the new count: the clusters split and those made of
/// their halves. Deterministic: new labels are numbered in the order of the clusters they come
/// from.
inline int SplitElongatedClusters(const PointArray &points, const ClusterNormalizationParams &param,
                                  Clustering &clusters, const FlatVector<char> *examine = nullptr,
                                  FlatVector<char> *changed = nullptr, const FlatVector<char> *forced = nullptr)
{
    const ClusterMembers members(clusters);
    const int count = clusters.clusterCount;
    // The splitting planes of the clusters to split, filled from the front of a buffer as found:
    // not a plane per cluster (48 B each, a tenth of the memory at the level search's peak); only
    // the pages of the planes found are touched.
    struct SplitPlane { Eigen::Vector3d centroid, majorAxis; };
    FlatVector<SplitPlane> planes(size_t(std::max(0, count)));
    IndexArray planeOf(size_t(std::max(0, count))); // -1: kept whole
    std::atomic<int> planesFound(0);
#pragma omp parallel for schedule(dynamic, 256)
    for (int c = 0; c < count; ++c) {
        planeOf[c] = -1;
        if (examine && !(*examine)[size_t(c)]) continue;
        const int size = members.Size(c);
        const bool atCrease = param.creasePoints && members.AnyFlagged(c, *param.creasePoints);
        // At a crease the limits only tighten: the smaller cap, the smaller never-split size.
        int maxSize = param.maxClusterSize, minSplit = param.minSplitSize;
        if (atCrease) {
            if (param.creaseClusterSize > 0)
                maxSize = maxSize > 0 ? std::min(maxSize, param.creaseClusterSize) : param.creaseClusterSize;
            minSplit = std::min(minSplit, param.creaseMinSplitSize);
        }
        const bool tooLarge = (maxSize > 0 && size > maxSize) || (forced && (*forced)[size_t(c)]);
        if (size < std::max(2, minSplit) && !tooLarge) continue;
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (const int *i = members.begin(c); i != members.end(c); ++i)
            mean += Eigen::Vector3d(points[*i][0], points[*i][1], points[*i][2]);
        mean /= size;
        CovarianceAccumulator cov;
        for (const int *i = members.begin(c); i != members.end(c); ++i)
            cov.Add(Eigen::Vector3d(points[*i][0], points[*i][1], points[*i][2]) - mean);
        const PrincipalAxes pa = ComputePrincipalAxes(cov.Covariance());
        if (!(pa.value[0] > 0) || (!tooLarge && pa.value[0] <= param.threshold * pa.value[1])) continue;
        const int slot = planesFound++;
        planes[size_t(slot)] = {mean, pa.axis.col(0)};
        planeOf[c] = slot;
    }
    int split = 0;
    for (int c = 0; c < count; ++c) {
        if (planeOf[c] < 0) continue;
        const SplitPlane &plane = planes[size_t(planeOf[c])];
        const int newLabel = clusters.clusterCount;
        int moved = 0;
        for (const int *i = members.begin(c); i != members.end(c); ++i) {
            const Eigen::Vector3d d = Eigen::Vector3d(points[*i][0], points[*i][1], points[*i][2]) - plane.centroid;
            if (d.dot(plane.majorAxis) > 0) { clusters.label[*i] = newLabel; ++moved; }
        }
        if (moved == 0) continue; // every point on the plane: nothing to split
        ++clusters.clusterCount;
        ++split;
        planeOf[c] = -2; // split
    }
    if (changed) {
        changed->assign(size_t(clusters.clusterCount), 0);
        for (int c = 0; c < count; ++c) (*changed)[size_t(c)] = planeOf[c] == -2;
        std::fill(changed->begin() + count, changed->end(), char(1));
    }
    return split;
}

/// Step 3: rounds of a splitting pass and singleton rejoining (within `rejoinChord`, as
/// RejoinSingletons), until a round splits nothing or `maxRounds` rounds ran; step() is called
/// after each pass. After the first round only the clusters the last one changed are examined
/// again: the same result as examining all of them. The stopping rule looks at no count of the
/// whole input, so a part of an input is normalized alike whatever else the input holds.
/// Precondition: the singletons of `clusters` found no cluster in a last rejoining (as after
/// naive sampling). Returns the rounds that split a cluster.
template <class Step>
int NormalizeClusters(const PointArray &points, const PointArray &normals, const NeighborGraph &graph,
                      const ClusterNormalizationParams &param, double rejoinChord, int maxRounds, Clustering &clusters,
                      const Step &step)
{
    FlatVector<char> examine, changed;
    int rounds = 0;
    for (; rounds < maxRounds; ++rounds) {
        const int split = SplitElongatedClusters(points, param, clusters, rounds == 0 ? nullptr : &examine, &changed);
        step();
        if (split == 0) break;
        RejoinSingletons(normals, graph, rejoinChord, clusters, kRejoinMaxPasses, &changed);
        step();
        const IndexArray renumbered = clusters.Compact();
        examine.assign(size_t(clusters.clusterCount), 0);
        for (size_t old = 0; old < renumbered.size(); ++old)
            if (renumbered[old] >= 0 && changed[old]) examine[size_t(renumbered[old])] = 1;
    }
    return rounds;
}

} // namespace gaussphere
} // namespace vcg

#endif
