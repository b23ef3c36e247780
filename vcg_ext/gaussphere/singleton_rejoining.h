// Singleton rejoining (paper, section 3.3): a one-point cluster joins the neighbouring
// cluster whose normal is closest to its own (least 1 - <n, n_cluster>).
//
// A cluster's normal is the normalized mean of its members' normals. A singleton only
// joins a cluster whose normal lies within maxChord of its own (the resampler passes the
// propagation radius, so a rejoined point is no farther from its cluster's normal than a
// propagated one), so rejoining never drags a cluster's normal along a chain of points. Passes repeat until no singleton moves: a singleton
// whose neighbours were all singletons may find a cluster once they have joined one.
// Within a pass all decisions are taken against the clustering as it was before the
// pass, so the result does not depend on the processing order or the thread count; a
// singleton only joins clusters of two or more points, so two singletons never swap
// into each other. A singleton with no such cluster around stays a cluster of its own.
#ifndef VCG_EXT_GAUSSPHERE_SINGLETON_REJOINING_H
#define VCG_EXT_GAUSSPHERE_SINGLETON_REJOINING_H

#include <vector>

#include <vcg/space/point3.h>

#include "adaptive_neighbors.h"
#include "clustering.h"

namespace vcg {
namespace gaussphere {

/// One pass; returns the number of singletons that joined a neighbouring cluster.
inline int RejoinSingletonsOnce(const PointArray &normals, const NeighborGraph &graph,
                                double maxChord, Clustering &clusters)
{
    const float maxScore = float(0.5 * maxChord * maxChord); // 1 - cos for that chord
    const int n = int(clusters.label.size());
    IndexArray size(clusters.clusterCount, 0);
    PointArray normalSum(clusters.clusterCount, vcg::Point3f(0, 0, 0));
    for (int i = 0; i < n; ++i) {
        const int l = clusters.label[i];
        if (l < 0) continue;
        ++size[l];
        normalSum[l] += normals[i];
    }
    IndexArray target(n);
#pragma omp parallel for schedule(dynamic, 4096)
    for (int i = 0; i < n; ++i) {
        target[i] = -1;
        const int own = clusters.label[i];
        if (own < 0 || size[own] != 1) continue;
        float bestScore = maxScore;
        for (const int *q = graph.begin(i); q != graph.end(i); ++q) {
            const int l = clusters.label[*q];
            if (l < 0 || l == own || size[l] < 2) continue;
            const float norm = normalSum[l].Norm();
            const float score = norm > 0 ? 1.f - normals[i].dot(normalSum[l]) / norm : 2.f;
            if (score < bestScore || (score == bestScore && (target[i] < 0 || l < target[i]))) {
                bestScore = score;
                target[i] = l;
            }
        }
    }
    int joined = 0;
    for (int i = 0; i < n; ++i)
        if (target[i] >= 0) { clusters.label[i] = target[i]; ++joined; }
    return joined;
}

/// Repeats passes until no singleton moves (at most maxPasses). Returns the number joined.
/// Postcondition: clusters may contain empty labels; call Compact() when needed.
inline int RejoinSingletons(const PointArray &normals, const NeighborGraph &graph,
                            double maxChord, Clustering &clusters, int maxPasses = 32)
{
    int joined = 0;
    for (int pass = 0; pass < maxPasses; ++pass) {
        const int moved = RejoinSingletonsOnce(normals, graph, maxChord, clusters);
        if (moved == 0) break;
        joined += moved;
    }
    return joined;
}

} // namespace gaussphere
} // namespace vcg

#endif
