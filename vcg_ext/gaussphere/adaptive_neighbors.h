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
    std::vector<float> spacing;     ///< mean distance to the (up to) 6 nearest neighbours

    int Size() const { return int(count.size()); }
    const int *begin(int i) const { return adjacency.data() + size_t(i) * stride; }
    const int *end(int i) const { return begin(i) + count[i]; }
};

struct AdaptiveNeighborParams
{
    int k = 16;               ///< neighbours examined per point (clamped to [1, 255] and N-1)
    double coneChord = 0.42;  ///< keep q when |n_p - n_q| <= coneChord, i.e. <n_p,n_q> >= 1 - chord^2/2
};

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
            const int near = std::min(found, 6);
            float sum = 0;
            for (int t = 0; t < near; ++t) sum += std::sqrt(d2[t]);
            g.spacing[i] = near > 0 ? sum / near : 0.f;
            int *out = g.adjacency.data() + size_t(i) * g.stride;
            int kept = 0;
            for (int t = 0; t < found; ++t)
                if (normals[i].dot(normals[idx[t]]) >= minDot) out[kept++] = idx[t];
            g.count[i] = std::uint8_t(kept);
        }
    }
    return g;
}

} // namespace gaussphere
} // namespace vcg

#endif
