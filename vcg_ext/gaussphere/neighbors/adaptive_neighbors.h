// Adaptive neighbours (paper, section 3.2.1): the k nearest neighbours of a point,
// kept only inside its cone of normals <n_p, n_q> >= 1 - d_max^2 / 2.
//
// The result is the paper's directed neighbour graph N(p), stored with a fixed stride of
// k slots per point: the k nearest, nearest first, with the ones inside the cone moved
// to the front. Keeping the rejected ones lets RestrictToCone() re-filter the same search
// for another Gaussian sphere level without searching again. Each point also gets its
// local sample spacing, which the surfel stage uses to close the gaps between surfels, and,
// on request, a mark if it lies at a crease (crease_points.h) or on the rim of an open surface
// (boundary_points.h).
#ifndef VCG_EXT_GAUSSPHERE_ADAPTIVE_NEIGHBORS_H
#define VCG_EXT_GAUSSPHERE_ADAPTIVE_NEIGHBORS_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include <vcg/space/point3.h>

#include <vcg_ext/gaussphere/neighbors/boundary_points.h>
#include <vcg_ext/gaussphere/neighbors/crease_points.h>
#include <vcg_ext/gaussphere/support/flat_vector.h>
#include <vcg_ext/gaussphere/neighbors/point_grid.h>

namespace vcg {
namespace gaussphere {

struct NeighborGraph
{
    int stride = 0;                 ///< k: slots per point
    FlatVector<int> adjacency;      ///< N(i) = adjacency[i*stride, i*stride + count[i])
    FlatVector<std::uint8_t> count; ///< neighbours inside the cone of `chord`
    FlatVector<std::uint8_t> found; ///< neighbours found (min(k, N-1)), kept ones first
    /// Mean distance to the (up to) 6 nearest neighbours at a non-zero distance; for a
    /// point whose k neighbours all coincide with it, the median spacing of the others
    /// (or 1e-3 when every point coincides: there is no scale to read).
    FlatVector<float> spacing;
    /// Per point: 1 if one of its k nearest (inside the cone or not) meets it at a crease
    /// (CreaseTest), else 0; empty unless AdaptiveNeighborParams::creaseAngle > 0.
    FlatVector<char> crease;
    /// Per point: 1 if its k nearest leave a gap wider than AdaptiveNeighborParams::
    /// boundaryGapDegrees around it (IsBoundaryPoint), else 0; empty unless that is > 0.
    FlatVector<char> boundary;
    double chord = -1;              ///< cone chord the slots are partitioned by (-1: none yet);
                                    ///< reset it to -1 if the normals change

    int Size() const { return int(count.size()); }
    const int *begin(int i) const { return adjacency.data() + size_t(i) * stride; }
    const int *end(int i) const { return begin(i) + count[i]; }
};

struct AdaptiveNeighborParams
{
    int k = 16;               ///< neighbours examined per point (clamped to [1, 255] and N-1)
    double coneChord = 0.42;  ///< keep q when |n_p - n_q| <= coneChord, i.e. <n_p,n_q> >= 1 - chord^2/2
    double creaseAngle = 0;   ///< degrees in (0, 120): mark crease points (NeighborGraph::crease); 0: none
    double boundaryGapDegrees = 0; ///< degrees in (0, 180): mark boundary points (NeighborGraph::boundary); 0: none
};

/// Replaces zero spacings (points with only coincident neighbours) by the median of the
/// positive ones, or by 1e-3 if there are none.
inline void FillUnknownSpacing(FlatVector<float> &spacing)
{
    std::vector<float> known;
    for (float s : spacing)
        if (s > 0) known.push_back(s);
    float fallback = 1e-3f;
    if (!known.empty()) {
        std::nth_element(known.begin(), known.begin() + known.size() / 2, known.end());
        fallback = known[known.size() / 2];
    }
    for (float &s : spacing)
        if (!(s > 0)) s = fallback;
}

/// The cone test of a chord between unit normals: |n_p - n_q| <= chord iff <n_p, n_q> >= this.
inline float ConeMinDot(double chord) { return float(1.0 - 0.5 * chord * chord); }

/// Writes the neighbours `ordered[0, found)` of point i into `slot`: those q with
/// <n_i, n_q> >= minDot first, then the others, each group in its given order. Returns
/// the number kept. `ordered` and `slot` must not overlap. `seeDot(<n_i, n_q>)` is called
/// for each q, for other uses of the same products.
template <class DotVisitor>
int PartitionByCone(const PointArray &normals, int i, float minDot, const int *ordered, int found, int *slot,
                    DotVisitor &&seeDot)
{
    int kept = 0, dropped = 0;
    int rejected[255];
    for (int t = 0; t < found; ++t) {
        const float dot = normals[i].dot(normals[ordered[t]]);
        seeDot(dot);
        if (dot >= minDot) slot[kept++] = ordered[t];
        else rejected[dropped++] = ordered[t];
    }
    std::copy(rejected, rejected + dropped, slot + kept);
    return kept;
}

/// Orders each point's slots canonically: the neighbours q with |n_p - n_q| <= chord
/// first, then the others, each group by increasing (distance, index); sets count. The
/// result depends only on the chord, not on the order of the calls.
inline void RestrictToCone(const PointArray &points, const PointArray &normals,
                           double chord, NeighborGraph &g)
{
    if (chord == g.chord) return;
    g.chord = chord;
    const float minDot = ConeMinDot(chord);
    const int n = g.Size();
#pragma omp parallel
    {
        std::vector<std::uint64_t> keyed(g.stride), merged(g.stride);
        std::vector<int> ordered(g.stride);
#pragma omp for schedule(static)
        for (int i = 0; i < n; ++i) {
            int *slot = g.adjacency.data() + size_t(i) * g.stride;
            const int found = g.found[i];
            // The slots hold two runs, each in (distance, index) order: the previous kept
            // neighbours, then the previous rejected ones. Merging them restores the
            // canonical order in O(k); a stable partition then applies this chord.
            for (int t = 0; t < found; ++t)
                keyed[t] = DistanceIndexKey((points[slot[t]] - points[i]).SquaredNorm(), slot[t]);
            std::merge(keyed.begin(), keyed.begin() + g.count[i], keyed.begin() + g.count[i], keyed.begin() + found,
                       merged.begin());
            for (int t = 0; t < found; ++t) ordered[t] = int(std::uint32_t(merged[t]));
            const int kept = PartitionByCone(normals, i, minDot, ordered.data(), found, slot, [](float) {});
            g.count[i] = std::uint8_t(kept);
        }
    }
}

/// Keeps the first `slotCount` slots of every point (the nearest kept by the cone, then the nearest
/// rejected), at that stride: for stages that read no further, at a fraction of the memory. The
/// kept slots are copied into a buffer of their own and the full one is freed: both exist during
/// the copy (std::allocator cannot give back a buffer's tail). The graph can no longer be
/// restricted to another cone.
// (Not "slots": Qt defines it as a macro, and MeshLab plugins include these headers.)
inline void KeepFirstSlots(NeighborGraph &g, int slotCount)
{
    if (slotCount >= g.stride) return;
    const long long n = g.Size(), from = g.stride, to = std::max(0, slotCount);
    FlatVector<int> kept(size_t(n * to));
    const int *data = g.adjacency.data();
#pragma omp parallel for schedule(static)
    for (long long i = 0; i < n; ++i) {
        std::copy(data + i * from, data + i * from + to, kept.data() + i * to);
        g.found[size_t(i)] = std::uint8_t(std::min<long long>(g.found[size_t(i)], to));
        g.count[size_t(i)] = std::uint8_t(std::min<long long>(g.count[size_t(i)], to));
    }
    g.adjacency.swap(kept);
    g.stride = int(to);
    g.chord = -2; // no chord's partition: RestrictToCone would need the slots cut off
}

/// Builds N(p) for unit normals `normals` at `points` (same size, finite).
/// Postcondition: graph.Size() == points.size(); every kept neighbour j != i is among
/// the k nearest of i and satisfies the cone test. Runs in parallel with OpenMP; the
/// result does not depend on the thread count.
/// `progress` as in PointGrid::ForAllKNearest; if it stops the search, the graph is
/// returned empty (Size() == 0).
inline NeighborGraph BuildAdaptiveNeighbors(const PointArray &points,
                                            const PointArray &normals,
                                            const AdaptiveNeighborParams &param,
                                            const PointGrid &grid,
                                            const std::function<bool(double)> &progress = nullptr)
{
    const int n = int(points.size());
    NeighborGraph g;
    g.stride = std::max(1, std::min({param.k, 255, std::max(1, n - 1)}));
    g.adjacency.resize(size_t(n) * g.stride);
    g.count.resize(n);
    g.found.resize(n);
    g.spacing.resize(n);
    g.chord = param.coneChord;
    const float minDot = ConeMinDot(param.coneChord);
    const bool markCreases = param.creaseAngle > 0;
    const CreaseTest atCrease(markCreases ? param.creaseAngle : 90.0);
    if (markCreases) g.crease.resize(n);
    const bool markBoundary = param.boundaryGapDegrees > 0;
    if (markBoundary) g.boundary.resize(n);
    // One scratch buffer per thread: the callback runs on the search's threads.
    std::vector<std::vector<TangentDirection>> scratch(static_cast<size_t>(omp_get_max_threads()));
    const bool complete = grid.ForAllKNearest(g.stride, [&](int i, const int *idx, const float *d2, int found) {
        int near = 0;
        float sum = 0;
        for (int t = 0; t < found && near < 6; ++t)
            if (d2[t] > 0) { sum += std::sqrt(d2[t]); ++near; }
        g.spacing[i] = near > 0 ? sum / near : 0.f;
        // The same partition as RestrictToCone, so that it can skip this chord later.
        int *slot = g.adjacency.data() + size_t(i) * g.stride;
        bool crease = false;
        const int kept = markCreases ? PartitionByCone(normals, i, minDot, idx, found, slot, [&](float dot) { crease |= atCrease(dot); })
                                     : PartitionByCone(normals, i, minDot, idx, found, slot, [](float) {});
        std::fill(slot + found, slot + g.stride, -1);
        g.found[i] = std::uint8_t(found);
        g.count[i] = std::uint8_t(kept);
        if (markCreases) g.crease[i] = crease;
        if (markBoundary)
            g.boundary[i] = IsBoundaryPoint(points, normals, i, idx, found, param.boundaryGapDegrees,
                                            scratch[size_t(omp_get_thread_num())]);
    }, progress);
    if (!complete) return NeighborGraph();
    if (std::find(g.spacing.begin(), g.spacing.end(), 0.f) != g.spacing.end()) FillUnknownSpacing(g.spacing);
    return g;
}

} // namespace gaussphere
} // namespace vcg

#endif
