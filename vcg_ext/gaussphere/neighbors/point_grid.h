// All-k-nearest-neighbours of a point set through a uniform grid, cell by cell.
//
// Why: the neighbour search dominates the resampler's time, and a per-query tree walk
// repeats the same work for neighbouring queries. Here points are sorted by the Morton
// code of their cell; each cell copies the points of its 3x3x3 block once into flat
// arrays, and every point of the cell picks its k nearest from that shared list: all
// distances in one vectorized loop, a branch-free compaction of the candidates inside a
// distance bound, and a rank count (vectorized too) that sorts them. The bound is first
// a guess from the previous point's k-th distance; if fewer than k candidates fall inside
// it, the triangle inequality's bound and then the block's margin follow, so the guess
// only ever costs time, never exactness. The block holds the true k nearest whenever the
// k-th distance is below the distance from the point to the block's boundary; otherwise
// the search grows to 5x5x5 and 7x7x7 blocks, and the few points still unresolved
// (isolated outliers) are answered by a scan of every point (up to 64 of them) or a
// kd-tree, so the result is exact and the cost stays O(N) for surface samplings,
// O(N log N) at worst. Points with more than k exact copies (one cell, or the outliers) are
// answered from their copies alone, so that M copies do not cost M^2, and the other points
// of a cell holding more than 64 times the intended count (a dense clump the cell size
// does not resolve) join the unresolved ones (scanned or kd-tree, as above).
//
// Cell size. The grid aims at about `pointsPerCell` points per occupied cell. For a
// surface the count of occupied cells scales with area / size^2, so counting the occupied
// cells D0 of a coarse grid of size c0 gives the size directly: c = c0 sqrt(m D0 / N).
#ifndef VCG_EXT_GAUSSPHERE_POINT_GRID_H
#define VCG_EXT_GAUSSPHERE_POINT_GRID_H

#include <algorithm>
#include <atomic>
#include <functional>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

#include <omp.h>

#include <vcg/space/box3.h>
#include <vcg/space/point3.h>

#include <vcg_ext/gaussphere/neighbors/morton_order.h>
#include <vcg_ext/gaussphere/support/counting_sort.h>
#include <vcg_ext/gaussphere/support/cpu_dispatch.h>
#include <vcg_ext/gaussphere/support/flat_vector.h>

#include <nanoflann.hpp>

namespace vcg {
namespace gaussphere {

/// (squared distance, index) packed so that integer order is lexicographic order: the
/// bit pattern of a non-negative float grows with its value.
inline std::uint64_t DistanceIndexKey(float squaredDistance, int id)
{
    std::uint32_t bits;
    std::memcpy(&bits, &squaredDistance, sizeof bits);
    return std::uint64_t(bits) << 32 | std::uint32_t(id);
}
inline float DistanceOfKey(std::uint64_t key)
{
    const std::uint32_t bits = std::uint32_t(key >> 32);
    float d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
}

class PointGrid
{
public:
    typedef vcg::Point3f Point3;

    static constexpr double kPointsPerCell = 8.0; ///< the default cell occupancy aimed at

    /// Precondition: finite points. `step`, if given, is called between the stages of the
    /// construction (seconds apart at tens of millions of points), e.g. to report progress; an
    /// exception it throws leaves nothing behind.
    explicit PointGrid(const PointArray &points, double pointsPerCell = kPointsPerCell,
                       const std::function<void()> &step = nullptr)
        : points_(points), maxGridCell_(int(std::min(64 * pointsPerCell, 1e6)))
    {
        const int n = int(points.size());
        if (n == 0) return;
        const auto stepDone = [&step]() { if (step) step(); };
        box_ = RobustBox(points);
        stepDone();
        FlatVector<std::pair<std::uint64_t, int>> keyed(n);
        int outside = 0;
#pragma omp parallel for schedule(static) reduction(+ : outside)
        for (int i = 0; i < n; ++i) {
            keyed[i] = {0, i};
            outside += !box_.IsIn(points[i]);
        }
        if (outside > 0) { // rare (stray points): keep the others in index order
            int kept = 0;
            for (int i = 0; i < n; ++i) {
                if (box_.IsIn(points[i])) keyed[kept++] = {0, i};
                else far_.push_back(i);
            }
            keyed.resize(kept);
        }
        const int inside = int(keyed.size());
        cellSize_ = ChooseCellSize(pointsPerCell, keyed);
#pragma omp parallel for schedule(static)
        for (int s = 0; s < inside; ++s) keyed[s].first = MortonKey(CellOf(points[keyed[s].second]));
        stepDone();
        SortByKeyStable(keyed); // index order within a cell, as the pairs were made
        stepDone();
        order_.resize(n);
#pragma omp parallel for schedule(static)
        for (int s = 0; s < inside; ++s) order_[s] = keyed[s].second;
        std::copy(far_.begin(), far_.end(), order_.begin() + inside); // outliers last, in no cell
        for (int s = 0; s < inside; ++s)
            if (s == 0 || keyed[s].first != keyed[s - 1].first) cellStart_.push_back(s);
        cellStart_.push_back(inside);
        cellKey_.reserve(cellStart_.size() - 1);
        for (size_t c = 0; c + 1 < cellStart_.size(); ++c) cellKey_.push_back(keyed[cellStart_[c]].first);
        BuildCellTable();
        BuildShellOffsets();
    }

    /// To be called after the caller has permuted the point vector the grid was built on
    /// (the same object) into Order(): point order[s] is now point s, so the grid's order
    /// becomes the identity and nothing needs sorting again.
    void PointsRenumberedToOrder()
    {
        const int inside = int(order_.size() - far_.size());
        for (int s = 0; s < int(order_.size()); ++s) order_[s] = s;
        for (size_t f = 0; f < far_.size(); ++f) far_[f] = inside + int(f);
    }

    /// Whether the search runs its AVX2 kernels: by default when the CPU has AVX2. Setting it
    /// to false runs the portable loops (same results), e.g. to test them on such a CPU.
    static bool &Avx2Kernels()
    {
        static bool on = CpuHasAvx2();
        return on;
    }

    /// Whether grids whose occupied cells span at most kMaxDenseCells cells look cells up in a
    /// dense array (the default: one load per lookup, where most of the table's probes miss on a
    /// surface) rather than in the hash table that larger grids use. Same results either way;
    /// false tests the table.
    static bool &DenseCellTables()
    {
        static bool on = true;
        return on;
    }

    /// Point indices sorted by the Morton code of their cell: a spatially coherent order.
    const IndexArray &Order() const { return order_; }
    double CellSize() const { return cellSize_; }
    int CellCount() const { return int(cellKey_.size()); }

    /// Calls sink(i, index, squaredDistance, found) for every point i with its
    /// found = min(k, N-1) nearest other points by increasing (distance, index): ties are
    /// resolved by index, so the result is unique. Runs in parallel; sink
    /// must be safe to call concurrently for different i.
    /// `progress(fraction)` is called from the calling thread now and then; when it returns
    /// false the search stops early and ForAllKNearest returns false (some points unvisited).
    template <class Sink>
    bool ForAllKNearest(int k, Sink sink, const std::function<bool(double)> &progress = nullptr) const
    {
        const int n = int(points_.size());
        k = std::max(0, std::min(k, n - 1));
        std::vector<int> unresolved;
        std::atomic<int> cellsDone(0);
        std::atomic<bool> cancelled(false);
        const int reportEvery = std::max(1, CellCount() / 100);
#pragma omp parallel
        {
            CellScratch scratch(k);
#pragma omp for schedule(dynamic, 64)
            for (int c = 0; c < CellCount(); ++c) {
                if (cancelled.load(std::memory_order_relaxed)) continue;
                const int done = ++cellsDone;
                // Only the calling thread (OpenMP's master) talks to the caller's callback.
                if (progress && omp_get_thread_num() == 0 && done % reportEvery == 0 &&
                    !progress(double(done) / CellCount()))
                    cancelled = true;
                AnswerCell(c, k, sink, scratch);
            }
#pragma omp critical
            unresolved.insert(unresolved.end(), scratch.unresolved.begin(), scratch.unresolved.end());
        }
        if (cancelled) return false;
        AnswerUnresolved(unresolved, k, sink);
        return true;
    }

private:
    struct Cell { std::int64_t x, y, z; };

    /// nanoflann's kd-tree over all the points, for the points the grid leaves unresolved: the
    /// same (distance, index) order as the grid's, so the same unique result. Its distances are
    /// the grid's float squared norms (equal distances compare equal). A subtree's bound sums,
    /// in double, per-axis float squares that are each at most a point's own, but the point's
    /// float sum may round below that by up to 2^-23 of it: subtrees are pruned only beyond
    /// the k-th distance times 1 + 2^-20, so a point that ties it is still offered. nanoflann
    /// builds and searches recursively; each level halves a side of its node's box or splits
    /// off the points at one end of it, so the depth is bounded by float precision, not by N.
    class FallbackTree
    {
    public:
        explicit FallbackTree(const PointArray &points)
            : source_{points}, tree_(3, source_, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {}

        /// The found = min(k, N-1) nearest points other than i, as sorted keys in nearest[0, found).
        int KNearest(int i, int k, std::uint64_t *nearest) const
        {
            if (k <= 0) return 0;
            NearestKeys result{i, k, nearest};
#if NANOFLANN_VERSION >= 0x150 // renamed in 1.5 (Debian 13 has 1.7, Debian 12 1.4)
            tree_.findNeighbors(result, &source_.points[i][0], nanoflann::SearchParameters());
#else
            tree_.findNeighbors(result, &source_.points[i][0], nanoflann::SearchParams());
#endif
            return result.found;
        }

    private:
        struct Source
        {
            const PointArray &points;
            size_t kdtree_get_point_count() const { return points.size(); }
            float kdtree_get_pt(std::uint32_t id, size_t axis) const { return points[id][axis]; }
            template <class Box> bool kdtree_get_bbox(Box &) const { return false; }
        };
        struct Metric
        {
            typedef float ElementType;
            typedef double DistanceType;
            const Source &source;
            explicit Metric(const Source &s) : source(s) {}
            double evalMetric(const float *q, std::uint32_t id, size_t) const
            {
                return (source.points[id] - Point3(q[0], q[1], q[2])).SquaredNorm();
            }
            template <class U, class V> double accum_dist(U a, V b, size_t) const
            {
                const float d = float(a) - float(b);
                return d * d;
            }
        };
        /// nanoflann's result set: offers the points closer than worstDist() and visits the
        /// subtrees whose bound is at most that.
        struct NearestKeys
        {
            typedef double DistanceType;
            int self, k;
            std::uint64_t *nearest;
            int found = 0;
            double bound = std::numeric_limits<double>::max();

            bool full() const { return found == k; }
            void sort() const {} // nanoflann 1.5+ calls it; nearest[] is kept sorted
            double worstDist() const { return bound; }
            bool addPoint(double d2, std::uint32_t id)
            {
                if (int(id) == self) return true;
                InsertNearest(DistanceIndexKey(float(d2), int(id)), k, nearest, found);
                if (found == k) bound = std::nextafter(double(DistanceOfKey(nearest[k - 1])) * (1 + 1.0 / (1 << 20)), HUGE_VAL);
                return true;
            }
        };

        Source source_;
        nanoflann::KDTreeSingleIndexAdaptor<Metric, Source, 3, std::uint32_t> tree_;
    };

    static constexpr int kMaxRing = 3;
    // Both costs grow linearly with N: a scan ~2.5 ns per point and query, the kd-tree's build
    // ~250 ns per point (at 20 M points a tree for a few dozen isolated ones costs seconds without
    // a progress report), so scanning pays up to about 100 queries.
    static constexpr size_t kMaxScannedQueries = 64;
    static constexpr float kGuessGrowth = 1.3f; // measured: 1.2-1.4 best on scans
    static constexpr int kMaxRanked = 96;       // candidates ranked by counting; beyond, selected
    static constexpr int kRankLanes = 8;        // candidates ranked at once
    static constexpr int kCrowdedCell = 96;     // cells with more points are checked for copies

    /// An occupied cell near the home cell: its point range and its box.
    struct NearbyCell { int begin, end; float low[3], high[3]; };

    static float Squared(double v) { return float(v * v); }

    /// Grid box: the 0.1 % to 99.9 % quantiles of each coordinate, grown by half their
    /// extent on each side. Points outside (stray scanner returns far from the model) stay
    /// out of the grid, so that they cannot stretch its cells; the kd-tree answers them.
    static vcg::Box3f RobustBox(const PointArray &points)
    {
        const size_t n = points.size();
        vcg::Box3f box;
#pragma omp parallel for schedule(static, 1)
        for (int a = 0; a < 3; ++a) {
            FlatVector<float> coordinate(n);
            for (size_t i = 0; i < n; ++i) coordinate[i] = points[i][a];
            const size_t low = n / 1000, high = n - 1 - n / 1000;
            std::nth_element(coordinate.begin(), coordinate.begin() + low, coordinate.end());
            const float lo = coordinate[low];
            std::nth_element(coordinate.begin(), coordinate.begin() + high, coordinate.end());
            const float hi = coordinate[high];
            box.min[a] = lo - 0.5f * (hi - lo);
            box.max[a] = hi + 0.5f * (hi - lo);
        }
        return box;
    }

    /// `inside`: the points in the grid box (second members).
    double ChooseCellSize(double pointsPerCell, const FlatVector<std::pair<std::uint64_t, int>> &inside) const
    {
        const double extent = std::max({double(box_.DimX()), double(box_.DimY()), double(box_.DimZ())});
        if (!(extent > 0)) return 1.0;
        const int n = int(inside.size());
        // Coarse occupancy grid: about sqrt(N)/4 cells per axis, a bitmap of at most 512^3.
        const int resolution = std::max(8, std::min(512, int(std::sqrt(double(n)) / 4)));
        const double coarse = extent / resolution * (1 + 1e-6);
        std::vector<std::uint64_t> bits((size_t(resolution) * resolution * resolution + 63) / 64, 0);
        for (const auto &entry : inside) {
            const Point3 &p = points_[entry.second];
            const size_t x = std::min(size_t(resolution - 1), size_t((p[0] - box_.min[0]) / coarse)),
                         y = std::min(size_t(resolution - 1), size_t((p[1] - box_.min[1]) / coarse)),
                         z = std::min(size_t(resolution - 1), size_t((p[2] - box_.min[2]) / coarse));
            const size_t bit = (x * resolution + y) * resolution + z;
            bits[bit / 64] |= std::uint64_t(1) << (bit % 64);
        }
        size_t occupied = 0;
        for (std::uint64_t w : bits) occupied += size_t(__builtin_popcountll(w));
        const double size = coarse * std::sqrt(pointsPerCell * double(occupied) / std::max(1, n));
        // Keep the cell count per axis within the 21 bits of the Morton key.
        return std::max(size, extent / double(1 << 20));
    }

    Cell CellOf(const Point3 &p) const
    {
        return Cell{std::int64_t((p[0] - box_.min[0]) / cellSize_), std::int64_t((p[1] - box_.min[1]) / cellSize_),
                    std::int64_t((p[2] - box_.min[2]) / cellSize_)};
    }

    static std::uint64_t Compact(std::uint64_t v)
    {
        v &= 0x1249249249249249ull;
        v = (v ^ (v >> 2)) & 0x10c30c30c30c30c3ull;
        v = (v ^ (v >> 4)) & 0x100f00f00f00f00full;
        v = (v ^ (v >> 8)) & 0x1f0000ff0000ffull;
        v = (v ^ (v >> 16)) & 0x1f00000000ffffull;
        v = (v ^ (v >> 32)) & 0x1fffff;
        return v;
    }
    static std::uint64_t MortonKey(const Cell &c)
    {
        return MortonSpread(std::uint64_t(c.x)) | MortonSpread(std::uint64_t(c.y)) << 1 | MortonSpread(std::uint64_t(c.z)) << 2;
    }
    static Cell DecodeCell(std::uint64_t key)
    {
        return Cell{std::int64_t(Compact(key)), std::int64_t(Compact(key >> 1)), std::int64_t(Compact(key >> 2))};
    }

    // From cell to cell index: a dense array over the occupied cells' bounding box when that
    // holds at most kMaxDenseCells entries (small inputs: one load per lookup instead of hash
    // probes, most of them misses on a surface), an open-addressing table of the keys otherwise.
    void BuildCellTable()
    {
        if (CellCount() > 0) {
            Cell low = DecodeCell(cellKey_[0]), high = low;
            for (std::uint64_t key : cellKey_) {
                const Cell c = DecodeCell(key);
                low = {std::min(low.x, c.x), std::min(low.y, c.y), std::min(low.z, c.z)};
                high = {std::max(high.x, c.x), std::max(high.y, c.y), std::max(high.z, c.z)};
            }
            // Each side within the cap before the product (no overflow), and at most 64 cells per
            // occupied one (a surface gives ~20: a scattered input keeps the hash table).
            const std::int64_t side[3] = {high.x - low.x + 1, high.y - low.y + 1, high.z - low.z + 1};
            const bool sidesFit = side[0] <= kMaxDenseCells && side[1] <= kMaxDenseCells && side[2] <= kMaxDenseCells &&
                                  side[0] * side[1] <= kMaxDenseCells;
            const std::int64_t volume = sidesFit ? side[0] * side[1] * side[2] : kMaxDenseCells + 1;
            if (DenseCellTables() && volume <= kMaxDenseCells && volume <= 64 * std::int64_t(CellCount())) {
                denseLow_ = low;
                denseSize_ = {side[0], side[1], side[2]};
                dense_.resize(size_t(volume));
                std::fill(dense_.begin(), dense_.end(), -1);
                for (int c = 0; c < CellCount(); ++c) dense_[size_t(DenseIndex(Offset(DecodeCell(cellKey_[c]))))] = c;
                return;
            }
        }
        size_t size = 16;
        while (size < 2 * cellKey_.size()) size *= 2;
        table_.assign(size, -1);
        for (int c = 0; c < CellCount(); ++c) {
            size_t slot = Hash(cellKey_[c]) & (size - 1);
            while (table_[slot] >= 0) slot = (slot + 1) & (size - 1);
            table_[slot] = c;
        }
    }
    static size_t Hash(std::uint64_t key) { return size_t((key * 0x9E3779B97F4A7C15ull) >> 17); }
    /// A cell relative to the dense array's lowest corner, and its entry there.
    Cell Offset(const Cell &c) const { return Cell{c.x - denseLow_.x, c.y - denseLow_.y, c.z - denseLow_.z}; }
    std::int64_t DenseIndex(const Cell &offset) const { return (offset.x * denseSize_.y + offset.y) * denseSize_.z + offset.z; }
    int FindCell(const Cell &c) const
    {
        if (!dense_.empty()) {
            const Cell d = Offset(c);
            if (d.x < 0 || d.y < 0 || d.z < 0 || d.x >= denseSize_.x || d.y >= denseSize_.y || d.z >= denseSize_.z) return -1;
            return dense_[size_t(DenseIndex(d))];
        }
        const std::int64_t limit = std::int64_t(1) << 21;
        if (c.x < 0 || c.y < 0 || c.z < 0 || c.x >= limit || c.y >= limit || c.z >= limit) return -1;
        const std::uint64_t key = MortonKey(c);
        for (size_t slot = Hash(key) & (table_.size() - 1);; slot = (slot + 1) & (table_.size() - 1)) {
            const int found = table_[slot];
            if (found < 0) return -1;
            if (cellKey_[found] == key) return found;
        }
    }

    /// The occupied cells at Chebyshev distance exactly `ring` from home (ring 1 includes
    /// home itself), nearest to home first: home, then cells sharing a face, an edge, a corner.
    void CollectShell(const Cell &home, int ring, std::vector<NearbyCell> &out) const
    {
        for (const std::array<int, 4> &o : shellOffsets_[ring]) {
            const Cell cell{home.x + o[1], home.y + o[2], home.z + o[3]};
            const int c = FindCell(cell);
            if (c < 0) continue;
            NearbyCell nc;
            nc.begin = cellStart_[c];
            nc.end = cellStart_[c + 1];
            const std::int64_t xyz[3] = {cell.x, cell.y, cell.z};
            for (int a = 0; a < 3; ++a) {
                nc.low[a] = float(box_.min[a] + xyz[a] * cellSize_);
                nc.high[a] = float(box_.min[a] + (xyz[a] + 1) * cellSize_);
            }
            out.push_back(nc);
        }
    }

    /// Cell offsets of each shell, by increasing length: (squared length, dx, dy, dz).
    void BuildShellOffsets()
    {
        for (int ring = 1; ring <= kMaxRing; ++ring) {
            const int inner = ring == 1 ? -1 : ring - 1;
            for (int dx = -ring; dx <= ring; ++dx)
                for (int dy = -ring; dy <= ring; ++dy)
                    for (int dz = -ring; dz <= ring; ++dz)
                        if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) > inner)
                            shellOffsets_[ring].push_back({dx * dx + dy * dy + dz * dz, dx, dy, dz});
            std::sort(shellOffsets_[ring].begin(), shellOffsets_[ring].end());
        }
    }

    /// The points of the 3x3x3 block around a cell, as flat arrays for a vectorized scan.
    struct Block
    {
        std::vector<float> x, y, z, d2;
        std::vector<int> id;
        std::vector<std::uint64_t> keys;
        std::vector<float> nearD2;
        std::vector<int> nearId;
    };

    /// One thread's buffers for the cells it answers (ForAllKNearest).
    struct CellScratch
    {
        explicit CellScratch(int k) : idx(k + 1), d2(k + 1), nearest(k + 1) {}
        std::vector<int> idx;
        std::vector<float> d2;
        std::vector<std::uint64_t> nearest;
        std::vector<NearbyCell> shell[kMaxRing + 1];
        Block block;
        float lastKth = 0;           // k-th squared distance of the last point answered
        std::vector<int> unresolved; // points left to AnswerUnresolved
        std::vector<char> isCopy;    // per slot of a crowded cell: answered by AnswerCopies
        std::vector<int> byPosition; // AnswerCopies' scratch
    };

    /// Calls sink for the points of cell c that the grid answers (their copies, then the others
    /// through the block and, if need be, the rings around it); the rest go to t.unresolved.
    template <class Sink>
    void AnswerCell(int c, int k, Sink &sink, CellScratch &t) const
    {
        const Cell home = DecodeCell(cellKey_[c]);
        for (int ring = 1; ring <= kMaxRing; ++ring) t.shell[ring].clear();
        CollectShell(home, 1, t.shell[1]);
        int gathered = 1; // rings whose cells are in `shell`
        GatherBlock(t.shell[1], t.block);
        // The k-th distance of the previous point of this cell bounds this one's
        // (triangle inequality), so most candidates are dropped by one comparison.
        float previousKth = -1;
        Point3 previous(0, 0, 0); // read only once previousKth is set
        const int first = cellStart_[c], size = cellStart_[c + 1] - first;
        const bool copies = size > kCrowdedCell && k > 0 &&
                            AnswerCopies(&order_[first], size, k, sink, t.isCopy, t.byPosition, t.idx.data(), t.d2.data()) > 0;
        const bool denseClump = size > maxGridCell_ && k > 0; // the grid would scan it per point
        for (int s = first; s < first + size; ++s) {
            if (copies && t.isCopy[s - first]) continue;
            const int i = order_[s];
            if (denseClump) {
                t.unresolved.push_back(i);
                continue;
            }
            const Point3 &q = points_[i];
            const float margin2 = Squared(Margin(i, home, 1));
            int found = 0;
            if (k > 0) found = SearchBlock(t.block, q, i, k, margin2, previousKth, previous, t.lastKth, t.nearest.data());
            if (found < k && !SearchRings(home, i, k, t.shell, gathered, t.nearest.data(), found)) {
                t.unresolved.push_back(i); // an isolated point: answered by AnswerUnresolved
                previousKth = -1;
                continue;
            }
            UnpackKeys(t.nearest.data(), found, t.idx.data(), t.d2.data());
            previousKth = k > 0 ? t.d2[k - 1] : -1;
            t.lastKth = std::max(previousKth, 0.f);
            previous = q;
            sink(i, t.idx.data(), t.d2.data(), found);
        }
    }

    /// The k nearest of point i (at q) among the block's points, into `nearest`; returns how many
    /// were found, k unless the block holds fewer than k within its margin (margin2, squared).
    /// previousKth (negative: none) and `previous` are the last point of this cell answered,
    /// lastKth the thread's last k-th squared distance.
    static int SearchBlock(Block &block, const Point3 &q, int i, int k, float margin2, float previousKth,
                           const Point3 &previous, float lastKth, std::uint64_t *nearest)
    {
        int found = 0;
        float bound = margin2;
        if (previousKth >= 0) {
            const float reach = std::sqrt(previousKth) + (q - previous).Norm();
            bound = std::min(bound, reach * reach * 1.0001f);
        }
        // A guess from the last point first (usually right), then the bounds
        // that cannot fail while the block holds k points near enough.
        const float guess = std::min(bound, lastKth * kGuessGrowth);
        MeasureBlock(block, q);
        if (guess < bound) found = SelectNearest(block, i, k, guess, nearest);
        if (found < k) found = SelectNearest(block, i, k, bound, nearest);
        if (found < k && bound < margin2) found = SelectNearest(block, i, k, margin2, nearest);
        return found;
    }

    /// The k nearest of point i through the rings of cells around home, widened up to kMaxRing
    /// (shell[ring] collected as needed, `gathered` the rings collected), into `nearest` and
    /// `found`. Returns false when they are not known to be exact there (an isolated point).
    bool SearchRings(const Cell &home, int i, int k, std::vector<NearbyCell> *shell, int &gathered,
                     std::uint64_t *nearest, int &found) const
    {
        int ring = 1;
        found = 0;
        for (;; ++ring) {
            if (ring > gathered) CollectShell(home, ring, shell[gathered = ring]);
            ScanShell(shell[ring], i, k, nearest, found);
            if ((found == k && DistanceOfKey(nearest[k - 1]) < Squared(Margin(i, home, ring))) ||
                ring == kMaxRing)
                break;
        }
        return !(found < k || DistanceOfKey(nearest[k - 1]) >= Squared(Margin(i, home, ring)));
    }

    /// Calls sink for the points the grid left (`unresolved`, any order) and those outside the
    /// grid box: copies of one position first (AnswerCopies), the rest by a scan of every point
    /// or the kd-tree.
    template <class Sink>
    void AnswerUnresolved(std::vector<int> &unresolved, int k, Sink &sink) const
    {
        const int n = int(points_.size());
        unresolved.insert(unresolved.end(), far_.begin(), far_.end());
        if (unresolved.empty()) return;
        std::sort(unresolved.begin(), unresolved.end());
        if (int(unresolved.size()) > k && k > 0) { // copies of a far point are far too: all in the list
            std::vector<char> isCopy;
            std::vector<int> byPosition, idx(k);
            std::vector<float> d2(k);
            if (AnswerCopies(unresolved.data(), int(unresolved.size()), k, sink, isCopy, byPosition, idx.data(), d2.data()) > 0) {
                size_t kept = 0;
                for (size_t u = 0; u < unresolved.size(); ++u)
                    if (!isCopy[u]) unresolved[kept++] = unresolved[u];
                unresolved.resize(kept);
            }
        }
        // A few dozen isolated points are cheaper to answer by a scan of every point than
        // by building a tree over all of them (see kMaxScannedQueries).
        const bool scanAll = unresolved.size() <= kMaxScannedQueries;
        std::unique_ptr<FallbackTree> tree(scanAll ? nullptr : new FallbackTree(points_));
#pragma omp parallel
        {
            std::vector<int> idx(k);
            std::vector<float> d2(k);
            std::vector<std::uint64_t> nearest(k + 1);
#pragma omp for schedule(dynamic, 1)
            for (int u = 0; u < int(unresolved.size()); ++u) {
                const int i = unresolved[u];
                int found = 0;
                if (tree) {
                    found = tree->KNearest(i, k, nearest.data());
                } else {
                    for (int j = 0; j < n; ++j)
                        if (j != i) InsertNearest(DistanceIndexKey((points_[j] - points_[i]).SquaredNorm(), j), k, nearest.data(), found);
                }
                UnpackKeys(nearest.data(), found, idx.data(), d2.data());
                sink(i, idx.data(), d2.data(), found);
            }
        }
    }

    void GatherBlock(const std::vector<NearbyCell> &cells, Block &block) const
    {
        size_t size = 0;
        for (const NearbyCell &cell : cells) size += size_t(cell.end - cell.begin);
        block.x.resize(size);
        block.y.resize(size);
        block.z.resize(size);
        block.id.resize(size);
        size_t t = 0;
        for (const NearbyCell &cell : cells)
            for (int s = cell.begin; s < cell.end; ++s, ++t) {
                const Point3 &p = points_[order_[s]];
                block.x[t] = p[0];
                block.y[t] = p[1];
                block.z[t] = p[2];
                block.id[t] = order_[s];
            }
        block.d2.resize(block.x.size());
        block.keys.resize(block.x.size());
        // Room for RankCandidates' reads of whole groups of eight past the candidates.
        block.nearD2.resize(block.x.size() + kRankLanes);
        block.nearId.resize(block.x.size());
    }

    /// Squared distances from q to every point of the block, into block.d2.
    static void MeasureBlock(Block &block, const Point3 &q)
    {
        const int m = int(block.x.size());
        const float *x = block.x.data(), *y = block.y.data(), *z = block.z.data();
        float *d2 = block.d2.data();
        int j = 0;
#ifdef GAUSSPHERE_X86_DISPATCH
        if (Avx2Kernels()) j = MeasureAvx2(x, y, z, m, q, d2);
#endif
        const float qx = q[0], qy = q[1], qz = q[2];
        for (; j < m; ++j) { // vectorized (the rest, or all without AVX2)
            const float dx = x[j] - qx, dy = y[j] - qy, dz = z[j] - qz;
            d2[j] = dx * dx + dy * dy + dz * dz;
        }
    }

#ifdef GAUSSPHERE_X86_DISPATCH
    /// MeasureBlock's loop eight points at a time, with the same float operations in the same
    /// order: the same distances. (A build that enables FMA, e.g. -march=native, could contract
    /// the two loops differently; the project's build does not.) Returns where it stopped.
    __attribute__((target("avx2"))) static int MeasureAvx2(const float *x, const float *y, const float *z, int m,
                                                         const Point3 &q, float *d2)
    {
        const __m256 qx = _mm256_set1_ps(q[0]), qy = _mm256_set1_ps(q[1]), qz = _mm256_set1_ps(q[2]);
        int j = 0;
        for (; j + 8 <= m; j += 8) {
            const __m256 dx = _mm256_sub_ps(_mm256_loadu_ps(x + j), qx);
            const __m256 dy = _mm256_sub_ps(_mm256_loadu_ps(y + j), qy);
            const __m256 dz = _mm256_sub_ps(_mm256_loadu_ps(z + j), qz);
            const __m256 sum = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)), _mm256_mul_ps(dz, dz));
            _mm256_storeu_ps(d2 + j, sum);
        }
        return j;
    }

    /// The compaction of SelectNearest, eight candidates at a time: the lanes inside the bound
    /// are moved to the front by a permutation looked up from their mask. Same result as the
    /// scalar loop; used when the CPU has AVX2 (checked at run time, so the build stays generic).
    /// It spares the scalar loop's unpredictable branch per candidate. Handles whole groups of
    /// eight and returns where it stopped.
    __attribute__((target("avx2"))) static int CompactAvx2(const float *d2, const int *id, int m, int i,
                                                         float bound, float *near, int *nearId, int &inside)
    {
        // Per 8-bit mask: the positions of its set bits, in order, one byte each.
        static const std::array<std::uint64_t, 256> frontOf = [] {
            std::array<std::uint64_t, 256> table{};
            for (unsigned mask = 0; mask < 256; ++mask)
                for (unsigned bit = 0, slot = 0; bit < 8; ++bit)
                    if (mask >> bit & 1) table[mask] |= std::uint64_t(bit) << (8 * slot++);
            return table;
        }();
        const __m256 limit = _mm256_set1_ps(bound);
        const __m256i self = _mm256_set1_epi32(i);
        int j = 0, kept = inside; // a local: `inside` could alias the stores, reloaded each step
        for (; j + 8 <= m; j += 8) {
            const __m256 distances = _mm256_loadu_ps(d2 + j);
            const __m256i ids = _mm256_loadu_si256(reinterpret_cast<const __m256i *>(id + j));
            const __m256 isSelf = _mm256_castsi256_ps(_mm256_cmpeq_epi32(ids, self));
            const unsigned mask =
                unsigned(_mm256_movemask_ps(_mm256_andnot_ps(isSelf, _mm256_cmp_ps(distances, limit, _CMP_LT_OQ))));
            const __m256i order = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(static_cast<long long>(frontOf[mask])));
            // kept <= j: the eight stores stay within the arrays' first m entries.
            _mm256_storeu_ps(near + kept, _mm256_permutevar8x32_ps(distances, order));
            _mm256_storeu_si256(reinterpret_cast<__m256i *>(nearId + kept), _mm256_permutevar8x32_epi32(ids, order));
            kept += __builtin_popcount(mask);
        }
        inside = kept;
        return j;
    }
#endif

    /// Ranks the candidates near[0, inside) by counting, for each, the candidates closer than it:
    /// the ones ranked below k go to nearest[rank]. Eight candidates at a time against every
    /// other (the counts of a group stay in vector lanes: no horizontal sums). Returns true
    /// when counting could not order the k nearest: two of them, or the k-th and the next,
    /// are equally far (the caller then sorts keys). Equal distances share a count, the first
    /// rank of their run, so they either put more than k candidates below k or, if exactly
    /// k, make the ranks below k sum to less than 0 + 1 + ... + (k-1): checking the count and
    /// the sum costs less than counting equal distances. near[] must be readable up to the
    /// next multiple of kRankLanes; nearest holds k + 1 keys, the last one scratch.
    static bool RankCandidates(const float *near, const int *nearId, int inside, int k, std::uint64_t *nearest)
    {
        int ranked = 0, rankSum = 0;
        for (int a0 = 0; a0 < inside; a0 += kRankLanes) {
            int below[kRankLanes] = {};
            for (int b = 0; b < inside; ++b)
                for (int l = 0; l < kRankLanes; ++l) below[l] += int(near[b] < near[a0 + l]); // vectorized
            const int lanes = std::min(int(kRankLanes), inside - a0); // a copy: no odr-use (C++14)
            for (int l = 0; l < lanes; ++l) {
                const int rank = std::min(below[l], k); // k: the scratch slot
                nearest[rank] = DistanceIndexKey(near[a0 + l], nearId[a0 + l]);
                ranked += int(rank < k);
                rankSum += rank < k ? rank : 0;
            }
        }
        return !RanksDistinct(k, ranked, rankSum);
    }
    static bool RanksDistinct(int k, int ranked, int rankSum) { return ranked == k && rankSum == k * (k - 1) / 2; }

#ifdef GAUSSPHERE_X86_DISPATCH
    /// RankCandidates with eight lanes of AVX2: eight candidates are counted at once, and the
    /// ranks are stored without a branch (ranks of k and beyond land in a scratch slot); ties are
    /// detected by the count and sum checks, which cost less than counting equal distances.
    __attribute__((target("avx2"))) static bool RankAvx2(const float *near, const int *nearId, int inside, int k,
                                                       std::uint64_t *nearest)
    {
        const __m256i kk = _mm256_set1_epi32(k), laneIndex = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
        __m256i ranked = _mm256_setzero_si256(), rankSum = _mm256_setzero_si256();
        for (int a0 = 0; a0 < inside; a0 += kRankLanes) {
            const __m256 group = _mm256_loadu_ps(near + a0);
            __m256i below = _mm256_setzero_si256();
            // A true comparison is all ones (-1): subtracting it counts.
            for (int b = 0; b < inside; ++b)
                below = _mm256_sub_epi32(below, _mm256_castps_si256(_mm256_cmp_ps(_mm256_broadcast_ss(near + b), group, _CMP_LT_OQ)));
            // Ranks of k and beyond all land in the scratch slot nearest[k]: no branch to mispredict.
            alignas(32) int rank[kRankLanes];
            _mm256_store_si256(reinterpret_cast<__m256i *>(rank), _mm256_min_epi32(below, kk));
            const int lanes = std::min(int(kRankLanes), inside - a0); // a copy: no odr-use (C++14)
            for (int l = 0; l < lanes; ++l) nearest[rank[l]] = DistanceIndexKey(near[a0 + l], nearId[a0 + l]);
            const __m256i top = _mm256_and_si256(_mm256_cmpgt_epi32(kk, below), _mm256_cmpgt_epi32(_mm256_set1_epi32(lanes), laneIndex));
            ranked = _mm256_sub_epi32(ranked, top);
            rankSum = _mm256_add_epi32(rankSum, _mm256_and_si256(top, below));
        }
        alignas(32) int count[kRankLanes], sum[kRankLanes];
        _mm256_store_si256(reinterpret_cast<__m256i *>(count), ranked);
        _mm256_store_si256(reinterpret_cast<__m256i *>(sum), rankSum);
        int totalCount = 0, totalSum = 0;
        for (int l = 0; l < kRankLanes; ++l) { totalCount += count[l]; totalSum += sum[l]; }
        return !RanksDistinct(k, totalCount, totalSum);
    }
#endif

    /// The k nearest of the block's points (point i itself excluded, block.d2 measured from
    /// it) among those closer than sqrt(bound), by increasing (distance, index) into
    /// `nearest`. Returns k, or the number of such points when fewer than k are: the caller
    /// then widens the bound. Exact whatever the bound: if k points lie inside it, the k
    /// nearest are among them. `nearest` holds k + 1 keys (the last one scratch).
    static int SelectNearest(Block &block, int i, int k, float bound, std::uint64_t *nearest)
    {
        const int m = int(block.x.size());
        const float *d2 = block.d2.data();
        const int *id = block.id.data();
        float *near = block.nearD2.data();
        int *nearId = block.nearId.data();
        int inside = 0, j = 0;
#ifdef GAUSSPHERE_X86_DISPATCH
        const bool avx2 = Avx2Kernels();
        if (avx2) j = CompactAvx2(d2, id, m, i, bound, near, nearId, inside);
#endif
        for (; j < m; ++j) { // branch-free compaction (the rest, or all without AVX2)
            near[inside] = d2[j];
            nearId[inside] = id[j];
            inside += int(d2[j] < bound) & int(id[j] != i);
        }
        if (inside < k) return inside;
        // Rank by distance with a branch-free (vectorized) count, quadratic in `inside`:
        // only for the usual few dozen candidates. Many (coincident points) or equal
        // distances (regular grids) fall back to selecting and sorting (distance, index) keys.
        bool select = inside > kMaxRanked;
        if (!select) {
#ifdef GAUSSPHERE_X86_DISPATCH
            select = avx2 ? RankAvx2(near, nearId, inside, k, nearest) : RankCandidates(near, nearId, inside, k, nearest);
#else
            select = RankCandidates(near, nearId, inside, k, nearest);
#endif
        }
        if (!select) return k;
        std::uint64_t *keys = block.keys.data();
        for (int a = 0; a < inside; ++a) keys[a] = DistanceIndexKey(near[a], nearId[a]);
        if (inside > k) std::nth_element(keys, keys + (k - 1), keys + inside);
        std::sort(keys, keys + k);
        std::copy(keys, keys + k, nearest);
        return k;
    }

    /// Answers at once the points of ids[0, count) (ascending indices) that share their exact
    /// position with at least k others: their k nearest are the k lowest-index copies, at
    /// distance 0, which no other point precedes in (distance, index) order. Otherwise M copies
    /// of one position (scanners write invalid returns as the origin) would each scan all M.
    /// Precondition: every copy of a point of ids is in ids. (Distinct points closer than
    /// ~1e-19, whose squared distance underflows to 0, are not copies here: the only case where
    /// the order differs from brute force's.) Sets isCopy[t] for each ids[t]
    /// answered, calls sink for it, and returns how many were answered. idx, d2: k entries.
    template <class Sink>
    int AnswerCopies(const int *ids, int count, int k, Sink &sink, std::vector<char> &isCopy,
                     std::vector<int> &byPosition, int *idx, float *d2) const
    {
        byPosition.resize(count);
        for (int t = 0; t < count; ++t) byPosition[t] = t;
        auto position = [&](int t) { const Point3 &p = points_[ids[t]]; return std::make_tuple(p[0], p[1], p[2]); };
        std::sort(byPosition.begin(), byPosition.end(), [&](int a, int b) {
            return position(a) < position(b) || (position(a) == position(b) && a < b);
        });
        isCopy.assign(count, 0);
        int answered = 0;
        for (int run = 0, end; run < count; run = end) {
            for (end = run + 1; end < count && position(byPosition[end]) == position(byPosition[run]);) ++end;
            if (end - run <= k) continue; // fewer than k other copies: the search answers
            std::fill(d2, d2 + k, 0.f);
            for (int t = run; t < end; ++t) {
                int found = 0;
                for (int u = run; found < k; ++u)
                    if (u != t) idx[found++] = ids[byPosition[u]];
                isCopy[byPosition[t]] = 1;
                sink(ids[byPosition[t]], idx, d2, k);
            }
            answered += end - run;
        }
        return answered;
    }

    /// Adds the points of `cells` to the running k-nearest list of point i, skipping the
    /// cells whose box lies farther than the current k-th distance.
    void ScanShell(const std::vector<NearbyCell> &cells, int i, int k, std::uint64_t *nearest, int &found) const
    {
        const Point3 &q = points_[i];
        // `cells` come nearest first (CollectShell); a cell whose box lies beyond the
        // current k-th distance holds no better point.
        for (const NearbyCell &cell : cells) {
            if (found == k) {
                float boxDistance = 0;
                for (int a = 0; a < 3; ++a) {
                    const float d = std::max({cell.low[a] - q[a], 0.f, q[a] - cell.high[a]});
                    boxDistance += d * d;
                }
                if (boxDistance > DistanceOfKey(nearest[k - 1])) continue;
            }
            for (int s = cell.begin; s < cell.end; ++s) {
                const std::uint64_t key = DistanceIndexKey((points_[order_[s]] - q).SquaredNorm(), order_[s]);
                if (order_[s] != i) InsertNearest(key, k, nearest, found);
            }
        }
    }

    /// Splits the keys nearest[0, found) into point indices and squared distances.
    static void UnpackKeys(const std::uint64_t *nearest, int found, int *idx, float *d2)
    {
        for (int t = 0; t < found; ++t) {
            d2[t] = DistanceOfKey(nearest[t]);
            idx[t] = int(std::uint32_t(nearest[t]));
        }
    }

    /// Inserts key into the sorted list nearest[0, found) of at most k keys.
    static void InsertNearest(std::uint64_t key, int k, std::uint64_t *nearest, int &found)
    {
        if (k <= 0 || (found == k && key >= nearest[k - 1])) return;
        int pos = found < k ? found++ : k - 1;
        while (pos > 0 && key < nearest[pos - 1]) { nearest[pos] = nearest[pos - 1]; --pos; }
        nearest[pos] = key;
    }

    /// How far the search around point i is known to be complete: the boundary of the
    /// block within `ring` of home, and of the grid box when points lie outside it.
    double Margin(int i, const Cell &home, int ring) const
    {
        double margin = BlockMargin(i, home, ring);
        if (!far_.empty())
            for (int a = 0; a < 3; ++a)
                margin = std::min({margin, double(points_[i][a] - box_.min[a]), double(box_.max[a] - points_[i][a])});
        return std::max(0.0, margin);
    }

    /// Distance from point i to the boundary of the block of cells within `ring` of home.
    double BlockMargin(int i, const Cell &home, int ring) const
    {
        const Point3 &p = points_[i];
        double margin = std::numeric_limits<double>::max();
        const std::int64_t h[3] = {home.x, home.y, home.z};
        for (int a = 0; a < 3; ++a) {
            const double low = box_.min[a] + (h[a] - ring + 1) * cellSize_ - cellSize_;
            const double high = box_.min[a] + (h[a] + ring + 1) * cellSize_;
            margin = std::min({margin, p[a] - low, high - p[a]});
        }
        return std::max(0.0, margin);
    }

    const PointArray &points_;
    vcg::Box3f box_;
    double cellSize_ = 1.0;
    int maxGridCell_; // cells with more points go to the kd-tree, after their copies
    IndexArray order_;
    std::vector<int> far_;          // points outside the grid box
    std::vector<int> cellStart_;
    std::vector<std::uint64_t> cellKey_;
    std::vector<int> table_;
    // 8 MB at most: the dragon's 437,645 points (1.2 M entries, 51,000 occupied cells) are under
    // it, a million surface points (~2.7 M) are not, so at scale the hash table's memory per
    // point applies.
    static constexpr std::int64_t kMaxDenseCells = std::int64_t(1) << 21;
    Cell denseLow_{0, 0, 0}, denseSize_{0, 0, 0};
    IndexArray dense_; // a FlatVector: freeing a heap block this large would raise glibc's mmap threshold
    std::vector<std::array<int, 4>> shellOffsets_[kMaxRing + 1];
};

} // namespace gaussphere
} // namespace vcg

#endif
