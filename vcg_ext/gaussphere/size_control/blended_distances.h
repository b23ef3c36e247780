// Distances of points to the blended surface of a surfel set that changes a few surfels at a time
// (max_error_exchange.h's trials): a changed set is measured again only at the points whose
// projection can involve a changed surfel.
//
// A projection involves only the surfels within its reach (SurfelSurface::Project), so each point
// keeps its reach from the last measure, and a trial projects again the points whose reach holds a
// surfel that changed (split, merged, refitted): tens to hundreds per trial, on a surface of the
// surfels near them, or of all surfels where more points than surfels are projected again. The
// local measure equals a full one up to rounding, except where surfel centres tie for the k-th
// nearest of a projection step (regular grids): which of them a tree returns is arbitrary, for a
// full measure too.
//
// A tile of a tiled run measures beside the surfels its neighbours keep (FixedSurround), and its
// points that do not count for the largest distance may rise only to a share of it
// (kUncountedRiseShare).
#ifndef VCG_EXT_GAUSSPHERE_BLENDED_DISTANCES_H
#define VCG_EXT_GAUSSPHERE_BLENDED_DISTANCES_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include <vcg_ext/surfel/blended_surface.h>

#include <vcg_ext/gaussphere/clustering/clustering.h>
#include <vcg_ext/gaussphere/size_control/surface_error_bound.h>
#include <vcg_ext/gaussphere/support/flat_vector.h>
#include <vcg_ext/gaussphere/surfels/surfel_generation.h>

namespace vcg {
namespace gaussphere {

/// Surfels that blend beside a run's own and never change, and the run's clusters they stand in
/// for: a tile's neighbours keep the surfels beyond its faces, so its points there lie as far from
/// the merged output as from those, not from the clusters its halo gives it.
struct FixedSurround
{
    std::vector<Surfel> surfels; ///< blended in every measure, at the points' scale
    /// Per point (empty: its index), the key of the rule that decides which clusters the run keeps:
    /// those whose anchor, the member of smallest key, counts (MaxErrorExchangeParams::counted).
    std::vector<std::uint64_t> anchorKeys;
    std::vector<char> hidden;    ///< per cluster (missing: 0): nonzero where its surfel is not blended
    bool Given() const { return !surfels.empty() || !hidden.empty(); }

    /// Whether the run keeps a cluster of `members` (indices of points) by that rule.
    bool Kept(const std::vector<int> &members, const std::vector<char> &counted) const
    {
        int anchor = -1;
        for (int i : members)
            if (anchor < 0 || Key(i) < Key(anchor)) anchor = i;
        return anchor >= 0 && (counted.empty() || counted[size_t(anchor)] != 0);
    }

    /// Hides the clusters of `clusters` the run does not keep.
    void HideClustersNotKept(const Clustering &clusters, const std::vector<char> &counted)
    {
        std::vector<int> anchor(size_t(clusters.clusterCount), -1);
        for (size_t i = 0; i < clusters.label.size(); ++i) {
            const int c = clusters.label[i];
            if (c >= 0 && (anchor[size_t(c)] < 0 || Key(int(i)) < Key(anchor[size_t(c)]))) anchor[size_t(c)] = int(i);
        }
        hidden.assign(anchor.size(), 0);
        for (size_t c = 0; c < anchor.size(); ++c)
            hidden[c] = !(anchor[c] >= 0 && (counted.empty() || counted[size_t(anchor[c])] != 0));
    }

private:
    std::uint64_t Key(int i) const { return anchorKeys.empty() ? std::uint64_t(i) : anchorKeys[size_t(i)]; }
};

/// How far a point that does not count may rise, as a share of the largest distance. A tile
/// measures its halo points on its own surfels beyond its faces, which differ from those the
/// neighbouring tile keeps there (other merges, other crease fits), so a rise the tile sees just
/// below the largest distance can lie above it in the merged output (the dragon at 4,000 surfels
/// in 13 tiles: with a share of 1, one crease fit put the tiled largest distance 32 % above the
/// whole run's).
constexpr double kUncountedRiseShare = 0.75;

/// Points projected at a time for the blended normal errors of the crease fit.
constexpr int kNormalErrorBlock = 1 << 16;

/// Distances of the points to the blended surface of a set of surfels, kept for a changing set:
/// a new set is measured only at the points whose projection may involve a changed surfel. The
/// caller keeps the current set and passes it in (Try, BlendedAt): no second copy here.
///
/// No surface of every surfel is made after Reset: a projection involves only the surfels within
/// its reach (SurfelSurface::Project), so a point is projected on a surface of the surfels near it,
/// found through the tree of the set Reset measured (the unchanged ones sit where they sat then)
/// and the list of those changed since. A whole surface would cost tens of milliseconds per trial
/// at 100,000 surfels, and seconds at 2 million.
///
/// With a FixedSurround, the set blended is its surfels followed by the clusters' surfels it does
/// not hide (cluster c at Offset() + c); the indices below are those of that set, unless they
/// name a cluster.
class BlendedDistances
{
public:
    /// `counted`, if given and not empty, flags the points whose distances count for Max() and
    /// Worst(); `surround`, if given, blends beside the clusters' surfels. Both must outlive this object.
    BlendedDistances(const PointArray &points, const PointArray &normals, double diagonal,
                     const std::vector<char> *counted = nullptr, const FixedSurround *surround = nullptr)
        : points_(points), normals_(normals), counted_(counted != nullptr && !counted->empty() ? counted : nullptr),
          surround_(surround != nullptr && surround->Given() ? surround : nullptr),
          tolerance_(metric_.convergenceTolerance * diagonal)
    {}

    /// A measured surfel set: the distances that differ from the current ones.
    struct Measure
    {
        std::vector<int> points;          ///< projected again
        std::vector<double> distance;
        std::vector<float> reach;
        std::vector<float> normalError;   ///< |n_q - blended normal| at `points` (the blended L2,1 error)
        double max = 0;                   ///< over the points that count
        int worst = -1;
        /// The largest distance of the points that do not count and rose by more than the
        /// projection's tolerance (0: none): a change may not raise them above kUncountedRiseShare
        /// of the largest distance (a tile's halo points are other tiles' core points).
        double risenMax = 0;
        std::vector<int> fresh;           ///< surfels that differ from the set Reset measured (ascending)
        /// What a change must keep below the largest distance: max, and the points that rose
        /// scaled by their share.
        double Largest() const { return std::max(max, risenMax / kUncountedRiseShare); }
    };

    /// Measures `surfels` (one per cluster) at every point and makes them the current set.
    /// `step`, if given, is called between blocks of points (seconds apart at tens of millions of
    /// points); when it returns false the measure stops and Reset returns false.
    bool Reset(const std::vector<Surfel> &clusterSurfels, const std::function<bool()> &step = nullptr)
    {
        const int n = int(points_.size());
        distance_.assign(n, 0.0);
        reach_.assign(n, 0.f);
        max_ = 0;
        worst_ = -1;
        measured_.reset();
        changedSinceReset_.clear();
        std::vector<Surfel> scratch;
        const std::vector<Surfel> &surfels = Blended(clusterSurfels, scratch);
        measuredIndex_ = Visible(surfels);
        if (n == 0 || surfels.empty()) return true;
        SurfelSurface whole = WholeSurface(surfels);
        const int block = 1 << 16;
        for (int start = 0; start < n; start += block) {
            if (step && !step()) return false;
            const int count = std::min(block, n - start);
            Project(whole, nullptr, start, count, distance_.data() + start, reach_.data() + start);
        }
        // Trials only look surfels up by centre: the tree is kept, the blending data freed
        // (88 B a surfel; 9 B a point at TargetPercentage 10).
        measured_.reset(new CenterTree(std::move(whole).ReleaseTree()));
        for (int i = 0; i < n; ++i)
            if (Counts(i)) KeepWorst(distance_[i], i, max_, worst_);
        return true;
    }

    /// Measures `surfels` where they differ from `current`, the set last measured (Reset, or the
    /// one whose Measure was accepted); same cluster numbering, extra surfels count as changed.
    Measure Try(const std::vector<Surfel> &currentClusters, const std::vector<Surfel> &clusterSurfels) const
    {
        std::vector<Surfel> currentScratch, scratch;
        const std::vector<Surfel> &current = Blended(currentClusters, currentScratch);
        const std::vector<Surfel> &surfels = Blended(clusterSurfels, scratch);
        Measure m;
        std::vector<vcg::Point3d> moved; // old and new centres of every surfel that changed
        std::vector<int> changed;
        Changes(current, surfels, moved, changed);
        std::set_union(changed.begin(), changed.end(), changedSinceReset_.begin(), changedSinceReset_.end(),
                       std::back_inserter(m.fresh));
        double untouchedMax = 0;
        int untouchedWorst = -1; // the first point of the largest distance: the same for any thread count
        const std::vector<char> affected = Affected(moved, untouchedMax, untouchedWorst);
        for (int i = 0; i < int(affected.size()); ++i)
            if (affected[i]) m.points.push_back(i);
        ProjectAffected(surfels, m);
        for (int t = 0; t < int(m.points.size()); ++t) {
            const int i = m.points[t];
            if (Counts(i)) KeepWorst(m.distance[t], i, m.max, m.worst);
            else if (m.distance[t] > distance_[i] + tolerance_) m.risenMax = std::max(m.risenMax, m.distance[t]);
        }
        if (untouchedWorst >= 0 && (untouchedMax > m.max || m.worst < 0)) { m.max = untouchedMax; m.worst = untouchedWorst; }
        return m;
    }

    void Accept(Measure &&m)
    {
        for (size_t t = 0; t < m.points.size(); ++t) {
            distance_[m.points[t]] = m.distance[t];
            reach_[m.points[t]] = m.reach[t];
        }
        max_ = m.max;
        worst_ = m.worst;
        changedSinceReset_.swap(m.fresh);
    }

    /// |n_q - blended normal| at every point for `surfels`, the set last measured (one projection
    /// of every point on a surface of all of them, in blocks: the distances and reaches it also
    /// gives are not kept, 12 B a point at the exchanges' memory peak).
    std::vector<float> NormalErrors(const std::vector<Surfel> &clusterSurfels) const
    {
        const int n = int(points_.size());
        std::vector<float> normalError(points_.size(), 0.f);
        std::vector<Surfel> scratch;
        const std::vector<Surfel> &surfels = Blended(clusterSurfels, scratch);
        if (n == 0 || surfels.empty()) return normalError;
        const SurfelSurface surface = WholeSurface(surfels);
        const int block = std::min(n, kNormalErrorBlock);
        std::vector<double> distance(static_cast<size_t>(block));
        std::vector<float> reach(static_cast<size_t>(block));
        for (int first = 0; first < n; first += block)
            Project(surface, nullptr, first, std::min(block, n - first), distance.data(), reach.data(),
                    normalError.data() + first);
        return normalError;
    }

    double Distance(int i) const { return distance_[i]; }
    /// Distances that differ by less are the same: the tolerance of a projection.
    double Tolerance() const { return tolerance_; }
    /// Whether point i's distance counts for Max() and Worst().
    bool Counts(int i) const { return counted_ == nullptr || (*counted_)[size_t(i)] != 0; }
    double Max() const { return max_; }
    int Worst() const { return worst_; }
    /// Max() and Worst() again, after the caller changed the flags of the points that count.
    void Recount()
    {
        max_ = 0;
        worst_ = -1;
        for (int i = 0; i < int(distance_.size()); ++i)
            if (Counts(i)) KeepWorst(distance_[i], i, max_, worst_);
    }

    /// The surfels (clusters) of `current` facing point i's side among the k nearest to the last
    /// step of its projection (the ones blended there), nearest first (ties by index).
    std::vector<int> BlendedAt(int i, const std::vector<Surfel> &currentClusters) const
    {
        std::vector<int> local;
        std::vector<Surfel> scratch;
        const std::vector<Surfel> &current = Blended(currentClusters, scratch);
        const SurfelSurface surface = LocalSurface(current, changedSinceReset_, {i}, local);
        SurfelSurface::Scratch projection;
        const vcg::Point3d q = vcg::Point3d::Construct(points_[i]);
        surface.Project(q, vcg::Point3d::Construct(normals_[i]), metric_.maxIterations, tolerance_, projection);
        std::vector<std::pair<float, int>> nearest;
        for (int j = 0; j < projection.queue.getNofElements(); ++j) {
            const int c = local[size_t(projection.queue.getIndex(j))];
            if (c >= Offset() && current[c].normal.dot(normals_[i]) > 0)
                nearest.push_back({projection.queue.getWeight(j), c - Offset()});
        }
        std::sort(nearest.begin(), nearest.end());
        std::vector<int> blended;
        for (const auto &e : nearest) blended.push_back(e.second);
        return blended;
    }

private:
    /// Index in the blended set of a cluster's surfel (FixedSurround).
    int Offset() const { return surround_ ? int(surround_->surfels.size()) : 0; }

    /// Whether entry b of the blended set is a surfel the surround hides.
    bool Hidden(size_t b) const
    {
        if (!surround_ || b < surround_->surfels.size()) return false;
        const size_t c = b - surround_->surfels.size();
        return c < surround_->hidden.size() && surround_->hidden[c] != 0;
    }

    /// The blended set for the clusters' `surfels`: the surround's first, copied into `scratch`;
    /// without a surround `surfels` themselves.
    const std::vector<Surfel> &Blended(const std::vector<Surfel> &surfels, std::vector<Surfel> &scratch) const
    {
        if (!surround_) return surfels;
        scratch = surround_->surfels;
        scratch.insert(scratch.end(), surfels.begin(), surfels.end());
        return scratch;
    }

    /// The entries of the blended set `surfels` that blend (empty without a surround: all of them).
    std::vector<int> Visible(const std::vector<Surfel> &surfels) const
    {
        std::vector<int> visible;
        if (!surround_) return visible;
        for (size_t b = 0; b < surfels.size(); ++b)
            if (!Hidden(b)) visible.push_back(int(b));
        return visible;
    }

    /// The blended surface of every surfel of `surfels` that blends (local: their indices, empty
    /// for all of them).
    SurfelSurface WholeSurface(const std::vector<Surfel> &surfels, std::vector<int> *local = nullptr) const
    {
        std::vector<int> visible = Visible(surfels);
        if (!surround_) {
            if (local) {
                local->resize(surfels.size());
                for (int c = 0; c < int(surfels.size()); ++c) (*local)[size_t(c)] = c;
            }
            return BlendedSurfaceOf(surfels, metric_);
        }
        SurfelSurface surface = BlendedSurfaceOf(surfels, visible.data(), visible.size(), metric_);
        if (local) local->swap(visible);
        return surface;
    }

    /// Takes (distance, point) as the worst if it is the first or farther: called in point order,
    /// the first point of the largest distance, the same for any thread count.
    static void KeepWorst(double distance, int point, double &max, int &worst)
    {
        if (worst < 0 || distance > max) { max = distance; worst = point; }
    }

    static bool Same(const Surfel &a, const Surfel &b)
    {
        return a.position == b.position && a.normal == b.normal && a.majorAxis == b.majorAxis &&
               a.minorAxis == b.minorAxis && a.blendScale == b.blendScale;
    }

    /// The surfels of `surfels` that differ from `current` (`changed`, ascending; extra ones on
    /// either side count; hidden ones do not) and their old and new centres (`moved`).
    void Changes(const std::vector<Surfel> &current, const std::vector<Surfel> &surfels,
                 std::vector<vcg::Point3d> &moved, std::vector<int> &changed) const
    {
        for (size_t c = 0; c < std::max(surfels.size(), current.size()); ++c) {
            if (Hidden(c)) continue;
            const bool had = c < current.size(), has = c < surfels.size();
            if (had && has && Same(current[c], surfels[c])) continue;
            if (had) moved.push_back(vcg::Point3d::Construct(current[c].position));
            if (has) moved.push_back(vcg::Point3d::Construct(surfels[c].position));
            changed.push_back(int(c));
        }
    }

    /// Flags the points whose current projection reaches one of the `moved` centres; the largest
    /// distance of the others and its first point go to untouchedMax, untouchedWorst (left as
    /// they are when every point is flagged).
    std::vector<char> Affected(const std::vector<vcg::Point3d> &moved, double &untouchedMax, int &untouchedWorst) const
    {
        const int n = int(points_.size());
        std::vector<char> affected(n, 0);
        // Many changed surfels (the crease fit's groups): their centres are looked up in a tree,
        // the candidates it finds checked as below (the same points, in a time that does not
        // grow with the number of changed surfels times the points).
        std::unique_ptr<CenterTree> movedTree;
        if (moved.size() > 64) movedTree.reset(new CenterTree(moved));
#pragma omp parallel
        {
            double localMax = 0;
            int localWorst = -1;
            std::vector<unsigned> near;
            std::vector<float> scratch;
#pragma omp for schedule(static) nowait
            for (int i = 0; i < n; ++i) {
                const vcg::Point3d p = vcg::Point3d::Construct(points_[i]);
                const double r2 = double(reach_[i]) * reach_[i];
                if (movedTree && std::isfinite(r2)) {
                    near.clear();
                    scratch.clear();
                    // Widened by the single-precision rounding of the tree's distances.
                    movedTree->Within(p, double(reach_[i]) * (1 + 1e-5) + 1e-5 * p.Norm(), near, scratch);
                    for (unsigned c : near)
                        if ((moved[c] - p).SquaredNorm() <= r2) { affected[i] = 1; break; }
                } else {
                    for (const vcg::Point3d &c : moved)
                        if ((c - p).SquaredNorm() <= r2) { affected[i] = 1; break; }
                }
                if (!affected[i] && Counts(i)) KeepWorst(distance_[i], i, localMax, localWorst);
            }
#pragma omp critical
            if (localWorst >= 0 && (untouchedWorst < 0 || localMax > untouchedMax ||
                                    (localMax == untouchedMax && localWorst < untouchedWorst))) {
                untouchedMax = localMax;
                untouchedWorst = localWorst;
            }
        }
        return affected;
    }

    /// Projects the points `m.points` on `surfels`: on a surface of the surfels near them
    /// (LocalSurface), and again on every surfel where a projection reached farther than that.
    void ProjectAffected(const std::vector<Surfel> &surfels, Measure &m) const
    {
        const int count = int(m.points.size());
        m.distance.assign(count, 0.0);
        m.reach.assign(count, 0.f);
        m.normalError.assign(count, 0.f);
        if (count == 0) return;
        std::vector<int> local;
        Project(LocalSurface(surfels, m.fresh, m.points, local), m.points.data(), 0, count, m.distance.data(),
                m.reach.data(), m.normalError.data());
        std::vector<int> beyond, beyondPoint; // projections that reached farther (indices into m.points,
                                              // points): again on every surfel
        for (int t = 0; t < count; ++t)
            if (!(m.reach[t] <= LocalRadius(m.points[t]))) { beyond.push_back(t); beyondPoint.push_back(m.points[t]); }
        if (beyond.empty()) return;
        std::vector<double> distance(beyond.size());
        std::vector<float> reach(beyond.size()), normalError(beyond.size());
        Project(WholeSurface(surfels), beyondPoint.data(), 0, int(beyond.size()), distance.data(),
                reach.data(), normalError.data());
        for (size_t b = 0; b < beyond.size(); ++b) {
            m.distance[size_t(beyond[b])] = distance[b];
            m.reach[size_t(beyond[b])] = reach[b];
            m.normalError[size_t(beyond[b])] = normalError[b];
        }
    }

    /// How far from point i a local surface holds every surfel (LocalSurface): twice the reach of
    /// its current projection, which a new one mostly stays within (checked).
    double LocalRadius(int i) const { return 2.0 * reach_[i]; }

    /// A surface of the surfels of `surfels` that projections of `points` reaching no farther than
    /// their LocalRadius involve, `local` receiving its surfels' indices in `surfels`: those the
    /// tree of the measured set finds within that radius of a point, unless listed in `fresh`
    /// (ascending: the surfels that differ from that set), and every one of `fresh`. Blended with
    /// the floor on the sizes of the whole set (MakeEllipseSurfelSurface). Every surfel instead
    /// where there are more points than surfels, a radius is infinite or fewer surfels than a
    /// projection blends are found.
    SurfelSurface LocalSurface(const std::vector<Surfel> &surfels, const std::vector<int> &fresh,
                                         const std::vector<int> &points, std::vector<int> &local) const
    {
        local.clear();
        // More points than surfels (the crease fit's trials, which move most surfels at once):
        // looking up each point's surfels costs more than the surface of them all, which gives the
        // same projections.
        bool whole = !measured_ || points.size() > surfels.size();
        std::vector<unsigned> near;
        std::vector<float> scratch;
        for (size_t p = 0; p < points.size() && !whole; ++p) {
            const double radius = LocalRadius(points[p]);
            whole = !std::isfinite(radius);
            if (whole) break;
            const vcg::Point3d q = vcg::Point3d::Construct(points_[points[p]]);
            near.clear();
            scratch.clear();
            // Widened by the single-precision rounding of the tree's distances.
            measured_->Within(q, radius * (1 + 1e-5) + 1e-5 * q.Norm(), near, scratch);
            for (unsigned t : near) {
                const int c = measuredIndex_.empty() ? int(t) : measuredIndex_[t];
                if (c < int(surfels.size()) && !std::binary_search(fresh.begin(), fresh.end(), c)) local.push_back(c);
            }
        }
        if (!whole) {
            for (int c : fresh)
                if (c < int(surfels.size()) && !Hidden(size_t(c))) local.push_back(c);
            SortUnique(local);
        }
        if (whole || local.size() < size_t(metric_.neighborCount)) return WholeSurface(surfels, &local);
        vcg::Box3d box;
        for (size_t c = 0; c < surfels.size(); ++c)
            if (!Hidden(c)) box.Add(vcg::Point3d::Construct(surfels[c].position));
        return BlendedSurfaceOf(surfels, local.data(), local.size(), metric_,
                                SmallestSurfelSize(box));
    }

    /// Projects the points `which[0, count)` (null: first .. first + count - 1) on `surface`:
    /// their distances and reaches (rounded up to floats) into distance[t], reach[t].
    void Project(const SurfelSurface &surface, const int *which, int first, int count, double *distance,
                 float *reach, float *normalError = nullptr) const
    {
#pragma omp parallel
        {
            SurfelSurface::Scratch scratch;
#pragma omp for schedule(dynamic, 256)
            for (int t = 0; t < count; ++t) {
                const int i = which ? which[t] : first + t;
                const vcg::Point3d q = vcg::Point3d::Construct(points_[i]);
                double pointReach = 0;
                const auto projection = surface.Project(q, vcg::Point3d::Construct(normals_[i]), metric_.maxIterations,
                                                        tolerance_, scratch, &pointReach);
                distance[t] = (q - projection.foot).Norm();
                if (normalError)
                    normalError[t] = float((vcg::Point3d::Construct(normals_[i]) - projection.normal).Norm());
                reach[t] = std::nextafter(float(pointReach), std::numeric_limits<float>::infinity());
            }
        }
    }

    const PointArray &points_, &normals_;
    const std::vector<char> *counted_; // null: every point counts
    const FixedSurround *surround_;    // null: none
    const BlendParams metric_;
    double tolerance_;
    std::vector<double> distance_;
    std::vector<float> reach_; // 4 bytes a point: at 20 million points the exchange's largest array
    std::unique_ptr<CenterTree> measured_;    // centres of the set Reset measured
    std::vector<int> measuredIndex_;          // ... blended-set index of each (empty: the same)
    std::vector<int> changedSinceReset_;                // surfels of the current set not as measured_ has them
    double max_ = 0;
    int worst_ = -1;
};

} // namespace gaussphere
} // namespace vcg

#endif
