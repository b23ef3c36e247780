// Naive sampling by index propagation (paper, section 3.2.2-3.2.3, Algorithm 1).
//
// A seed takes a new label; the label spreads along the adaptive neighbour graph to
// unlabelled points whose normal lies in the seed's Gaussian triangle and within the
// inscribed radius d_max / (2 sqrt 3) of the reference normal. The traversal uses an
// explicit container (no recursion) and stops expanding at a depth limit, the paper's
// positional constraint on large flat regions.
//
// Reference normal. Algorithm 1 compares each candidate with the root (seed) while the
// text compares neighbouring points. Comparing with the seed bounds every member's normal
// to a disc of the inscribed radius around the seed's, which bounds the shape error; with
// the current point, labels drift across the whole triangle. Seed is the default; the
// other reading is kept as an option for comparison.
#ifndef VCG_EXT_GAUSSPHERE_INDEX_PROPAGATION_H
#define VCG_EXT_GAUSSPHERE_INDEX_PROPAGATION_H

#include <cmath>
#include <functional>
#include <vector>

#include <vcg/space/point3.h>

#include "adaptive_neighbors.h"
#include "clustering.h"

namespace vcg {
namespace gaussphere {

enum class PropagationReference { Seed, CurrentPoint };
enum class PropagationOrder { DepthFirst, BreadthFirst };

struct IndexPropagationParams
{
    int maxDepth = 6;              ///< hops from the seed that may still expand; <= 0: no limit
    double inscribedRadius = 0.121;///< d_max / (2 sqrt 3), as a chord between unit normals
    PropagationReference reference = PropagationReference::Seed;
    PropagationOrder order = PropagationOrder::DepthFirst; ///< the paper uses a stack
};

/// Labels every point whose `clusters.label` is not -1 (points pre-marked -1 are
/// excluded and stay -1). `triangle[i]` is the Gaussian triangle of normal i; seeds are
/// taken in `seedOrder` (a permutation of the points). Postcondition: every non-excluded
/// point has a label in [0, clusterCount); points of one cluster share a triangle.
/// `progress(fraction)` is called now and then; when it returns false labelling stops
/// and the function returns false (the clustering is then incomplete).
inline bool PropagateIndices(const std::vector<vcg::Point3f> &normals, const std::vector<int> &triangle,
                             const NeighborGraph &graph, const std::vector<int> &seedOrder,
                             const IndexPropagationParams &param, Clustering &clusters,
                             const std::function<bool(double)> &progress = nullptr)
{
    const int unlabelled = -2;
    for (int &l : clusters.label) l = (l == -1) ? -1 : unlabelled;
    const float maxChord2 = float(param.inscribedRadius * param.inscribedRadius);
    struct Visit { int point; int depth; };
    // One vector serves both orders: a stack popped at the back, or a queue read from
    // `head` (cleared when a seed's cluster is complete).
    std::vector<Visit> pending;
    size_t head = 0;
    int next = 0;
    const size_t reportEvery = std::max<size_t>(1, seedOrder.size() / 50);
    for (size_t s = 0; s < seedOrder.size(); ++s) {
        if (progress && s % reportEvery == 0 && !progress(double(s) / seedOrder.size())) return false;
        const int seed = seedOrder[s];
        if (clusters.label[seed] != unlabelled) continue;
        const int id = next++;
        clusters.label[seed] = id;
        pending.clear();
        head = 0;
        pending.push_back({seed, 0});
        while (head < pending.size()) {
            Visit v;
            if (param.order == PropagationOrder::DepthFirst) { v = pending.back(); pending.pop_back(); }
            else v = pending[head++];
            if (param.maxDepth > 0 && v.depth >= param.maxDepth) continue;
            const vcg::Point3f &ref = normals[param.reference == PropagationReference::Seed ? seed : v.point];
            for (const int *q = graph.begin(v.point); q != graph.end(v.point); ++q) {
                const int j = *q;
                if (clusters.label[j] != unlabelled || triangle[j] != triangle[seed]) continue;
                if ((normals[j] - ref).SquaredNorm() > maxChord2) continue;
                clusters.label[j] = id;
                pending.push_back({j, v.depth + 1});
            }
        }
    }
    clusters.clusterCount = next;
    return true;
}

} // namespace gaussphere
} // namespace vcg

#endif
