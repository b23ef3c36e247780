// Beyond the paper: clusters with a stray member beside a crease are split.
//
// The surface a set of surfels defines blends, at each point, the surfels whose centres are
// nearest to it (vcg_ext/surfel/blended_surface.h: 8 by default). Beside a crease the clusters
// are small (cluster_normalization.h), and a wide cluster of the flat side next to them can hold
// a point that lies nearer to the centres of many of those small clusters than to its own: its
// own surfel then weighs little or nothing in its blend, which follows surfels that do not
// represent it (maxplanck: the largest distance to the blended surface, twice the next; sharp
// sphere: the largest normal error, at a crease point whose own surfel is not among its 10
// nearest).
//
// A member is stray when at least kStrayNearerClusters other clusters of its found neighbours,
// facing its side (neighbour normal . its normal > 0), have centroids nearer to it than its own
// cluster's centroid. Only points beside a crease are tested: crease points and their
// neighbours (NeighborGraph::crease), where the cluster sizes change abruptly. One pass splits
// every cluster holding a stray member through its centroid, across its major axis, and rejoins
// the singletons this leaves. On the 16 models of bench/ at level 8 it adds 0.5-3.5 % surfels
// and lowers the largest distance and normal errors where they were stray members.
#ifndef VCG_EXT_GAUSSPHERE_STRAY_MEMBERS_H
#define VCG_EXT_GAUSSPHERE_STRAY_MEMBERS_H

#include <algorithm>
#include <vector>

#include <vcg_ext/gaussphere/clustering/cluster_normalization.h>
#include <vcg_ext/gaussphere/clustering/clustering.h>
#include <vcg_ext/gaussphere/clustering/singleton_rejoining.h>

namespace vcg {
namespace gaussphere {

/// Other clusters around a point, nearer to it than its own cluster's centroid, that make it stray.
constexpr int kStrayNearerClusters = 5;

/// Per cluster of `clusters`: 1 when it holds a stray member beside a crease (file header).
/// Nothing is flagged when graph.crease is empty (no crease angle).
/// \pre `graph` is the neighbour graph of `points` with its found slots; one label per point.
/// \post the same flags for any thread count.
inline FlatVector<char> ClustersWithStrayMembers(const PointArray &points, const PointArray &normals,
                                                 const NeighborGraph &graph, const Clustering &clusters)
{
    const int count = clusters.clusterCount, n = graph.Size();
    FlatVector<char> flagged(size_t(std::max(0, count)));
    std::fill(flagged.begin(), flagged.end(), char(0));
    if (graph.crease.empty() || count == 0) return flagged;
    const ClusterMembers members(clusters);
    std::vector<vcg::Point3d> centroid(static_cast<size_t>(count));
#pragma omp parallel for schedule(static)
    for (int c = 0; c < count; ++c) {
        vcg::Point3d sum(0, 0, 0);
        for (const int *i = members.begin(c); i != members.end(c); ++i) sum += vcg::Point3d::Construct(points[*i]);
        centroid[size_t(c)] = sum / double(std::max(1, members.Size(c)));
    }
    FlatVector<char> stray(static_cast<size_t>(n));
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
        stray[size_t(i)] = 0;
        const int own = clusters.label[i];
        if (own < 0 || members.Size(own) < 2) continue;
        const int *begin = graph.begin(i), *end = begin + graph.found[i];
        if (!graph.crease[i] && std::none_of(begin, end, [&graph](int j) { return graph.crease[j] != 0; })) continue;
        const vcg::Point3d p = vcg::Point3d::Construct(points[i]);
        const double ownDistance = (p - centroid[size_t(own)]).SquaredNorm();
        int nearer[kStrayNearerClusters];
        int found = 0;
        for (const int *q = begin; q != end && found < kStrayNearerClusters; ++q) {
            const int other = clusters.label[*q];
            if (other < 0 || other == own || normals[*q].dot(normals[i]) <= 0) continue;
            if ((p - centroid[size_t(other)]).SquaredNorm() >= ownDistance) continue;
            if (std::find(nearer, nearer + found, other) == nearer + found) nearer[found++] = other;
        }
        stray[size_t(i)] = found >= kStrayNearerClusters;
    }
    for (int i = 0; i < n; ++i)
        if (stray[size_t(i)]) flagged[size_t(clusters.label[i])] = 1;
    return flagged;
}

/// Splits the clusters with a stray member beside a crease (file header) in one pass, then
/// rejoins the singletons left (within `rejoinChord`, as RejoinSingletons) and compacts the
/// labels. Every flagged cluster is split whatever its shape and size, so `param` (that of
/// normalization) decides nothing here. Returns the clusters split.
/// \pre as ClustersWithStrayMembers. \post the same clustering for any thread count.
inline int SplitClustersWithStrayMembers(const PointArray &points, const PointArray &normals, const NeighborGraph &graph,
                                         const ClusterNormalizationParams &param, double rejoinChord,
                                         Clustering &clusters)
{
    const FlatVector<char> flagged = ClustersWithStrayMembers(points, normals, graph, clusters);
    FlatVector<char> changed;
    const int split = SplitElongatedClusters(points, param, clusters, &flagged, &changed, &flagged);
    if (split == 0) return 0;
    RejoinSingletons(normals, graph, rejoinChord, clusters, kRejoinMaxPasses, &changed);
    clusters.Compact();
    return split;
}

} // namespace gaussphere
} // namespace vcg

#endif
