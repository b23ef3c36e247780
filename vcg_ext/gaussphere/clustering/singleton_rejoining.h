// Singleton rejoining (paper, section 3.3): a one-point cluster joins the neighbouring
// cluster whose normal is closest to its own (least 1 - <n, n_cluster>).
//
// A cluster's normal is the normalized mean of its members' normals. A singleton only
// joins a cluster whose normal lies within maxChord of its own (the resampler passes the
// propagation radius, so a rejoined point is no farther from its cluster's normal than a
// propagated one), so rejoining never drags a cluster's normal along a chain of points.
// Passes repeat until no singleton moves: a singleton whose neighbours were all singletons
// may find a cluster once they have joined one.
// Within a pass all decisions are taken against the clustering as it stands at the start
// of the pass, so the result does not depend on the processing order or the thread count; a
// singleton only joins clusters of two or more points, so two singletons never swap
// into each other. A singleton with no such cluster around stays a cluster of its own.
#ifndef VCG_EXT_GAUSSPHERE_SINGLETON_REJOINING_H
#define VCG_EXT_GAUSSPHERE_SINGLETON_REJOINING_H

#include <algorithm>
#include <utility>
#include <vector>

#include <vcg/space/point3.h>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>
#include <vcg_ext/gaussphere/clustering/clustering.h>

namespace vcg {
namespace gaussphere {

/// Up to this many singletons (or clusters to re-sum) a pass runs on the calling thread alone:
/// below it, starting the threads costs more than they save. (The few thousand singletons a
/// normalization round leaves on the igea take a fraction of a millisecond a pass.)
constexpr size_t kRejoinParallelMin = 512;
/// How many singletons ahead a pass fetches the next one's data.
constexpr int kRejoinPrefetchAhead = 8;
/// Passes of rejoining at most: a pass only moves singletons next to a cluster that changed in
/// the one before, so passes stop long before this on real inputs.
constexpr int kRejoinMaxPasses = 32;

namespace detail {

/// Each cluster's size and the sum of its members' normals, in point order.
inline void SumClusterNormals(const PointArray &normals, const ClusterMembers &before, int count,
                              IndexArray &size, PointArray &normalSum)
{
#pragma omp parallel for schedule(static)
    for (int c = 0; c < count; ++c) {
        size[c] = before.Size(c);
        vcg::Point3f sum(0, 0, 0);
        for (const int *m = before.begin(c); m != before.end(c); ++m) sum += normals[*m]; // in point order
        normalSum[c] = sum;
    }
}

/// One pass's decisions: target[s] is the cluster singletons[s] joins, -1 for none, taken
/// against the clustering as it stands at the start of the pass. With `onlyNearChanges`, a
/// singleton is looked at only when its own cluster or a neighbour's is flagged `changed`: it
/// found no cluster before, and only a change can give it one.
inline void ChooseRejoinTargets(const PointArray &normals, const NeighborGraph &graph, const IndexArray &label,
                                const IndexArray &size, const PointArray &normalSum,
                                const FlatVector<char> &changed, const IndexArray &singletons,
                                bool onlyNearChanges, float maxScore, IndexArray &target)
{
    // Later passes have few singletons left, for which threads would cost more than they save.
#pragma omp parallel for schedule(dynamic, 256) if (singletons.size() > kRejoinParallelMin)
    for (int s = 0; s < int(singletons.size()); ++s) {
        const int i = singletons[s], own = label[i];
        // Singletons lie scattered: fetch a later one's neighbour list and label ahead
        // (the decisions are bound by memory latency, not arithmetic).
        if (s + kRejoinPrefetchAhead < int(singletons.size())) {
            __builtin_prefetch(graph.begin(singletons[s + kRejoinPrefetchAhead]));
            __builtin_prefetch(label.data() + singletons[s + kRejoinPrefetchAhead]);
        }
        target[s] = -1;
        const auto nextToChange = [&](int q) { return label[q] >= 0 && changed[label[q]]; };
        if (onlyNearChanges && !changed[own] && std::none_of(graph.begin(i), graph.end(i), nextToChange)) continue;
        float bestScore = maxScore;
        int best = -1;
        for (const int *q = graph.begin(i); q != graph.end(i); ++q) {
            const int l = label[*q];
            if (l < 0 || l == own || size[l] < 2) continue;
            const float norm = normalSum[l].Norm();
            const float score = norm > 0 ? 1.f - normals[i].dot(normalSum[l]) / norm : 2.f;
            if (score < bestScore || (score == bestScore && (best < 0 || l < best))) {
                bestScore = score;
                best = l;
            }
        }
        target[s] = best;
    }
}

/// Moves every singleton with a target into it: its own cluster empties, the join is appended
/// to `joins` and the target to `touched`. Keeps the singletons left, in order; returns the
/// number moved.
inline int MoveSingletons(const IndexArray &target, IndexArray &singletons, IndexArray &label, IndexArray &size,
                          PointArray &normalSum, std::vector<std::pair<int, int>> &joins,
                          std::vector<int> &touched)
{
    size_t left = 0;
    for (size_t s = 0; s < singletons.size(); ++s) {
        const int i = singletons[s], t = target[s];
        if (t < 0) { singletons[left++] = i; continue; }
        size[label[i]] = 0;
        normalSum[label[i]] = vcg::Point3f(0, 0, 0);
        label[i] = t;
        ++size[t];
        joins.push_back({t, i});
        touched.push_back(t);
    }
    const int moved = int(singletons.size() - left);
    singletons.resize(left);
    return moved;
}

/// Sums again the normals of the `touched` clusters (sorted, unique) over their members in
/// point order: those of `before` merged with the singletons in `joins` (sorted).
inline void ResumJoinedClusters(const PointArray &normals, const ClusterMembers &before,
                                const std::vector<std::pair<int, int>> &joins, const std::vector<int> &touched,
                                PointArray &normalSum)
{
#pragma omp parallel for schedule(dynamic, 256) if (touched.size() > kRejoinParallelMin)
    for (int u = 0; u < int(touched.size()); ++u) {
        const int t = touched[u];
        // Merge the members that stayed with the singletons that joined, both ascending.
        auto j = std::lower_bound(joins.begin(), joins.end(), std::make_pair(t, -1));
        const int *m = before.begin(t);
        vcg::Point3f sum(0, 0, 0);
        while (m != before.end(t) || (j != joins.end() && j->first == t)) {
            const bool takeJoin = j != joins.end() && j->first == t && (m == before.end(t) || j->second < *m);
            sum += normals[takeJoin ? (j++)->second : *m++];
        }
        normalSum[t] = sum;
    }
}

} // namespace detail

/// Repeats passes until no singleton moves (at most maxPasses). Returns the number joined.
/// `changed`, if given, holds a flag per cluster: on entry those changed since the last
/// rejoining of this clustering (whose singletons left over found no cluster then; null: every
/// singleton is new), on return also those singletons joined.
/// Postcondition: clusters may contain empty labels; call Compact() when needed.
///
/// Cost: the cluster sizes and normal sums are computed once, then only the clusters that
/// singletons joined are summed again, over their members in point order, so that each pass
/// sees exactly the sums a pass computing them afresh would (the same float additions in the
/// same order), and later passes only visit the singletons still left.
inline int RejoinSingletons(const PointArray &normals, const NeighborGraph &graph, double maxChord,
                            Clustering &clusters, int maxPasses = kRejoinMaxPasses,
                            FlatVector<char> *changedSinceLast = nullptr)
{
    const float maxScore = float(0.5 * maxChord * maxChord); // 1 - cos for that chord
    IndexArray &label = clusters.label;
    const ClusterMembers before(clusters); // members that stay put: all but the singletons
    const int count = clusters.clusterCount;
    IndexArray size(count);
    PointArray normalSum(count);
    detail::SumClusterNormals(normals, before, count, size, normalSum);
    IndexArray singletons;
    for (int c = 0; c < count; ++c)
        if (size[c] == 1) singletons.push_back(*before.begin(c));
    if (singletons.empty() || maxPasses <= 0) return 0;
    std::vector<std::pair<int, int>> joins; // (cluster, point) of every singleton that joined
    IndexArray target(singletons.size());
    std::vector<int> touched;                // clusters that singletons joined in a pass...
    FlatVector<char> changed(count, 0);      // ... flagged for the next one
    if (changedSinceLast) std::copy(changedSinceLast->begin(), changedSinceLast->end(), changed.begin());
    int joined = 0;
    for (int pass = 0; pass < maxPasses && !singletons.empty(); ++pass) {
        detail::ChooseRejoinTargets(normals, graph, label, size, normalSum, changed, singletons,
                                    pass > 0 || changedSinceLast, maxScore, target);
        if (pass == 0 && changedSinceLast) std::fill(changed.begin(), changed.end(), char(0));
        for (int t : touched) changed[t] = 0; // the previous pass's flags
        touched.clear();
        const size_t joinsBefore = joins.size();
        const int moved = detail::MoveSingletons(target, singletons, label, size, normalSum, joins, touched);
        if (moved == 0) break;
        joined += moved;
        std::sort(joins.begin() + joinsBefore, joins.end());
        std::inplace_merge(joins.begin(), joins.begin() + joinsBefore, joins.end());
        SortUnique(touched);
        for (int t : touched) changed[t] = 1;
        detail::ResumJoinedClusters(normals, before, joins, touched, normalSum);
    }
    if (changedSinceLast)
        for (const auto &join : joins) (*changedSinceLast)[size_t(join.first)] = 1;
    return joined;
}

} // namespace gaussphere
} // namespace vcg

#endif
