// Beyond the paper: refining a clustering to an exact size or to an error bound.
//
// Both refinements split one cluster at a time through its centroid, perpendicular to
// the tangent direction along which its normals vary most (the principal direction of
// the normal covariance, as for the ellipse axes; the positional major axis for a flat
// cluster). Splitting along the normal variation separates the two sides of a crease or
// ridge first, which is what keeps the result feature sensitive.
//
// - SplitToCount: splits the cluster with the largest L2,1 error, sum |n_i - n'|^2 over its
//   members (ties: the larger cluster), until the requested count is reached. Each split
//   adds exactly one cluster.
// - SplitToErrorBound: splits every cluster with a member farther than maxDistance from its
//   surfel plane (surfel centre, surfel normal) until none is; a one-point cluster lies on its
//   own plane, so this ends.
//
// Clusters are kept as ranges of one index array, partitioned in place, so a split costs
// time proportional to the cluster's size and no memory beyond the ranges.
//
// - MergeToCount: the other direction, for targets below what the coarsest Gaussian sphere
//   gives. Neighbouring clusters (linked by the k-NN graph) merge greedily, cheapest pair
//   first. The cost is what the merge adds to three squared errors: the normal error (Ward:
//   |A||B|/(|A|+|B|) |m_A - m_B|^2), and, in units of h^2, the members' squared distances to
//   the merged surfel's plane (through the centroid, along the mean normal) and, weighted
//   less, their spread around the centroid (Ward: |A||B|/(|A|+|B|) |c_A - c_B|^2). Flat,
//   coplanar neighbours merge first; a merge across a bend pays for the height it adds.
//   MergeSpread::Extent replaces the Ward spread by the merged cluster's mean squared distance
//   to its centroid: that term does not grow with the members' number, so clusters grow to one
//   extent wherever the input is dense or sparse, and surfels merged from single points spread
//   evenly over flat parts (the output meant for surface reconstruction: ResampleEvenly, resampling.h).
#ifndef VCG_EXT_GAUSSPHERE_CLUSTER_REFINEMENT_H
#define VCG_EXT_GAUSSPHERE_CLUSTER_REFINEMENT_H

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <memory>
#include <queue>
#include <utility>
#include <vector>

#include <omp.h>

#include <vcg/space/point3.h>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>
#include <vcg_ext/gaussphere/clustering/clustering.h>
#include <vcg_ext/gaussphere/surfels/surfel_generation.h>

namespace vcg {
namespace gaussphere {

/// Partitions the members [first, last) of one cluster in two through their centroid, across
/// the tangent direction along which their normals vary most (file header). Returns where the
/// second part starts, or null if every member projects to the same side along each candidate
/// direction (u, v, then the normal): coincident points.
inline int *SplitMembers(const PointArray &points, const PointArray &normals, int *first, int *last, double invH2)
{
    const ClusterFrame f = ComputeClusterFrame(points, normals, first, last, invH2);
    for (const Eigen::Vector3d &dir : {f.u, f.v, f.normal}) {
        int *mid = std::partition(first, last, [&](int i) {
            return (detail::ToEigen(points[i]) - f.centroid).dot(dir) <= 0;
        });
        if (mid != first && mid != last) return mid;
    }
    return nullptr;
}

/// What SplitToCount and MergeToCount return when their `progress` stopped them.
constexpr int kRefinementCancelled = -1;

/// One split of SplitToCount, in the order made: the cluster split, the cluster it added, and the
/// split's priority (the L2,1 error of the cluster split, then its size). Each part's error is at
/// most the error of the cluster it came from, so the priorities fall along the sequence, up to
/// the rounding of errors computed from float normals (a part's can exceed its cluster's by that).
struct CountSplit
{
    int cluster = 0, added = 0;
    double error = 0;
    int size = 0;
};

/// One merge of MergeToCount, in the order made: the two clusters merged, as numbered before
/// merging (the one whose number the merged cluster carries on first; each a cluster no merge has
/// taken away yet), and the merge's cost (MergeCostModel). Costs mostly rise along the sequence; a
/// merged cluster's pairs can cost less than a merge made before.
struct CountMerge
{
    int kept = 0, gone = 0;
    double cost = 0;
};

class ClusterRefiner
{
public:
    /// invH2 = 1/h^2 of the surfel normal weights (SurfelGenerationParams::weightWidth).
    ClusterRefiner(const PointArray &points, const PointArray &normals,
                   Clustering &clusters, double invH2)
        : points_(points), normals_(normals), clusters_(clusters), invH2_(invH2)
    {
        const ClusterMembers members(clusters);
        index_ = members.index;
        for (int c = 0; c < clusters.clusterCount; ++c) range_.push_back({members.offset[c], members.offset[c + 1]});
    }

    int Count() const { return int(range_.size()); }

    /// Splits the clusters with the largest L2,1 error until there are `target` clusters
    /// (or no cluster can be split). Returns the number of splits; `record`, if given, receives
    /// them in order. `progress(fraction)`, if given, is called every few thousand splits; when it
    /// returns false splitting stops (the splits made so far stay) and SplitToCount returns
    /// kRefinementCancelled.
    int SplitToCount(int target, const std::function<bool(double)> &progress = nullptr,
                     std::vector<CountSplit> *record = nullptr)
    {
        typedef std::pair<std::pair<double, int>, int> Entry; // ((error, size), cluster)
        std::priority_queue<Entry> queue;
        auto push = [&](int c) {
            if (Size(c) > 1) queue.push({{NormalError(c), Size(c)}, c});
        };
        for (int c = 0; c < Count(); ++c) push(c);
        int splits = 0;
        const int needed = std::max(1, target - Count());
        int nextReport = 0;
        while (Count() < target && !queue.empty()) {
            if (progress && splits >= nextReport) {
                if (!progress(double(splits) / needed)) return kRefinementCancelled;
                nextReport = splits + 4096;
            }
            const Entry top = queue.top();
            queue.pop();
            const int c = top.second;
            const int added = Split(c);
            if (added < 0) continue;
            if (record) record->push_back({c, added, top.first.first, top.first.second});
            ++splits;
            push(c);
            push(added);
        }
        return splits;
    }

    /// Splits until every member lies within maxDistance of its cluster's surfel plane.
    /// Returns the number of splits.
    int SplitToErrorBound(double maxDistance)
    {
        std::vector<int> pending;
        for (int c = 0; c < Count(); ++c) pending.push_back(c);
        int splits = 0;
        while (!pending.empty()) {
            const int c = pending.back();
            pending.pop_back();
            if (Size(c) < 2 || PlaneDistance(c) <= maxDistance) continue;
            const int added = Split(c);
            if (added < 0) continue; // coincident points: nothing to separate
            ++splits;
            pending.push_back(c);
            pending.push_back(added);
        }
        return splits;
    }

    int Size(int c) const { return range_[c].second - range_[c].first; }

    /// Splits cluster c in two (SplitMembers); returns the new cluster's index, or -1 if it
    /// cannot be split.
    int Split(int c)
    {
        int *first = index_.data() + range_[c].first, *last = index_.data() + range_[c].second;
        int *mid = SplitMembers(points_, normals_, first, last, invH2_);
        if (!mid) return -1;
        const int added = Count();
        const int split = int(mid - index_.data());
        range_.push_back({split, range_[c].second});
        range_[c].second = split;
        for (const int *i = Begin(added); i != End(added); ++i) clusters_.label[*i] = added;
        clusters_.clusterCount = Count();
        return added;
    }

private:
    const int *Begin(int c) const { return index_.data() + range_[c].first; }
    const int *End(int c) const { return index_.data() + range_[c].second; }

    double NormalError(int c) const
    {
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (const int *i = Begin(c); i != End(c); ++i) mean += detail::ToEigen(normals_[*i]);
        mean /= Size(c);
        // sum |n_i - mean|^2 = sum |n_i|^2 - size |mean|^2 for the unconstrained minimizer.
        return std::max(0.0, Size(c) * (1.0 - mean.squaredNorm()));
    }

    double PlaneDistance(int c) const
    {
        const ClusterFrame f = ComputeClusterFrame(points_, normals_, Begin(c), End(c), invH2_);
        double worst = 0;
        for (const int *i = Begin(c); i != End(c); ++i)
            worst = std::max(worst, std::abs((detail::ToEigen(points_[*i]) - f.center).dot(f.normal)));
        return worst;
    }

    const PointArray &points_, &normals_;
    Clustering &clusters_;
    double invH2_;
    IndexArray index_;
    std::vector<std::pair<int, int>> range_;
};

/// Weights of MergeToCount's positional terms against its normal term: the height above the
/// merged plane weighs most, so that a merge across a bend pays for the edge it rounds, and the
/// spread a little, so that merged surfels stay compact. Tuned with bench/ at 5 % and 10 % of its
/// models, where most clusters come from merging.
constexpr double kMergePlaneWeight = 16.0;
constexpr double kMergeSpreadWeight = 0.1;

/// The spread term of MergeToCount's cost (file header).
enum class MergeSpread
{
    Ward,  ///< what the merge adds to the spread, weighted by kMergeSpreadWeight
    Extent ///< the merged cluster's mean squared distance to its centroid, weighted 1
};

/// The upper triangle of a symmetric 3x3 matrix, row by row: (0,0) (0,1) (0,2) (1,1) (1,2) (2,2).
/// At namespace scope, not in MergeCostModel: indexing odr-uses the arrays, and C++14 has no
/// inline variables to define a class member in a header.
constexpr int kMomentRow[6] = {0, 0, 0, 1, 1, 2}, kMomentColumn[6] = {0, 1, 2, 1, 2, 2};

/// The cost of merging two clusters (file header), from per-cluster sums that give a merged
/// cluster's errors in O(1). Positions are taken relative to the centroid of all points, which
/// keeps the second moments of a model far from the origin from losing the clusters' spread to
/// cancellation.
class MergeCostModel
{
public:
    /// \pre clusters' labels in [-1, clusterCount), `members` = ClusterMembers(clusters);
    ///      weightWidth = h of the surfel normal weights.
    MergeCostModel(const PointArray &points, const PointArray &normals, const Clustering &clusters,
                   const ClusterMembers &members, double weightWidth, MergeSpread spread = MergeSpread::Ward)
        : sums_(clusters.clusterCount), invH2_(1.0 / (weightWidth * weightWidth)), spread_(spread)
    {
        Eigen::Vector3d origin = Eigen::Vector3d::Zero();
        double clustered = 0;
        for (size_t i = 0; i < clusters.label.size(); ++i)
            if (clusters.label[i] >= 0) { origin += detail::ToEigen(points[i]); ++clustered; }
        origin /= std::max(1.0, clustered);
        // Each cluster's sums over its members in point order, whatever the thread count.
#pragma omp parallel for schedule(dynamic, 1024)
        for (int c = 0; c < clusters.clusterCount; ++c) {
            Sums &s = sums_[size_t(c)];
            for (const int *i = members.begin(c); i != members.end(c); ++i) {
                const Eigen::Vector3d p = detail::ToEigen(points[*i]) - origin;
                s.size += 1;
                s.normalSum += detail::ToEigen(normals[*i]);
                s.positionSum += p;
                for (int e = 0; e < 6; ++e) s.moment[e] += p[kMomentRow[e]] * p[kMomentColumn[e]];
            }
        }
    }

    /// What merging clusters a and b adds to the weighted squared errors.
    double Cost(int a, int b) const
    {
        const Sums &A = sums_[a], &B = sums_[b];
        Sums merged = A;
        merged.Add(B);
        const double ward = A.size * B.size / (A.size + B.size);
        // May be negative: each part's error is taken along its own mean normal, its surfel's,
        // and a merged normal that fits both parts better lowers the surfels' height error. Not
        // clamped at 0: a merge that straightens two surfels is the one to make first.
        const double addedHeight = merged.PlaneError() - A.PlaneError() - B.PlaneError();
        if (spread_ == MergeSpread::Extent)
            return ward * (A.normalSum / A.size - B.normalSum / B.size).squaredNorm() +
                   (merged.Scatter().trace() / merged.size + kMergePlaneWeight * addedHeight) * invH2_;
        return ward * ((A.normalSum / A.size - B.normalSum / B.size).squaredNorm() +
                       kMergeSpreadWeight * (A.positionSum / A.size - B.positionSum / B.size).squaredNorm() * invH2_) +
               kMergePlaneWeight * addedHeight * invH2_;
    }

    /// Cluster `keep` takes over the members of `gone`.
    void Merge(int keep, int gone) { sums_[keep].Add(sums_[gone]); }

private:
    struct Sums // 104 bytes a cluster: at 20 million points merging holds millions of them
    {
        double size = 0;
        Eigen::Vector3d normalSum = Eigen::Vector3d::Zero(), positionSum = Eigen::Vector3d::Zero();
        double moment[6] = {0, 0, 0, 0, 0, 0}; // sum of p p^T, upper triangle (kMomentRow, kMomentColumn)

        void Add(const Sums &o)
        {
            size += o.size;
            normalSum += o.normalSum;
            positionSum += o.positionSum;
            for (int e = 0; e < 6; ++e) moment[e] += o.moment[e];
        }
        /// Sum of the members' squared distances to the plane through the centroid along the
        /// mean normal; with normals that cancel out (no plane), the whole spread.
        /// Sum of (p - centroid)(p - centroid)^T over the members.
        Eigen::Matrix3d Scatter() const
        {
            Eigen::Matrix3d full;
            for (int e = 0; e < 6; ++e) full(kMomentRow[e], kMomentColumn[e]) = full(kMomentColumn[e], kMomentRow[e]) = moment[e];
            return full - positionSum * positionSum.transpose() / size;
        }
        double PlaneError() const
        {
            const Eigen::Matrix3d scatter = Scatter();
            const double length = normalSum.norm();
            if (!(length > 1e-6 * size)) return std::max(0.0, scatter.trace());
            const Eigen::Vector3d n = normalSum / length;
            return std::max(0.0, n.dot(scatter * n));
        }
    };
    std::vector<Sums> sums_;
    double invH2_;
    MergeSpread spread_;
};

/// Per cluster, the other clusters linked to it by `graph` (every neighbour found, not only the
/// cone), sorted, without repeats. `members` = ClusterMembers(clusters). `progress(fraction)`, if
/// given, is called now and then from the calling thread (at 20 million points this takes
/// seconds); when it returns false the lists are left incomplete and `cancelled`, if given, set.
inline std::vector<std::vector<int>> ClusterAdjacency(const NeighborGraph &graph, const Clustering &clusters,
                                                      const ClusterMembers &members,
                                                      const std::function<bool(double)> &progress = nullptr,
                                                      bool *cancelled = nullptr)
{
    std::vector<std::vector<int>> adjacent(clusters.clusterCount);
    const int chunk = 1024, chunks = (clusters.clusterCount + chunk - 1) / chunk;
    const int reportEvery = std::max(1, chunks / 50);
    std::atomic<int> chunksDone(0);
    std::atomic<bool> stop(false);
#pragma omp parallel
    {
        // Most links repeat (a cluster's members share neighbours, and a cluster has a few
        // neighbouring clusters): repeats are dropped as they come, by a look at the few kept,
        // before those are sorted and stored at their exact size.
        std::vector<int> linked;
#pragma omp for schedule(dynamic, 1024)
        for (int a = 0; a < clusters.clusterCount; ++a) {
            if (a % chunk == 0) {
                const int done = ++chunksDone;
                // Only the calling thread (OpenMP's master) talks to the caller's callback.
                if (progress && omp_get_thread_num() == 0 && done % reportEvery == 0 && !progress(double(done) / chunks))
                    stop = true;
            }
            if (stop.load(std::memory_order_relaxed)) continue;
            linked.clear();
            for (const int *i = members.begin(a); i != members.end(a); ++i) {
                const int *slot = graph.adjacency.data() + size_t(*i) * graph.stride;
                for (int t = 0; t < graph.found[*i]; ++t) {
                    const int b = clusters.label[slot[t]];
                    if (b >= 0 && b != a && std::find(linked.begin(), linked.end(), b) == linked.end()) linked.push_back(b);
                }
            }
            std::sort(linked.begin(), linked.end());
            adjacent[size_t(a)].assign(linked.begin(), linked.end());
        }
    }
    if (cancelled) *cancelled = stop;
    return adjacent;
}


/// Two clusters linked by the neighbour graph, a < b, and what merging them costs.
struct MergePair
{
    double cost;
    int a, b;
    bool operator<(const MergePair &o) const { return cost < o.cost || (cost == o.cost && (a < o.a || (a == o.a && b < o.b))); }
};

/// The pairs (a, b), a < b, with b in adjacent[a] (ClusterAdjacency: a member of a has a neighbour
/// in b; the k-nearest graph is not symmetric, and here too a link seen only from b's members
/// is not listed), as entries makeEntry(cost, a, b) with their costs by `model`, ordered by a,
/// then b; computed in parallel. The buffer has room for `spare` times as many entries more
/// (MergeToCount's queue grows in place).
template <class Entry, class MakeEntry>
std::vector<Entry> LinkedPairs(const MergeCostModel &model, const std::vector<std::vector<int>> &adjacent,
                               MakeEntry makeEntry, double spare = 0)
{
    const int count = int(adjacent.size());
    std::vector<size_t> start(size_t(count) + 1, 0); // first pair of each cluster a
    for (int a = 0; a < count; ++a) {
        const std::vector<int> &list = adjacent[size_t(a)];
        start[size_t(a) + 1] = start[size_t(a)] + size_t(list.end() - std::upper_bound(list.begin(), list.end(), a));
    }
    std::vector<Entry> pairs;
    pairs.reserve(start.back() + size_t(spare * double(start.back())));
    pairs.resize(start.back());
#pragma omp parallel for schedule(dynamic, 1024)
    for (int a = 0; a < count; ++a) {
        const std::vector<int> &list = adjacent[size_t(a)];
        size_t slot = start[size_t(a)];
        for (auto b = std::upper_bound(list.begin(), list.end(), a); b != list.end(); ++b)
            pairs[slot++] = makeEntry(model.Cost(a, *b), a, *b);
    }
    return pairs;
}

inline std::vector<MergePair> LinkedPairs(const MergeCostModel &model, const std::vector<std::vector<int>> &adjacent)
{
    return LinkedPairs<MergePair>(model, adjacent, [](double cost, int a, int b) { return MergePair{cost, a, b}; });
}

/// What MergeToCount and the exchanges merge by: each cluster's linked clusters and the cost model.
struct MergeBasis
{
    std::vector<std::vector<int>> adjacent; ///< ClusterAdjacency
    MergeCostModel model;
};

/// Builds the MergeBasis of `clusters` in steps (member lists, adjacency, cost model; each takes
/// seconds at 20 million points), calling `progress(fraction)`, fraction in [0, 1), before each and
/// within the adjacency; null when it returned false.
inline std::unique_ptr<MergeBasis> BuildMergeBasis(const PointArray &points, const PointArray &normals,
                                                   const NeighborGraph &graph, const Clustering &clusters,
                                                   double weightWidth, const std::function<bool(double)> &progress,
                                                   MergeSpread spread = MergeSpread::Ward)
{
    const auto goOn = [&progress](double fraction) { return !progress || progress(fraction); };
    if (!goOn(0)) return nullptr;
    const ClusterMembers members(clusters);
    if (!goOn(0.25)) return nullptr;
    bool stopped = false;
    std::vector<std::vector<int>> adjacent =
        ClusterAdjacency(graph, clusters, members, [&goOn](double done) { return goOn(0.25 + 0.5 * done); }, &stopped);
    if (stopped || !goOn(0.75)) return nullptr;
    return std::unique_ptr<MergeBasis>(
        new MergeBasis{std::move(adjacent), MergeCostModel(points, normals, clusters, members, weightWidth, spread)});
}

namespace detail {

/// MergeToCount's state: which cluster each merged one went to, and the queue of candidate
/// merges, cheapest first.
class MergeQueue
{
public:
    /// A candidate is costed after `when` merges; it is stale once a side merged away or took
    /// another cluster in since (changed[side] > when): the merge that changed a side costed that
    /// side's pairs anew.
    struct Candidate { double cost; int a, b, when; };
    struct Later
    {
        bool operator()(const Candidate &x, const Candidate &y) const
        {
            return x.cost > y.cost || (x.cost == y.cost && (x.a > y.a || (x.a == y.a && x.b > y.b)));
        }
    };

    /// The linked pairs of `count` clusters, none merged yet.
    /// The heap is one buffer, a quarter larger than the pairs: when full, stale entries are
    /// dropped (the order of the valid ones is a total order: the same merges) before it grows,
    /// so that the queue stays near the pairs' size (a doubling vector can hold 3 times as many
    /// at its peak).
    MergeQueue(const MergeCostModel &model, const std::vector<std::vector<int>> &adjacent, int count)
        : parent(count), changed(count, 0),
          heap(LinkedPairs<Candidate>(
              model, adjacent, [](double cost, int a, int b) { return Candidate{cost, a, b, 0}; }, 0.25))
    {
        for (int k = 0; k < count; ++k) parent[k] = k;
        std::make_heap(heap.begin(), heap.end(), Later());
    }

    /// The cluster that k went to.
    int Root(int k)
    {
        while (parent[k] != k) k = parent[k] = parent[parent[k]];
        return k;
    }
    bool Stale(const Candidate &c)
    {
        return Root(c.a) != c.a || Root(c.b) != c.b || changed[c.a] > c.when || changed[c.b] > c.when;
    }
    void Push(const Candidate &c)
    {
        if (heap.size() == heap.capacity() && !heap.empty()) {
            heap.erase(std::remove_if(heap.begin(), heap.end(), [this](const Candidate &x) { return Stale(x); }),
                       heap.end());
            std::make_heap(heap.begin(), heap.end(), Later());
            if (heap.size() > heap.capacity() / 2) heap.reserve(heap.capacity() + heap.capacity() / 2);
        }
        heap.push_back(c);
        std::push_heap(heap.begin(), heap.end(), Later());
    }
    Candidate Pop()
    {
        std::pop_heap(heap.begin(), heap.end(), Later());
        const Candidate top = heap.back();
        heap.pop_back();
        return top;
    }

    std::vector<int> parent;  ///< union-find forest of the merged clusters
    std::vector<int> changed; ///< per cluster: the merges done when it last took another in
    std::vector<Candidate> heap;
};

/// Merges the clusters of `top` (not stale), the `merges`-th merge: the smaller adjacency list
/// goes into the larger one, whose pairs are costed anew. Returns the cluster kept.
inline int MergeCandidate(const MergeQueue::Candidate &top, int merges, MergeQueue &queue,
                           std::vector<std::vector<int>> &adjacent, MergeCostModel &model)
{
    int keep = top.a, gone = top.b;
    if (adjacent[keep].size() < adjacent[gone].size()) std::swap(keep, gone);
    queue.parent[gone] = keep;
    model.Merge(keep, gone);
    queue.changed[keep] = merges + 1;
    std::vector<int> merged;
    for (int x : adjacent[keep]) merged.push_back(queue.Root(x));
    for (int x : adjacent[gone]) merged.push_back(queue.Root(x));
    SortUnique(merged);
    merged.erase(std::remove(merged.begin(), merged.end(), keep), merged.end());
    adjacent[keep] = std::move(merged);
    std::vector<int>().swap(adjacent[gone]);
    for (int x : adjacent[keep]) {
        const int a = std::min(keep, x), b = std::max(keep, x);
        queue.Push({model.Cost(a, b), a, b, merges + 1});
    }
    return keep;
}

/// Labels every point with its cluster's root, compacts the clusters, and replaces `adjacent`
/// (of the `count` clusters before merging) by the links of the compacted ones.
inline void RelabelMerged(int count, MergeQueue &queue, std::vector<std::vector<int>> &adjacent,
                          Clustering &clusters)
{
    for (int &l : clusters.label)
        if (l >= 0) l = queue.Root(l);
    const IndexArray remap = clusters.Compact();
    // A merged cluster's list holds the roots of its parts' links when it was last merged: their
    // roots now, renumbered, are the links of its members.
    std::vector<std::vector<int>> links(size_t(clusters.clusterCount));
    for (int c = 0; c < count; ++c) {
        if (remap[c] < 0) continue;
        std::vector<int> &list = links[size_t(remap[c])];
        for (int x : adjacent[size_t(c)]) {
            const int linked = remap[queue.Root(x)];
            if (linked >= 0 && linked != remap[c]) list.push_back(linked);
        }
        SortUnique(list);
        list.shrink_to_fit();
        std::vector<int>().swap(adjacent[size_t(c)]);
    }
    adjacent.swap(links);
}

} // namespace detail

/// Merges neighbouring clusters, cheapest first (MergeCostModel), until `target` remain (or no
/// two clusters are linked), from `basis` = BuildMergeBasis(clusters): the graph is not read
/// again (the caller may cut it meanwhile). Returns the number of merges; clusters are compacted
/// afterwards, and basis.adjacent then holds the merged clusters' links in their numbering
/// (what ClusterAdjacency would give for them), basis.model is spent. `progress(fraction)`, if
/// given, is called now and then from the calling thread (every few thousand merges: at 20
/// million points merging takes seconds); when it returns false merging stops and MergeToCount
/// returns kRefinementCancelled, the clusters unchanged. `record`, if given, receives the merges
/// in order.
inline int MergeToCount(MergeBasis &basis, int target, Clustering &clusters,
                        const std::function<bool(double)> &progress = nullptr,
                        std::vector<CountMerge> *record = nullptr)
{
    const int count = clusters.clusterCount;
    if (target >= count) return 0;
    const auto goOn = [&progress](double fraction) { return !progress || progress(fraction); };
    std::vector<std::vector<int>> &adjacent = basis.adjacent;
    MergeCostModel &model = basis.model;
    detail::MergeQueue queue(model, adjacent, count);
    if (!goOn(0.1)) return kRefinementCancelled;
    const int needed = count - target;
    int remaining = count, merges = 0, nextReport = 0;
    while (remaining > target && !queue.heap.empty()) {
        if (merges >= nextReport) {
            if (!goOn(0.1 + 0.9 * merges / needed)) return kRefinementCancelled;
            nextReport = merges + 4096;
        }
        const detail::MergeQueue::Candidate top = queue.Pop();
        if (queue.Stale(top)) continue;
        const int kept = detail::MergeCandidate(top, merges, queue, adjacent, model);
        if (record != nullptr) record->push_back({kept, kept == top.a ? top.b : top.a, top.cost});
        --remaining;
        ++merges;
    }
    detail::RelabelMerged(count, queue, adjacent, clusters);
    return merges;
}

/// MergeToCount, its basis built from `graph` (every neighbour found, not only the cone): the
/// basis takes the first fifth of the progress.
inline int MergeToCount(const PointArray &points, const PointArray &normals, const NeighborGraph &graph,
                        double weightWidth, int target, Clustering &clusters,
                        const std::function<bool(double)> &progress = nullptr)
{
    if (target >= clusters.clusterCount) return 0;
    const auto goOn = [&progress](double fraction) { return !progress || progress(fraction); };
    const std::unique_ptr<MergeBasis> basis =
        BuildMergeBasis(points, normals, graph, clusters, weightWidth, [&goOn](double done) { return goOn(0.2 * done); });
    if (!basis || !goOn(0.2)) return kRefinementCancelled;
    return MergeToCount(*basis, target, clusters, [&goOn](double done) { return goOn(0.2 + 0.8 * done); });
}

} // namespace gaussphere
} // namespace vcg

#endif
