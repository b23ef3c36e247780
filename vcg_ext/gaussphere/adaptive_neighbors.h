// Adaptive neighbours (paper, section 3.2.1): the k nearest neighbours of a point,
// kept only inside its cone of normals <n_p, n_q> >= 1 - d_max^2 / 2.
//
// The result is the paper's directed neighbour graph N(p), stored with a fixed stride of
// k slots per point (no second copy of the unfiltered k-NN lists), plus each point's
// local sample spacing, which the surfel stage uses to close the gaps between surfels.
#ifndef VCG_EXT_GAUSSPHERE_ADAPTIVE_NEIGHBORS_H
#define VCG_EXT_GAUSSPHERE_ADAPTIVE_NEIGHBORS_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <vcg/space/point3.h>

#include "point_kdtree.h"

namespace vcg {
namespace gaussphere {

struct NeighborGraph
{
    int stride = 0;                 ///< k: slots per point
    std::vector<int> adjacency;     ///< neighbours of i in adjacency[i*stride, i*stride + count[i])
    std::vector<std::uint8_t> count;
    /// Mean distance to the (up to) 6 nearest neighbours at a non-zero distance; for a
    /// point whose k neighbours all coincide with it, the median spacing of the others
    /// (or 1e-3 when every point coincides: there is no scale to read).
    std::vector<float> spacing;

    int Size() const { return int(count.size()); }
    const int *begin(int i) const { return adjacency.data() + size_t(i) * stride; }
    const int *end(int i) const { return begin(i) + count[i]; }
};

struct AdaptiveNeighborParams
{
    int k = 16;               ///< neighbours examined per point (clamped to [1, 255] and N-1)
    double coneChord = 0.42;  ///< keep q when |n_p - n_q| <= coneChord, i.e. <n_p,n_q> >= 1 - chord^2/2
};

/// Replaces zero spacings (points with only coincident neighbours) by the median of the
/// positive ones, or by 1e-3 if there are none.
inline void FillUnknownSpacing(std::vector<float> &spacing)
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

/// Builds N(p) for unit normals `normals` at `points` (same size, finite).
/// Postcondition: graph.Size() == points.size(); every kept neighbour j != i is among
/// the k nearest of i and satisfies the cone test. Runs in parallel with OpenMP; the
/// result does not depend on the thread count.
inline NeighborGraph BuildAdaptiveNeighbors(const std::vector<vcg::Point3f> &points,
                                            const std::vector<vcg::Point3f> &normals,
                                            const AdaptiveNeighborParams &param,
                                            const PointKdTree &tree)
{
    const int n = int(points.size());
    NeighborGraph g;
    g.stride = std::max(1, std::min({param.k, 255, std::max(1, n - 1)}));
    g.adjacency.assign(size_t(n) * g.stride, -1);
    g.count.assign(n, 0);
    g.spacing.assign(n, 0.f);
    const float minDot = float(1.0 - 0.5 * param.coneChord * param.coneChord);
    const std::vector<int> &order = tree.LeafOrder();

#pragma omp parallel
    {
        std::vector<int> idx(g.stride);
        std::vector<float> d2(g.stride);
#pragma omp for schedule(dynamic, 2048)
        for (int s = 0; s < n; ++s) {
            const int i = order[s]; // leaf order: consecutive queries touch the same leaves
            const int found = tree.KNearest(points[i], g.stride, i, idx.data(), d2.data());
            int near = 0;
            float sum = 0;
            for (int t = 0; t < found && near < 6; ++t)
                if (d2[t] > 0) { sum += std::sqrt(d2[t]); ++near; }
            g.spacing[i] = near > 0 ? sum / near : 0.f;
            int *out = g.adjacency.data() + size_t(i) * g.stride;
            int kept = 0;
            for (int t = 0; t < found; ++t)
                if (normals[i].dot(normals[idx[t]]) >= minDot) out[kept++] = idx[t];
            g.count[i] = std::uint8_t(kept);
        }
    }
    FillUnknownSpacing(g.spacing);
    return g;
}

} // namespace gaussphere
} // namespace vcg

#endif
