// Naive sampling by index propagation (paper, section 3.2.2-3.2.3, Algorithm 1).
//
// A seed takes a new label; the label spreads along the adaptive neighbour graph to
// unlabelled points whose normal lies in the seed's Gaussian triangle and within the
// inscribed radius d_max / (2 sqrt 3) of the seed's normal. The traversal is depth first on
// an explicit stack (the paper's Algorithm 1, without recursion) and stops expanding at a
// depth limit, the paper's positional constraint on large flat regions.
//
// Reference normal. Algorithm 1 compares each candidate with the root (seed) while the
// text compares neighbouring points. Comparing with the seed bounds every member's normal
// to a disc of the inscribed radius around the seed's, which bounds the shape error; with
// the current point, labels would drift across the whole triangle.
//
// Seed order. The caller gives it; the resampler's is unrelated to position (seed_order.h), so
// that what a cluster depends on stays near it.
#ifndef VCG_EXT_GAUSSPHERE_INDEX_PROPAGATION_H
#define VCG_EXT_GAUSSPHERE_INDEX_PROPAGATION_H

#include <algorithm>
#include <atomic>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <thread>
#include <vector>

#include <omp.h>

#include <vcg/space/point3.h>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>
#include <vcg_ext/gaussphere/clustering/clustering.h>

namespace vcg {
namespace gaussphere {

struct IndexPropagationParams
{
    int maxDepth = 6;              ///< hops from the seed that may still expand; <= 0: no limit
    double inscribedRadius = 0.121;///< d_max / (2 sqrt 3), as a chord between unit normals
};

namespace detail {

/// PropagateIndices' mark of a point still to label.
constexpr int kUnlabelled = -2;

/// Marks every point not pre-marked -1 as kUnlabelled; returns the number of triangles
/// (one more than the largest index in `triangle`).
inline int ResetPropagationLabels(const IndexArray &triangle, int n, int *label)
{
    const int unlabelled = kUnlabelled;
    int triangleCount = 0;
#pragma omp parallel for schedule(static) reduction(max : triangleCount)
    for (int i = 0; i < n; ++i) {
        assert(triangle[i] >= 0);
        label[i] = label[i] == -1 ? -1 : unlabelled;
        triangleCount = std::max(triangleCount, triangle[i] + 1);
    }
    return triangleCount;
}

/// The occupied triangles, largest first (stable); `count` receives every triangle's number of
/// points to label (at level 256 the sphere has 1.3 million triangles, most of them empty).
inline std::vector<int> OccupiedTrianglesBySize(const IndexArray &triangle, const int *label, int n,
                                                int triangleCount, IndexArray &count)
{
    count.assign(size_t(triangleCount), 0);
    for (int i = 0; i < n; ++i)
        if (label[i] != -1) ++count[size_t(triangle[i])];
    std::vector<int> byCount;
    for (int t = 0; t < triangleCount; ++t)
        if (count[t] > 0) byCount.push_back(t);
    std::stable_sort(byCount.begin(), byCount.end(), [&](int a, int b) { return count[a] > count[b]; });
    return byCount;
}

/// Gives each triangle of `byCount` (largest first) to the thread of least load so far, out
/// of `team` threads: the counts' greedy balance.
inline void BalanceTriangleOwners(const std::vector<int> &byCount, const IndexArray &count, int team,
                                  IndexArray &owner)
{
    std::vector<long long> load(size_t(team), 0);
    for (int t : byCount) {
        const int least = int(std::min_element(load.begin(), load.end()) - load.begin());
        owner[t] = least;
        load[size_t(least)] += count[t];
    }
}

/// A point waiting in the propagation, `depth` hops from its seed.
struct PropagationVisit { int point; int depth; };

/// Spreads the label `position` from `seed` (already labelled) to the unlabelled points of its
/// triangle `t` that pass the normal test, up to the depth limit. `pending` is working space:
/// the stack of points to visit.
inline void GrowCluster(const PointArray &normals, const IndexArray &triangle, const NeighborGraph &graph,
                        const IndexPropagationParams &param, float maxChord2, int seed, int t, int position,
                        int *label, std::vector<PropagationVisit> &pending)
{
    const int unlabelled = kUnlabelled;
    const int othersLabel = -3; // read for a neighbour of another triangle instead of its label
    typedef PropagationVisit Visit;
    const vcg::Point3f &ref = normals[seed];
    pending.clear();
    pending.push_back({seed, 0});
    while (!pending.empty()) {
        const Visit v = pending.back();
        pending.pop_back();
        if (param.maxDepth > 0 && v.depth >= param.maxDepth) continue;
        // Without branches: every neighbour is written past the end and the end moves
        // past it only if it joins (whether one does is unpredictable: a branch mispredicts).
        // The joined are labelled after the scan (neighbours are distinct: the same
        // joins), and their neighbour lists, visited soon, fetched ahead. A neighbour of
        // another thread's triangle has its label read too, though never used: labels
        // are read and written as relaxed atomics (plain moves on x86).
        const int *q = graph.begin(v.point), *qEnd = graph.end(v.point);
        const size_t before = pending.size();
        pending.resize(before + size_t(qEnd - q));
        Visit *next = pending.data() + before;
        for (; q != qEnd; ++q) {
            const int j = *q;
            const bool sameTriangle = triangle[j] == t;
            const int *labelOfJ = sameTriangle ? label + j : &othersLabel;
            const bool joins = sameTriangle & (__atomic_load_n(labelOfJ, __ATOMIC_RELAXED) == unlabelled) &
                               ((normals[j] - ref).SquaredNorm() <= maxChord2);
            *next = {j, v.depth + 1};
            next += joins;
        }
        pending.resize(size_t(next - pending.data()));
        for (size_t e = before; e < pending.size(); ++e) {
            __atomic_store_n(label + pending[e].point, position, __ATOMIC_RELAXED);
            __builtin_prefetch(graph.begin(pending[e].point));
        }
    }
}

/// On the reporter thread, calls `report` every 20 ms until no thread is `sweeping` or the
/// caller cancelled; it yields rather than sleeps, since the others are often done within
/// microseconds.
template <class Report>
void ReportUntilSweepsEnd(bool reporter, const std::atomic<int> &sweeping, const std::atomic<bool> &cancelled,
                          Report &report)
{
    auto lastReport = std::chrono::steady_clock::now();
    while (reporter && sweeping > 0 && !cancelled) {
        std::this_thread::yield();
        const auto now = std::chrono::steady_clock::now();
        if (now - lastReport > std::chrono::milliseconds(20)) {
            lastReport = now;
            report();
        }
    }
}

/// Replaces each provisional label (its seed's position in the seed order) by the number of
/// its cluster, the clusters numbered in the order of their seeds; returns the cluster count.
template <class SeedAt>
int NumberClustersBySeed(int seedCount, SeedAt seedAt, int n, int *label)
{
    IndexArray idOfPosition(seedCount);
    int next = 0;
    for (int s = 0; s < seedCount; ++s) {
        const int l = label[seedAt(s)];
        idOfPosition[s] = next;
        next += int(l == s);
    }
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i)
        if (label[i] >= 0) label[i] = idOfPosition[label[i]];
    return next;
}

/// The positions in the seed order of the seeds each thread owns (by their triangle), in that
/// order, gathered in one parallel pass over the seed order: a thread then reads its own seeds
/// only.
template <class SeedAt>
std::vector<IndexArray> SeedPositionsByOwner(int seedCount, SeedAt seedAt, const IndexArray &triangle,
                                             const IndexArray &owner, int team)
{
    std::vector<std::uint8_t> ownerAt(static_cast<size_t>(seedCount));
#pragma omp parallel for schedule(static)
    for (int position = 0; position < seedCount; ++position)
        ownerAt[size_t(position)] = std::uint8_t(owner[triangle[seedAt(position)]]);
    std::vector<IndexArray> positions(static_cast<size_t>(team));
#pragma omp parallel for schedule(static, 1)
    for (int thread = 0; thread < team; ++thread) {
        IndexArray &mine = positions[size_t(thread)];
        for (int position = 0; position < seedCount; ++position)
            if (ownerAt[size_t(position)] == thread) mine.push_back(position);
    }
    return positions;
}

/// How many seeds ahead the sweep fetches a seed's label and neighbour row: the seed order is
/// unrelated to memory order, so each seed's data is a cache miss unless asked for early.
constexpr size_t kSeedLookahead = 16;

} // namespace detail

/// Labels every point whose `clusters.label` is not -1 (points pre-marked -1 are
/// excluded and stay -1). `triangle[i]` is the Gaussian triangle of normal i (>= 0 for every
/// point, excluded ones included); seeds are taken in `seedOrder` (a permutation of the
/// points; empty: 0, 1, ..., n-1). Postcondition: every non-excluded point has a label in [0, clusterCount); points
/// of one cluster share a triangle; labels number the clusters in the order of their seeds
/// in seedOrder.
/// `progress(fraction)` is called now and then from the calling thread (inside an OpenMP
/// region: it must not throw); when it returns false labelling stops and the function
/// returns false (the clustering is then incomplete).
///
/// Parallel, with the result of the sequential algorithm: a label only spreads to points of
/// its seed's triangle, so the triangles are independent of each other. Each thread labels
/// the triangles it owns (at most 256 threads), taking their seeds in seedOrder; the labels
/// are then numbered by the seeds' positions in seedOrder, as a sequential pass over all seeds
/// numbers them.
inline bool PropagateIndices(const PointArray &normals, const IndexArray &triangle,
                             const NeighborGraph &graph, const IndexArray &seedOrder,
                             const IndexPropagationParams &param, Clustering &clusters,
                             const std::function<bool(double)> &progress = nullptr)
{
    const int unlabelled = detail::kUnlabelled;
    const int n = int(clusters.label.size());
    int *label = clusters.label.data();
    const int triangleCount = detail::ResetPropagationLabels(triangle, n, label);

    // Each thread takes whole triangles (only the occupied ones), balanced by their counts.
    IndexArray count;
    const std::vector<int> byCount = detail::OccupiedTrianglesBySize(triangle, label, n, triangleCount, count);
    IndexArray owner(size_t(triangleCount), 0);
    const int team = std::min(256, omp_get_max_threads());
    detail::BalanceTriangleOwners(byCount, count, team, owner);

    const float maxChord2 = float(param.inscribedRadius * param.inscribedRadius);
    const int seedCount = seedOrder.empty() ? n : int(seedOrder.size());
    auto seedAt = [&seedOrder](int position) { return seedOrder.empty() ? position : seedOrder[position]; };
    const std::vector<IndexArray> positionsOf = detail::SeedPositionsByOwner(seedCount, seedAt, triangle, owner, team);
    const int reportEvery = std::max(1, seedCount / 50);
    std::atomic<bool> cancelled(false);
    std::atomic<long long> swept(0); // seeds passed, summed over the threads
    std::atomic<int> sweeping(team); // threads not done yet
#pragma omp parallel num_threads(team)
    {
        // Only the calling thread (OpenMP's master) talks to the caller's callback.
        const int self = omp_get_thread_num();
        const bool reporter = self == 0;
        auto report = [&]() {
            if (progress && !progress(double(swept) / std::max(1, seedCount))) cancelled = true;
        };
        // A team smaller than asked for (nested regions) leaves the missing threads' seeds here.
        for (int thread = self; thread < team; thread += omp_get_num_threads()) {
            const IndexArray &mine = positionsOf[size_t(thread)];
            std::vector<detail::PropagationVisit> pending; // cleared when a seed's cluster is complete
            for (size_t i = 0; i < mine.size(); ++i) {
                if (i % size_t(reportEvery) == 0) {
                    if (i > 0) swept += reportEvery;
                    if (reporter) report();
                    if (cancelled.load(std::memory_order_relaxed)) break;
                }
                if (i + detail::kSeedLookahead < mine.size()) {
                    const int ahead = seedAt(mine[i + detail::kSeedLookahead]);
                    __builtin_prefetch(label + ahead);
                    __builtin_prefetch(graph.begin(ahead));
                }
                const int position = mine[i];
                const int seed = seedAt(position);
                if (label[seed] != unlabelled) continue;
                // Provisional label: the seed's position, unique per cluster; numbered below.
                __atomic_store_n(label + seed, position, __ATOMIC_RELAXED);
                detail::GrowCluster(normals, triangle, graph, param, maxChord2, seed, triangle[seed], position, label,
                                    pending);
            }
            --sweeping;
        }
        // The reporter keeps reporting (and listening for a cancel) until every thread is done.
        detail::ReportUntilSweepsEnd(reporter, sweeping, cancelled, report);
    }
    if (cancelled) return false;

    // Number the clusters by their seeds' positions in seedOrder.
    clusters.clusterCount = detail::NumberClustersBySeed(seedCount, seedAt, n, label);
    return true;
}

} // namespace gaussphere
} // namespace vcg

#endif
