// Beyond the paper: lowering the largest error at a fixed output size.
//
// At a target size (ResamplingParams::targetCount) the clusters come from one Gaussian sphere
// level, split or merged to the exact count. Their largest error, the distance of the worst
// point to the blended surface of the surfels (what bench/ reports as Delta*max, measured as
// vcg_ext/surfel_error measures it), is set by a single cluster: a merged, elongated surfel
// that leaves a member without a surfel facing it, or a cluster straddling a bend. The exchange
// trades clusters where the surface is easy for clusters where it is not, keeping the count:
// it splits a cluster at the worst point (its own, then those of the surfels blended there,
// nearest first), merges the cheapest pair of neighbouring clusters elsewhere (MergeCostModel, as
// MergeToCount chooses; pairs touching the split cluster or a kept exchange excluded), and
// keeps the exchange if the largest distance went down (by more than the rounding of projections
// summed in another order, 1e-9 of the diagonal). A split that does not lower it by itself
// (the count one higher) is not tried with merges; a merge that raises it again is followed by
// the next cheapest pair that shares no cluster with it. Rounds go on while an exchange is kept,
// up to maxRounds.
// The largest distance may be taken over some of the points only (MaxErrorExchangeParams::counted):
// a tile of a tiled run lowers its core points', as the whole run's rounds reach them
// (tools/gstile/target_share.h); no change may raise another point above 3/4 of it at the time
// (kUncountedRiseShare: the tile's halo points are other tiles' core points, where the surfels it
// keeps blend too), and the merge half takes no cluster with such a point (its neighbour decides
// there).
//
// Then the surfels the fit leaves in place at creases (surfel_offset.h: moved towards the blend's
// rounded edge, a small crease cluster leaves its face) are fitted too, all at once, if that lowers
// the sum of squared distances without raising the largest distance, nor the number of points
// beyond the 99.9th percentile of the distance or of the blended normal error on entry (so
// neither percentile rises); where it does, the moves of the surfels within reach of the points
// that rose are dropped and the rest tried again (up to 4 trials). At low counts the crease
// clusters are large (merged: ~20 points at 5 %) and on CAD parts nearly every surfel is one of
// them: left unfitted, the blend's rounding of the edges is the whole error there. The step costs
// a projection of every point for the blended normal errors and one to four trials. It comes
// after the exchanges, not in the recipe they try: crease surfels fitted before the exchanges
// raise the largest distance on some models, and the exchanges then stop early.
//
// A tile given the surfels its neighbours keep (FixedSurround: its seam step, tools/gstile/seam.h)
// then makes seam rounds: every point measured on those in place of the clusters the tile does not
// keep, exchanges (a split only into halves the tile keeps) that lower the largest distance so
// measured, down to the largest the other tiles reached on their own clusters. Its halo points
// count there too: a point beside a face is often lowered only by a change to the clusters of the
// tile that does not hold it. A point no exchange lowers (the surfels to change are another
// tile's) is set aside: it stops counting, may not rise, and the rounds go on with the next.
// The surfels refitted around a seam exchange take the crease fit's moves back (the plain fit
// leaves crease surfels in place), but for the clusters the exchange changes.
//
// Cost. A trial measures the distances again only where they can have changed
// (blended_distances.h); the surfels are updated where the change reaches (SurfelMaker::Update),
// into buffers reused by every trial, and the labels are changed in place and back (LabelChange).
// What stays linear is light: a comparison of every point's reach with the changed centres, a
// scan of the clusters' sampled neighbours for refits, a copy of the surfels. The exchanges take
// roughly as long as the rest of the resampling (bench/scale, at 10 % of 1 to 20 million points).
#ifndef VCG_EXT_GAUSSPHERE_MAX_ERROR_EXCHANGE_H
#define VCG_EXT_GAUSSPHERE_MAX_ERROR_EXCHANGE_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <functional>
#include <iterator>
#include <memory>
#include <utility>
#include <vector>

#include <vcg_ext/surfel/blended_surface.h>
#include <vcg_ext/surfel/percentile.h>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>
#include <vcg_ext/gaussphere/size_control/blended_distances.h>
#include <vcg_ext/gaussphere/size_control/cluster_refinement.h>
#include <vcg_ext/gaussphere/size_control/crease_fit_limits.h>
#include <vcg_ext/gaussphere/clustering/clustering.h>
#include <vcg_ext/gaussphere/size_control/surface_error_bound.h>
#include <vcg_ext/gaussphere/surfels/surfel_generation.h>
#include <vcg_ext/gaussphere/surfels/surfel_recipe.h>

namespace vcg {
namespace gaussphere {

/// Search widths: one split candidate and one merge per round often find no exchange that lowers
/// the largest distance; 6 split candidates (nearest the worst point first) and 4 merges per split
/// find one where wider searches do, at half their trials (bench/'s models at 5-30 %).
struct MaxErrorExchangeParams
{
    int maxRounds = 16;      ///< exchanges kept at most (0: none, the crease fit below only)
    /// Per point, nonzero where its distance counts for the largest one (empty: every point's).
    /// The other points are measured and blended alike; no exchange is made for them, and no
    /// change may raise one of them above the largest distance at the time (BlendedDistances::Measure).
    std::vector<char> counted;
    int splitCandidates = 6; ///< clusters at the worst point tried for the split, per round
    int mergeCandidates = 4; ///< cheapest pairs tried for the merge, per split that helps
    /// Last step: the surfels the fit leaves at creases (surfel_offset.h) are fitted too, for the
    /// clusters of at least this many members (0 = off; one-point clusters stand for the edge
    /// itself, crease_blend.h), where that lowers the sum of squared distances without raising the
    /// largest distance or the 99.9th percentiles of the distance and of the blended normal error.
    int creaseFitMinMembers = 2;
    /// ... tried at most this many times: each failed trial drops the moves of the surfels within
    /// reach of the points whose figures rose.
    int creaseFitTrials = 4;
    /// ... judged against these 99.9th percentiles (not given: the run's own on entry to the fit).
    CreaseFitLimits creaseFitLimits;
    /// On entry to the crease fit (not made when creaseFitMinMembers is 0), this many of the highest
    /// figures of the points that count go into MaxErrorExchangeResult::creaseFitEntry (0: none).
    int reportHighest = 0;
    MergeSpread mergeSpread = MergeSpread::Ward; ///< the merges' cost (MergeCostModel), as the clusters were merged
    /// Surfels kept elsewhere around the points, blended in place of the clusters it hides
    /// (FixedSurround). Given, the seam rounds follow the crease fit: exchanges measured beside it
    /// at every point (a split keeps both halves, FixedSurround::Kept), while the largest distance
    /// so measured lies above seamTarget; a point no exchange lowers is set aside.
    FixedSurround surround;
    double seamTarget = 0; ///< ... (0: the largest distance after the crease fit, maxAfter)
    /// ... at most this many exchanges kept, and points set aside, whatever maxRounds is: a tile
    /// whose share of the rounds is 0 mends its border too.
    int seamRounds = 16;
};

struct MaxErrorExchangeResult
{
    int exchanges = 0;      ///< exchanges kept
    int creaseFits = 0;     ///< surfels at creases fitted by the crease fit (creaseFitMinMembers)
    int trials = 0;         ///< surfel sets measured (each split, each split with a merge)
    double maxBefore = 0;   ///< largest distance to the blended surface before, model units
    double maxAfter = 0;    ///< ... and after
    std::vector<double> maxima; ///< maxBefore, then the largest distance after each kept exchange
    /// With MaxErrorExchangeParams::surround, the seam rounds after the crease fit: exchanges kept,
    /// points set aside (no exchange lowered them), and the largest distance of the points that
    /// count measured beside the surround before and after them.
    int seamExchanges = 0;
    int seamSetAside = 0;
    double seamMaxBefore = 0, seamMaxAfter = 0;
    CreaseFitEntry creaseFitEntry; ///< with MaxErrorExchangeParams::reportHighest (empty if no point counts)
    bool cancelled = false; ///< progress returned false
};

/// Merge pairs cheapest first, sorted as they are read: the exchange reads a few hundred of them,
/// cluster adjacency gives millions at 20 million points (seconds of sorting, without a report).
/// Only the `keep` cheapest are kept (16 B a pair; an exchange's bound: PairsReadAtMost).
class CheapestFirst
{
public:
    CheapestFirst() = default;
    explicit CheapestFirst(std::vector<MergePair> pairs, size_t keep = size_t(-1)) : pairs_(std::move(pairs))
    {
        if (keep >= pairs_.size()) return;
        std::nth_element(pairs_.begin(), pairs_.begin() + keep, pairs_.end()); // (cost, a, b): a total order
        pairs_.resize(keep);
        pairs_.shrink_to_fit();
    }
    bool Empty() const { return pairs_.empty(); }
    /// The i-th cheapest pair, or null past the last kept.
    const MergePair *At(size_t i)
    {
        if (i >= pairs_.size()) return nullptr;
        if (i >= sorted_) { // the next cheapest ones, at least as many as are sorted already
            const size_t end = std::min(pairs_.size(), std::max(i + 1, 2 * sorted_ + 1024));
            std::nth_element(pairs_.begin() + sorted_, pairs_.begin() + (end - 1), pairs_.end());
            std::sort(pairs_.begin() + sorted_, pairs_.begin() + end);
            sorted_ = end;
        }
        return &pairs_[i];
    }

private:
    std::vector<MergePair> pairs_;
    size_t sorted_ = 0;
};

/// How many of the cheapest `pairs` (between `clusterCount` clusters) ExchangeForMaxError can
/// read: a split tried with merges reads them in order until mergeCandidates are tried, skipping
/// the pairs that touch an excluded cluster (the settled ones, 3 per kept exchange; the split
/// one; the 2 of each merge tried), so no further than mergeCandidates + the pairs of the
/// 3 (maxRounds + seamRounds) + 1 + 2 mergeCandidates clusters that have the most. A few thousand of the
/// million pairs at 10 % of 10 million points.
inline size_t PairsReadAtMost(const std::vector<MergePair> &pairs, int clusterCount, const MaxErrorExchangeParams &param)
{
    const long long rounds = param.maxRounds + (param.surround.Given() ? param.seamRounds : 0);
    const long long excludedAtMost = 3LL * rounds + 1 + 2LL * param.mergeCandidates;
    if (excludedAtMost >= clusterCount) return pairs.size();
    std::vector<int> pairsOf(size_t(clusterCount), 0);
    for (const MergePair &p : pairs) {
        ++pairsOf[size_t(p.a)];
        ++pairsOf[size_t(p.b)];
    }
    std::nth_element(pairsOf.begin(), pairsOf.begin() + excludedAtMost, pairsOf.end(), std::greater<int>());
    size_t bound = size_t(std::max(1, param.mergeCandidates));
    for (long long c = 0; c < excludedAtMost; ++c) bound += size_t(pairsOf[size_t(c)]);
    return std::min(bound, pairs.size());
}

/// Labels of a clustering changed for a trial, with what they were: Undo() restores them and the
/// cluster count, and so does the destructor (an exception in a trial leaves the clustering as it
/// was) unless Keep() was called.
class LabelChange
{
public:
    explicit LabelChange(Clustering &clusters) : clusters_(clusters), count_(clusters.clusterCount) {}
    ~LabelChange() { Undo(); }
    LabelChange(const LabelChange &) = delete;
    LabelChange &operator=(const LabelChange &) = delete;

    void Set(int point, int label)
    {
        before_.push_back({point, clusters_.label[point]});
        clusters_.label[point] = label;
    }
    void Undo()
    {
        if (kept_) return;
        for (auto e = before_.rbegin(); e != before_.rend(); ++e) clusters_.label[e->first] = e->second;
        before_.clear();
        clusters_.clusterCount = count_;
    }
    void Keep() { kept_ = true; }

private:
    Clustering &clusters_;
    int count_;
    bool kept_ = false;
    std::vector<std::pair<int, int>> before_;
};

namespace detail {

/// What FitCreaseSurfels judges its trials by, over the points that count (MaxErrorExchangeParams::
/// counted), on entry: the run's own figures, the percentiles as given (MaxErrorExchangeParams::
/// creaseFitLimits) if they are.
struct CreaseFitBaseline
{
    std::vector<float> normalError; ///< per point, for the set on entry
    double sumOfSquares = 0;        ///< of the distances
    double largest = 0;             ///< no point that counts may rise above it
    double distanceLimit = 0, normalLimit = 0; ///< the 99.9th percentiles (or the limits given) ...
    int distanceBeyond = 0, normalBeyond = 0;  ///< ... and the points beyond them, whose number may not rise
};

/// The `count` highest of `values`, highest first (a copy of those only).
inline std::vector<double> Highest(const std::vector<double> &values, std::size_t count)
{
    std::vector<double> highest(std::min(count, values.size()));
    std::partial_sort_copy(values.begin(), values.end(), highest.begin(), highest.end(), std::greater<double>());
    return highest;
}

/// The crease fit's baseline for `fitted`, the set `distances` measured; with param.reportHighest,
/// the highest figures into `entry`. False when no point counts.
inline bool MeasureCreaseFitBaseline(const PointArray &points, const BlendedDistances &distances,
                                     const std::vector<Surfel> &fitted, const MaxErrorExchangeParams &param,
                                     CreaseFitBaseline &base, CreaseFitEntry &entry)
{
    const int n = int(points.size());
    base.normalError = distances.NormalErrors(fitted);
    // One copy of the figures of the points that count at a time (8 B a point), in point order.
    std::vector<double> figures;
    figures.reserve(points.size());
    for (int i = 0; i < n; ++i) {
        if (!distances.Counts(i)) continue;
        figures.push_back(distances.Distance(i));
        base.sumOfSquares += figures.back() * figures.back(); // in point order: the same for any thread count
    }
    if (figures.empty()) return false;
    const CreaseFitLimits &limits = param.creaseFitLimits;
    if (param.reportHighest > 0) entry.distances = Highest(figures, std::size_t(param.reportHighest));
    base.distanceLimit = limits.given ? limits.distance : NearestRankPercentile(std::move(figures), 99.9);
    figures.clear(); // moved from: emptied before its reuse
    figures.reserve(points.size());
    for (int i = 0; i < n; ++i)
        if (distances.Counts(i)) figures.push_back(base.normalError[size_t(i)]);
    if (param.reportHighest > 0) entry.normalErrors = Highest(figures, std::size_t(param.reportHighest));
    base.normalLimit = limits.given ? limits.normalError : NearestRankPercentile(std::move(figures), 99.9);
    base.largest = distances.Max();
    for (int i = 0; i < n; ++i) {
        if (!distances.Counts(i)) continue;
        base.distanceBeyond += distances.Distance(i) > base.distanceLimit;
        base.normalBeyond += base.normalError[size_t(i)] > base.normalLimit;
    }
    return true;
}

/// A crease fit's move of one surfel: (cluster, move along its normal).
using CreaseMove = std::pair<int, float>;

/// ExchangeForMaxError's crease fit (file header): the surfels of `current` left at creases, fitted
/// where the measure allows it. `distances` has measured current.fitted; a kept fit is accepted
/// there and swapped into `current`. Counts its measures in `trials`; returns the moves kept
/// (clusters ascending; empty when none). With param.reportHighest, `entry` receives the highest
/// figures on entry (crease_fit_limits.h).
template <class GoOn>
std::vector<CreaseMove> FitCreaseSurfels(const PointArray &points, const Clustering &clusters, const SurfelMaker &maker,
                     const MaxErrorExchangeParams &param, BlendedDistances &distances, SurfelMaker::Set &current,
                     int &trials, CreaseFitEntry &entry, GoOn &&goOn)
{
    // The surfels left at creases (surfel_offset.h), fitted where the measure allows it: the sum of
    // squared distances must fall, and neither the largest distance, nor the number of points
    // beyond the 99.9th percentiles of the distance and of the blended normal error (their values
    // on entry to this step, or the limits given) may rise, so neither percentile rises.
    const ClusterMembers members(clusters);
    const std::vector<CreaseMove> moves = maker.CreaseMoves(current, clusters, members, param.creaseFitMinMembers);
    if ((moves.empty() && param.reportHighest == 0) || !goOn()) return {};
    CreaseFitBaseline base;
    if (!MeasureCreaseFitBaseline(points, distances, current.fitted, param, base, entry) || moves.empty()) return {};
    // All moves at once; where that raises a figure, the moves of the surfels within reach of
    // the points that rose are dropped and the rest tried again, up to creaseFitTrials times.
    std::vector<CreaseMove> kept = moves;
    std::vector<Surfel> fitted;
    for (int attempt = 0; attempt < param.creaseFitTrials && !kept.empty() && goOn(); ++attempt) {
        fitted = current.fitted;
        for (const auto &move : kept) MoveSurfel(fitted[size_t(move.first)], move.second);
        ++trials;
        BlendedDistances::Measure measure = distances.Try(current.fitted, fitted);
        double squares = base.sumOfSquares;
        int dBeyond = base.distanceBeyond, nBeyond = base.normalBeyond;
        std::vector<size_t> rose; // indices into measure.points
        for (size_t t = 0; t < measure.points.size(); ++t) {
            const int i = measure.points[t];
            if (!distances.Counts(i)) { // it may not rise above its share of the largest distance (Measure::risenMax)
                const double after = measure.distance[t];
                if (after / kUncountedRiseShare > distances.Max() && after > distances.Distance(i) + distances.Tolerance()) rose.push_back(t);
                continue;
            }
            const double before = distances.Distance(i), after = measure.distance[t];
            const float normalBefore = base.normalError[size_t(i)], normalAfter = measure.normalError[t];
            squares += after * after - before * before;
            const bool distanceRose = after > base.distanceLimit && !(before > base.distanceLimit);
            const bool normalRose = normalAfter > base.normalLimit && !(normalBefore > base.normalLimit);
            dBeyond += int(after > base.distanceLimit) - int(before > base.distanceLimit);
            nBeyond += int(normalAfter > base.normalLimit) - int(normalBefore > base.normalLimit);
            if (distanceRose || normalRose || after > base.largest) rose.push_back(t);
        }
        if (!(squares < base.sumOfSquares)) break;
        if (measure.max <= base.largest && measure.risenMax / kUncountedRiseShare <= distances.Max() &&
            dBeyond <= base.distanceBeyond && nBeyond <= base.normalBeyond) {
            distances.Accept(std::move(measure));
            current.fitted.swap(fitted);
            return kept;
        }
        std::vector<CreaseMove> rest;
        for (const auto &move : kept) {
            const vcg::Point3d c = vcg::Point3d::Construct(fitted[size_t(move.first)].position);
            bool near = false;
            for (size_t t : rose) {
                const double r = measure.reach[t];
                near = near || (c - vcg::Point3d::Construct(points[size_t(measure.points[t])])).SquaredNorm() <= r * r;
            }
            if (!near) rest.push_back(move);
        }
        if (rest.size() == kept.size()) break; // nothing to drop: the rise is not local
        kept.swap(rest);
    }
    return {};
}

/// ExchangeForMaxError's merge pairs: every linked pair of `clusters`, cheapest first, as many as
/// the exchange can read (PairsReadAtMost), into `pairs`. The links read every neighbour slot of
/// `graph` (or come from `clusterLinks`, taken over), the surfels and their fit only the first
/// kOffsetNeighbors: `graph` is cut to those once the links are known, before the costs, the
/// pairs and the exchange's own buffers exist. Returns false when goOn() stopped it.
template <class GoOn>
bool ListMergePairs(const PointArray &points, const PointArray &normals, NeighborGraph &graph, double weightWidth,
                    const MaxErrorExchangeParams &param, const Clustering &clusters,
                    std::vector<std::vector<int>> *clusterLinks, GoOn &goOn, CheapestFirst &pairs)
{
    const ClusterMembers members(clusters);
    std::vector<std::vector<int>> links;
    bool stopped = !goOn();
    if (clusterLinks) links.swap(*clusterLinks);
    else if (!stopped) links = ClusterAdjacency(graph, clusters, members, [&goOn](double) { return goOn(); }, &stopped);
    if (stopped || !goOn()) return false;
    KeepFirstSlots(graph, kOffsetNeighbors);
    const MergeCostModel model(points, normals, clusters, members, weightWidth, param.mergeSpread);
    if (!goOn()) return false;
    std::vector<MergePair> linked = LinkedPairs(model, links);
    if (!param.counted.empty()) {
        // No merge takes a cluster with a point that does not count: in a tile, a cluster reaching
        // its halo, whose merge is the neighbouring tile's to make. Clusters not settled keep
        // their members, so the pairs are dropped here once.
        std::vector<char> uncounted(size_t(clusters.clusterCount), 0);
        for (size_t i = 0; i < param.counted.size(); ++i)
            if (!param.counted[i] && clusters.label[i] >= 0) uncounted[size_t(clusters.label[i])] = 1;
        linked.erase(std::remove_if(linked.begin(), linked.end(),
                                    [&uncounted](const MergePair &p) { return uncounted[size_t(p.a)] || uncounted[size_t(p.b)]; }),
                     linked.end());
    }
    const size_t readable = PairsReadAtMost(linked, clusters.clusterCount, param);
    pairs = CheapestFirst(std::move(linked), readable);
    return true;
}

/// What the rounds of ExchangeForMaxError read and change.
struct ExchangeState
{
    const PointArray &points, &normals;
    const MaxErrorExchangeParams &param;
    const SurfelMaker &maker;
    Clustering &clusters;
    BlendedDistances *distances; ///< has measured current.fitted
    CheapestFirst &pairs;
    SurfelMaker::Set &current;   ///< the surfels of `clusters`
    SurfelMaker::Set &trial;     ///< the set every trial fills
    std::vector<char> &settled;  ///< clusters of kept exchanges: not merged again
    MaxErrorExchangeResult &result;
    int count;                   ///< clusters.clusterCount between trials
    double rounding;             ///< a largest distance lower by less than this is the same
    double invH2;                ///< 1 / weightWidth^2, for SplitMembers
    bool besideSurround;         ///< `distances` measure beside param.surround: a split keeps both halves
    /// The crease fit's moves the clusters keep (the seam rounds come after it; nullptr before).
    std::vector<CreaseMove> *creaseMoves;
};

/// The surfels x.trial fitted again around a change (SurfelMaker::Update) take the crease fit's
/// moves back, but for the `changed` clusters: their unfitted surfels are those the moves were
/// fitted to (a move reads the unfitted surfels only), and the plain fit would leave them at the
/// crease. Nothing to do before the crease fit.
inline void KeepCreaseMoves(ExchangeState &x, std::initializer_list<int> changed)
{
    if (!x.creaseMoves) return;
    for (const CreaseMove &move : *x.creaseMoves) {
        if (std::find(changed.begin(), changed.end(), move.first) != changed.end()) continue;
        Surfel &surfel = x.trial.fitted[size_t(move.first)];
        surfel = x.trial.unfitted[size_t(move.first)];
        MoveSurfel(surfel, move.second);
    }
}

/// Drops the crease fit's moves of the `changed` clusters of a kept exchange (their surfels are new).
inline void DropCreaseMoves(ExchangeState &x, std::initializer_list<int> changed)
{
    if (!x.creaseMoves) return;
    std::vector<CreaseMove> &moves = *x.creaseMoves;
    moves.erase(std::remove_if(moves.begin(), moves.end(),
                               [&changed](const CreaseMove &move) {
                                   return std::find(changed.begin(), changed.end(), move.first) != changed.end();
                               }),
                moves.end());
}

/// The merges tried with the split of cluster c into firstHalf and secondHalf (ascending; the
/// labels of `x.clusters` as before the split, `members` theirs): the cheapest pairs that touch
/// neither c, a settled cluster nor a merge tried before, at most mergeCandidates; the second half
/// takes the index of the cluster merged away. Keeps the first exchange that lowers the largest
/// distance (clusters, distances, current and settled updated) and returns whether one was kept.
template <class GoOn>
bool TryMerges(ExchangeState &x, const ClusterMembers &members, int c, const std::vector<int> &firstHalf,
               const std::vector<int> &secondHalf, GoOn &goOn)
{
    std::vector<char> excluded = x.settled;
    excluded[c] = 1;
    int merges = 0;
    for (size_t p = 0; const MergePair *pair = x.pairs.At(p); ++p) {
        if (merges >= x.param.mergeCandidates) break;
        const int keep = pair->a, gone = pair->b;
        if (excluded[keep] || excluded[gone]) continue;
        ++merges;
        std::vector<int> merged;
        std::merge(members.begin(keep), members.end(keep), members.begin(gone), members.end(gone),
                   std::back_inserter(merged));
        if (!goOn()) break;
        ++x.result.trials;
        LabelChange exchange(x.clusters);
        for (const int *i = members.begin(gone); i != members.end(gone); ++i) exchange.Set(*i, keep);
        for (int i : secondHalf) exchange.Set(i, gone);
        x.maker.Update(x.current, members, x.clusters, {c, gone, keep}, {firstHalf, secondHalf, merged}, x.trial);
        KeepCreaseMoves(x, {c, gone, keep});
        BlendedDistances::Measure measure = x.distances->Try(x.current.fitted, x.trial.fitted);
        if (measure.Largest() < x.distances->Max() - x.rounding) {
            exchange.Keep();
            DropCreaseMoves(x, {c, gone, keep});
            x.distances->Accept(std::move(measure));
            std::swap(x.current, x.trial); // the old set's buffers serve the next trials
            x.settled[c] = x.settled[keep] = x.settled[gone] = 1;
            return true;
        }
        exchange.Undo();
        excluded[keep] = excluded[gone] = 1;
    }
    return false;
}

/// The largest of `distances` at the first n points where `counted` flags them (empty: every one).
inline double LargestCounted(const BlendedDistances &distances, const std::vector<char> &counted, int n)
{
    double largest = 0;
    for (int i = 0; i < n; ++i)
        if (counted.empty() || counted[size_t(i)]) largest = std::max(largest, distances.Distance(i));
    return largest;
}

/// The split of cluster c into firstHalf and secondHalf (ascending), tried alone, its second half
/// as an extra cluster: if that does not lower the largest distance, a merge elsewhere is not
/// tried (it seldom helps where the split did not); if it does, TryMerges. Trials change the
/// labels in place and undo the change (no copy of them). Returns whether an exchange was kept.
template <class GoOn>
bool TrySplit(ExchangeState &x, const ClusterMembers &members, int c, const std::vector<int> &firstHalf,
              const std::vector<int> &secondHalf, GoOn &goOn)
{
    if (!goOn()) return false;
    ++x.result.trials;
    LabelChange split(x.clusters);
    for (int i : secondHalf) split.Set(i, x.count);
    x.clusters.clusterCount = x.count + 1;
    x.maker.Update(x.current, members, x.clusters, {c, x.count}, {firstHalf, secondHalf}, x.trial);
    KeepCreaseMoves(x, {c, x.count});
    const bool splitHelps = x.distances->Try(x.current.fitted, x.trial.fitted).Largest() < x.distances->Max() - x.rounding;
    split.Undo();
    if (!splitHelps) return false;
    return TryMerges(x, members, c, firstHalf, secondHalf, goOn);
}

/// One round of ExchangeForMaxError: splits of the worst point's cluster first, then of those of
/// the surfels blended at it, nearest first (at most splitCandidates), each tried with merges
/// where it helps. Returns whether an exchange was kept.
template <class GoOn>
bool ExchangeRound(ExchangeState &x, GoOn &goOn)
{
    const ClusterMembers members(x.clusters);
    std::vector<int> candidates{x.clusters.label[x.distances->Worst()]};
    for (int c : x.distances->BlendedAt(x.distances->Worst(), x.current.fitted))
        if (std::find(candidates.begin(), candidates.end(), c) == candidates.end()) candidates.push_back(c);
    bool kept = false;
    int splitsTried = 0;
    for (int c : candidates) {
        if (kept || x.result.cancelled || splitsTried >= x.param.splitCandidates) break;
        if (members.Size(c) < 2) continue;
        std::vector<int> part(members.begin(c), members.end(c));
        int *mid = SplitMembers(x.points, x.normals, part.data(), part.data() + part.size(), x.invH2);
        if (!mid) continue;
        std::vector<int> firstHalf(part.data(), mid), secondHalf(mid, part.data() + part.size());
        std::sort(firstHalf.begin(), firstHalf.end());
        std::sort(secondHalf.begin(), secondHalf.end());
        // Beside a surround, a half the run would not keep would leave its points to no surfel:
        // such a split is no candidate.
        const FixedSurround &surround = x.param.surround;
        if (x.besideSurround &&
            !(surround.Kept(firstHalf, x.param.counted) && surround.Kept(secondHalf, x.param.counted)))
            continue;
        ++splitsTried;
        kept = TrySplit(x, members, c, firstHalf, secondHalf, goOn);
    }
    return kept;
}

/// ExchangeForMaxError's seam rounds (file header), after the crease fit, whose kept moves are
/// `creaseMoves`: every point, the tile's halo points too, measured beside param.surround and
/// lowered while an exchange does so, down to param.seamTarget (or the largest distance the run
/// reached). The clusters the run does not keep, as the rounds before left them, are hidden, and
/// the seam rounds keep them (a split keeps both halves, a merge takes clusters of counted points).
/// A point no exchange of the run lowers (its surfels are another tile's) is set aside: it stops
/// counting, so it may not rise (BlendedDistances::Measure), and the rounds go on with the next.
/// Exchanges and set-asides are each at most param.seamRounds.
template <class GoOn>
void SeamRounds(const ExchangeState &run, std::vector<CreaseMove> &creaseMoves, double diagonal, GoOn &goOn)
{
    const MaxErrorExchangeParams &param = run.param;
    MaxErrorExchangeResult &result = run.result;
    FixedSurround surround = param.surround;
    surround.HideClustersNotKept(run.clusters, param.counted);
    std::vector<char> seamCounted(run.points.size(), 1);
    BlendedDistances beside(run.points, run.normals, diagonal, &seamCounted, &surround);
    if (!beside.Reset(run.current.fitted, goOn)) return;
    ExchangeState seam = run;
    seam.distances = &beside;
    seam.besideSurround = true;
    seam.creaseMoves = &creaseMoves;
    const int n = int(run.points.size());
    result.seamMaxBefore = LargestCounted(beside, param.counted, n);
    const double target = param.seamTarget > 0 ? param.seamTarget : result.maxAfter;
    while (result.seamExchanges < param.seamRounds && result.seamSetAside < param.seamRounds &&
           !seam.pairs.Empty() && beside.Max() > target && !result.cancelled) {
        if (ExchangeRound(seam, goOn)) {
            ++result.seamExchanges;
        } else if (!result.cancelled) {
            seamCounted[size_t(beside.Worst())] = 0;
            beside.Recount();
            ++result.seamSetAside;
        }
    }
    result.seamMaxAfter = LargestCounted(beside, param.counted, n);
}

} // namespace detail

/// Exchanges clusters of `clusters` at a fixed count to lower the largest distance of a point
/// to the blended surface of the surfels `maker` makes of them (file header), measured as
/// metric::ComputeSurfelError measures it (default BlendParams) over the bounding-box
/// `diagonal` of the points. `progress(round)` is called before the first measure, between its
/// steps (generation, fit, blocks of points, the merge pairs' set-up) and before each trial (round
/// from 0); when it returns false the exchange stops with cancelled = true and the clusters of the
/// last kept exchange. On return `surfels` holds maker.Make(clusters).fitted; when cancelled, they
/// may be unfitted or not made at all (a cancelled run is discarded).
/// Nothing is tried with fewer than 3 clusters, weightWidth <= 0 (no merge cost) or every point
/// on the surface already.
/// \pre points and unit normals as clustered, every point labelled, `graph` their neighbour
///      graph (the maker's too); clusters compact with clusterCount >= 1.
/// `clusterLinks`, if given, is ClusterAdjacency of `clusters` (MergeToCount leaves it in its
/// basis): taken over, and `graph` is then read for the fits' slots only.
/// \post clusters.clusterCount unchanged; maxAfter <= maxBefore; deterministic: the result does
///       not depend on the thread count. Unless nothing was tried, `graph` keeps only its first
///       kOffsetNeighbors slots per point (KeepFirstSlots: what the maker's fits read; at 20 M
///       points its other slots would be 32 B a point at the exchanges' memory peak).
inline MaxErrorExchangeResult ExchangeForMaxError(const PointArray &points, const PointArray &normals,
                                                  NeighborGraph &graph, double weightWidth, double diagonal,
                                                  const MaxErrorExchangeParams &param, Clustering &clusters,
                                                  const SurfelMaker &maker,
                                                  std::vector<Surfel> &surfels,
                                                  const std::function<bool(int)> &progress = nullptr,
                                                  std::vector<std::vector<int>> *clusterLinks = nullptr)
{
    MaxErrorExchangeResult result;
    const int count = clusters.clusterCount;
    const bool active = count >= 3 && param.maxRounds >= 0 && weightWidth > 0;
    if (!active) {
        surfels = maker.MakeFitted(clusters);
        return result;
    }
    int round = 0;
    auto goOn = [&]() {
        if (progress && !progress(round)) result.cancelled = true;
        return !result.cancelled;
    };
    BlendedDistances distances(points, normals, diagonal, &param.counted);
    if (!goOn()) return result; // cancelled: the caller discards the run
    // The clusters of a kept exchange are not merged again (that would undo it); neither, among
    // the merges tried with one split, are the clusters of a merge that failed (otherwise the next
    // cheapest pairs merge the same neighbourhood back, and the exchanges stall). The pairs
    // between the other clusters keep their links and costs, so they are listed once: every
    // linked pair, cheapest first (ties by index: deterministic).
    CheapestFirst pairs;
    if (!detail::ListMergePairs(points, normals, graph, weightWidth, param, clusters, clusterLinks, goOn, pairs))
        return result;
    SurfelMaker::Set current = maker.Make(clusters, goOn); // unfitted if cancelled before the fit
    if (result.cancelled || !goOn() || !distances.Reset(current.fitted, goOn)) {
        surfels = std::move(current.fitted);
        return result;
    }
    result.maxBefore = distances.Max();
    result.maxima.push_back(result.maxBefore);
    std::vector<char> settled(count, 0);
    // One surfel set for every trial: its buffers (two surfels per cluster) are filled anew, not
    // allocated anew (fresh pages cost more than the copy on a virtual machine).
    SurfelMaker::Set trial;
    // A largest distance lower by less than `rounding` is the same: projections summed in another
    // order (a trial's surface holds the surfels near the points it projects) differ in the last bits.
    detail::ExchangeState state{points,  normals, param,   maker,  clusters,          &distances,
                                pairs,   current, trial,   settled, result,           count,
                                1e-9 * diagonal, 1.0 / (weightWidth * weightWidth), false, nullptr};
    for (; round < param.maxRounds && !pairs.Empty() && distances.Max() > 0 && !result.cancelled; ++round) {
        if (!detail::ExchangeRound(state, goOn)) break;
        ++result.exchanges;
        result.maxima.push_back(distances.Max());
    }
    std::vector<detail::CreaseMove> creaseMoves;
    if (!result.cancelled && param.creaseFitMinMembers > 0 && goOn()) {
        creaseMoves = detail::FitCreaseSurfels(points, clusters, maker, param, distances, current, result.trials,
                                               result.creaseFitEntry, goOn);
        result.creaseFits = int(creaseMoves.size());
    }
    result.maxAfter = distances.Max();
    if (param.surround.Given() && !result.cancelled && goOn()) detail::SeamRounds(state, creaseMoves, diagonal, goOn);
    surfels = std::move(current.fitted);
    return result;
}

} // namespace gaussphere
} // namespace vcg

#endif
