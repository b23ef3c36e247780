// Cluster normalization (paper, section 3.4): a cluster whose positions are elongated,
// lambda1 / lambda2 > threshold for the two largest eigenvalues of their covariance,
// is split in two by the plane through its centroid perpendicular to the major axis.
//
// Clusters smaller than `minSplitSize` are left alone: the covariance of two to five
// points is dominated by sampling noise, and splitting them mostly makes singletons
// that rejoining merges back, inflating the count without improving the shape.
// Clusters larger than `maxClusterSize` are split along their major axis whatever their
// shape, so that flat regions keep surfels of bounded size.
// Clusters holding a crease point (crease_points.h) get tighter limits of their own,
// `creaseClusterSize` and `creaseMinSplitSize` (used where smaller than the general ones):
// beside a crease a wide surfel rounds the edge off, and an elongated one lying along the
// edge reaches far across it.
#ifndef VCG_EXT_GAUSSPHERE_CLUSTER_NORMALIZATION_H
#define VCG_EXT_GAUSSPHERE_CLUSTER_NORMALIZATION_H

#include <algorithm>
#include <atomic>
#include <vector>

#include <vcg/space/point3.h>

#include <vcg_ext/gaussphere/clustering/clustering.h>
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

/// One splitting pass over all clusters. Returns the number of clusters split.
/// Deterministic: new labels are numbered in the order of the clusters they come from.
inline int SplitElongatedClusters(const PointArray &points, const ClusterNormalizationParams &param,
                                  Clustering &clusters)
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
        const int size = members.Size(c);
        const bool atCrease = param.creasePoints && members.AnyFlagged(c, *param.creasePoints);
        // At a crease the limits only tighten: the smaller cap, the smaller never-split size.
        int maxSize = param.maxClusterSize, minSplit = param.minSplitSize;
        if (atCrease) {
            if (param.creaseClusterSize > 0)
                maxSize = maxSize > 0 ? std::min(maxSize, param.creaseClusterSize) : param.creaseClusterSize;
            minSplit = std::min(minSplit, param.creaseMinSplitSize);
        }
        if (size < std::max(2, minSplit)) continue;
        const bool tooLarge = maxSize > 0 && size > maxSize;
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
    }
    return split;
}

} // namespace gaussphere
} // namespace vcg

#endif
