// Beyond the paper: narrower blends around creases.
//
// The surface a set of surfels defines is a blend of the surfels near each point (an MLS
// projection: the metric of vcg_ext/surfel_error, a point-set surface tool), in which each surfel
// weighs as far as its Gaussian reaches, 1.5 semi-axes. Beside a crease that reach crosses the
// edge: the surfels of one face pull the blend at the other face's points, and the edge comes out
// rounded by a fraction of the surfel size even where every surfel lies on its own face (S' = S
// does it too: the metric's floor). Narrowing the weights of the surfels around a crease
// (Surfel::blendScale) keeps each face's blend on its own surfels closer to the edge; their
// ellipses keep their size, so that a splat rendering keeps covering the surface.
//
// Which surfels: those of the clusters holding a crease point or one of its k neighbours, one-point
// clusters excepted. A one-point cluster at a crease stands for the edge itself (its normal is the
// input's, averaged across the edge): narrowed too, it would let the faces' surfels take the edge
// over. The neighbours' clusters are narrowed as well as the crease points' own, and so are the
// clusters made only of crease points: every surfel whose weight reaches across the edge.
//
// The scale, 0.65 by default (ResamplingParams::creaseBlendScale), balances two faults: a wider
// blend still rounds the edge, a narrower one follows each surfel's plane out to its rim, which
// raises the largest error on CAD parts at low counts, where the surfels are large; 0.65 is where
// bench/'s comparisons with the peers show the fewest losses.
#ifndef VCG_EXT_GAUSSPHERE_CREASE_BLEND_H
#define VCG_EXT_GAUSSPHERE_CREASE_BLEND_H

#include <vector>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>
#include <vcg_ext/gaussphere/clustering/clustering.h>
#include <vcg_ext/gaussphere/surfels/surfel_generation.h>

namespace vcg {
namespace gaussphere {

/// Sets Surfel::blendScale to `scale` on the surfels of more than one member whose clusters hold a
/// point marked in graph.crease or one of the (up to k, inside the cone of normals or not)
/// neighbours of one (file header); the others keep theirs. Nothing changes when graph.crease is
/// empty (no crease angle) or scale >= 1. Returns how many surfels it narrowed.
/// \pre surfels[c] is the surfel of cluster c of `clusters` (GenerateSurfels, memberCount set);
///      `graph` is the neighbour graph of the clustered points; 0 < scale.
/// \post Does not depend on the thread count (serial: a few crease points times k).
inline int NarrowBlendsAroundCreases(const NeighborGraph &graph, const Clustering &clusters, float scale,
                                     std::vector<Surfel> &surfels)
{
    if (scale >= 1 || graph.crease.empty()) return 0;
    int narrowed = 0;
    auto narrow = [&](int point) {
        const int c = clusters.label[point];
        if (c < 0 || surfels[c].memberCount < 2 || surfels[c].blendScale == scale) return;
        surfels[c].blendScale = scale;
        ++narrowed;
    };
    for (int i = 0; i < graph.Size(); ++i) {
        if (!graph.crease[i]) continue;
        narrow(i);
        for (const int *q = graph.begin(i), *end = q + graph.found[i]; q != end; ++q) narrow(*q);
    }
    return narrowed;
}

/// The points whose clusters NarrowBlendsAroundCreases narrows: crease points and their (up to k)
/// neighbours, one bit per point; empty when it narrows nothing (scale >= 1, no crease marks).
/// Taken while the graph has all its slots, for NarrowFlaggedBlends later.
inline std::vector<bool> NarrowingFlags(const NeighborGraph &graph, float scale)
{
    std::vector<bool> flags;
    if (scale >= 1 || graph.crease.empty()) return flags;
    flags.assign(size_t(graph.Size()), false);
    for (int i = 0; i < graph.Size(); ++i) {
        if (!graph.crease[i]) continue;
        flags[size_t(i)] = true;
        for (const int *q = graph.begin(i), *end = q + graph.found[i]; q != end; ++q) flags[size_t(*q)] = true;
    }
    return flags;
}

/// NarrowBlendsAroundCreases from `flags` = NarrowingFlags(graph, scale): the same surfels
/// narrowed, without reading the graph's rows again.
inline void NarrowFlaggedBlends(const std::vector<bool> &flags, const Clustering &clusters, float scale,
                                std::vector<Surfel> &surfels)
{
    for (size_t i = 0; i < flags.size(); ++i) {
        const int c = flags[i] ? clusters.label[i] : -1;
        if (c >= 0 && surfels[size_t(c)].memberCount >= 2) surfels[size_t(c)].blendScale = scale;
    }
}

} // namespace gaussphere
} // namespace vcg

#endif
