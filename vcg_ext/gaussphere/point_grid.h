// All-k-nearest-neighbours of a point set through a uniform grid, cell by cell.
//
// Why: the neighbour search dominates the resampler's time, and a per-query tree walk
// repeats the same work for neighbouring queries. Here points are sorted by the Morton
// code of their cell; each cell gathers the points of its 3x3x3 block once, and every
// point of the cell picks its k nearest from that shared list. The block holds the true
// k nearest whenever the k-th distance does not exceed the distance from the point to the
// block's boundary; otherwise the block grows to 5x5x5 and 7x7x7, and the few points still
// unresolved (isolated outliers) are answered by a kd-tree, so the result is exact and the
// cost stays O(N) for surface samplings, O(N log N) at worst.
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
#include <utility>
#include <vector>

#include <omp.h>

#include <vcg/space/box3.h>
#include <vcg/space/point3.h>

#include "point_kdtree.h"

namespace vcg {
namespace gaussphere {

/// The low 21 bits of v moved to every third bit: interleaving three of these gives a
/// 63-bit Morton (Z-order) code.
inline std::uint64_t MortonSpread(std::uint64_t v)
{
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

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

    /// Precondition: finite points.
    explicit PointGrid(const std::vector<Point3> &points, double pointsPerCell = 6.0)
        : points_(points)
    {
        const int n = int(points.size());
        if (n == 0) return;
        box_ = RobustBox(points);
        std::vector<std::pair<std::uint64_t, int>> keyed;
        keyed.reserve(n);
        for (int i = 0; i < n; ++i) {
            if (box_.IsIn(points[i])) keyed.push_back({0, i});
            else far_.push_back(i);
        }
        const int inside = int(keyed.size());
        cellSize_ = ChooseCellSize(pointsPerCell, keyed);
#pragma omp parallel for schedule(static)
        for (int s = 0; s < inside; ++s) keyed[s].first = MortonKey(CellOf(points[keyed[s].second]));
        std::sort(keyed.begin(), keyed.end());
        order_.resize(n);
        for (int s = 0; s < inside; ++s) order_[s] = keyed[s].second;
        std::copy(far_.begin(), far_.end(), order_.begin() + inside); // outliers last, in no cell
        sortedX_.resize(inside);
        sortedY_.resize(inside);
        sortedZ_.resize(inside);
        for (int s = 0; s < inside; ++s) {
            sortedX_[s] = points[order_[s]][0];
            sortedY_[s] = points[order_[s]][1];
            sortedZ_[s] = points[order_[s]][2];
        }
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

    /// Point indices sorted by the Morton code of their cell: a spatially coherent order.
    const std::vector<int> &Order() const { return order_; }
    double CellSize() const { return cellSize_; }
    int CellCount() const { return int(cellKey_.size()); }

    /// Calls sink(i, index, squaredDistance, found) for every point i with its
    /// found = min(k, N-1) nearest other points by increasing (distance, index): ties are
    /// resolved by index, as in PointKdTree, so the result is unique. Runs in parallel; sink
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
            std::vector<int> idx(k + 1);
            std::vector<float> d2(k + 1);
            std::vector<std::uint64_t> nearest(k + 1);
            std::vector<NearbyCell> shell[kMaxRing + 1];
            std::vector<int> localUnresolved;
#pragma omp for schedule(dynamic, 64)
            for (int c = 0; c < CellCount(); ++c) {
                if (cancelled.load(std::memory_order_relaxed)) continue;
                const int done = ++cellsDone;
                // Only the calling thread (OpenMP's master) talks to the caller's callback.
                if (progress && omp_get_thread_num() == 0 && done % reportEvery == 0 &&
                    !progress(double(done) / CellCount()))
                    cancelled = true;
                const Cell home = DecodeCell(cellKey_[c]);
                for (int ring = 1; ring <= kMaxRing; ++ring) shell[ring].clear();
                CollectShell(home, 1, shell[1]);
                int gathered = 1; // rings whose cells are in `shell`
                for (int s = cellStart_[c]; s < cellStart_[c + 1]; ++s) {
                    const int i = order_[s];
                    int found = 0;
                    int ring = 1;
                    for (;; ++ring) {
                        if (ring > gathered) CollectShell(home, ring, shell[gathered = ring]);
                        ScanShell(shell[ring], i, k, nearest.data(), found);
                        const bool complete = k == 0 || (found == k && DistanceOfKey(nearest[k - 1]) < Squared(Margin(i, home, ring)));
                        if (complete || ring == kMaxRing) break;
                    }
                    if (k > 0 && (found < k || DistanceOfKey(nearest[k - 1]) >= Squared(Margin(i, home, ring)))) {
                        localUnresolved.push_back(i); // an isolated point: the kd-tree answers it
                        continue;
                    }
                    for (int t = 0; t < found; ++t) {
                        d2[t] = DistanceOfKey(nearest[t]);
                        idx[t] = int(std::uint32_t(nearest[t]));
                    }
                    sink(i, idx.data(), d2.data(), found);
                }
            }
#pragma omp critical
            unresolved.insert(unresolved.end(), localUnresolved.begin(), localUnresolved.end());
        }
        if (cancelled) return false;
        unresolved.insert(unresolved.end(), far_.begin(), far_.end());
        if (unresolved.empty()) return true;
        std::sort(unresolved.begin(), unresolved.end());
        const PointKdTree tree(points_);
#pragma omp parallel
        {
            std::vector<int> idx(k);
            std::vector<float> d2(k);
#pragma omp for schedule(dynamic, 16)
            for (int u = 0; u < int(unresolved.size()); ++u) {
                const int i = unresolved[u];
                const int found = tree.KNearest(points_[i], k, i, idx.data(), d2.data());
                sink(i, idx.data(), d2.data(), found);
            }
        }
        return true;
    }

private:
    struct Cell { std::int64_t x, y, z; };

    static constexpr int kMaxRing = 3;

    /// An occupied cell near the home cell: its point range and its box.
    struct NearbyCell { int begin, end; float low[3], high[3]; };

    static float Squared(double v) { return float(v * v); }

    /// Grid box: the 0.1 % to 99.9 % quantiles of each coordinate, grown by half their
    /// extent on each side. Points outside (stray scanner returns far from the model) stay
    /// out of the grid, so that they cannot stretch its cells; the kd-tree answers them.
    static vcg::Box3f RobustBox(const std::vector<Point3> &points)
    {
        const size_t n = points.size();
        vcg::Box3f box;
        std::vector<float> coordinate(n);
        for (int a = 0; a < 3; ++a) {
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
    double ChooseCellSize(double pointsPerCell, const std::vector<std::pair<std::uint64_t, int>> &inside) const
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

    // Open-addressing table from cell key to cell index.
    void BuildCellTable()
    {
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
    int FindCell(const Cell &c) const
    {
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
                const float dx = sortedX_[s] - q[0], dy = sortedY_[s] - q[1], dz = sortedZ_[s] - q[2];
                const std::uint64_t key = DistanceIndexKey(dx * dx + dy * dy + dz * dz, order_[s]);
                if (found == k && key >= nearest[k - 1]) continue;
                if (order_[s] == i) continue;
                int pos = found < k ? found++ : k - 1;
                while (pos > 0 && key < nearest[pos - 1]) { nearest[pos] = nearest[pos - 1]; --pos; }
                nearest[pos] = key;
            }
        }
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

    const std::vector<Point3> &points_;
    vcg::Box3f box_;
    double cellSize_ = 1.0;
    std::vector<int> order_;
    std::vector<int> far_;          // points outside the grid box
    std::vector<int> cellStart_;
    std::vector<std::uint64_t> cellKey_;
    std::vector<int> table_;
    std::vector<float> sortedX_, sortedY_, sortedZ_; // coordinates in grid order
    std::vector<std::array<int, 4>> shellOffsets_[kMaxRing + 1];
};

} // namespace gaussphere
} // namespace vcg

#endif
