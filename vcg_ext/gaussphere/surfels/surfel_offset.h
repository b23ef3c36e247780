// Beyond the paper: surfel offsets fitted to the blended surface.
//
// A surfel stands at its cluster's centroid, lifted onto the surface above it (surfel
// generation). The surface a point-set surface tool computes from surfels, though, and what
// bench/ measures, is the blend of their positions (an MLS projection, vcg_ext/surfel_error):
// between two surfels on a curved surface the blend follows neither's plane, and the surface it
// draws lies off the samples by a fraction of the curvature times the spacing squared, inside or
// outside depending on the sizes and weights around. FitSurfelOffsets measures that directly: each
// member of a cluster is compared with the blended plane at it, and the surfel moves along its
// normal by the mean signed distance, the least-squares offset of that surfel for the blend it
// takes part in. The move is kept in Surfel::fitOffset: a splat renderer blends shading, not
// positions, and draws each surfel at its unfitted position (drawn where the fit puts them, the
// splats stand off the surface and swell the silhouettes on convex parts).
//
// The blended plane at a point is one step of the projection of vcg_ext/surfel_error: the
// Gaussian-weighted mean of the surfels around it (its own and those of the clusters of its
// first 8 neighbour slots: the nearest inside its cone of normals, then the nearest outside it;
// on its side of a thin part), weights sized by each ellipse; and two
// members per cluster are compared, not all. This costs a few milliseconds and keeps most of
// what the full projection of every member (iterated, onto the 8 nearest surfel centres) would
// gain, at a small fraction of its cost (which is several times the whole resampling's).
//
// Clusters holding a crease point stay where they are: there the blend rounds the crease off,
// and moving a surfel towards the rounded blend takes it off its face, which raises the largest
// error on CAD parts. So do surfels whose blend is narrowed (the band around creases,
// crease_blend.h; the error bound's one-point surfels): their blend follows each surfel's own
// plane closely already, and moving them trades a little RMS error for a larger maximum. At a
// target size the exchanges fit the crease surfels last, where that helps (max_error_exchange.h).
#ifndef VCG_EXT_GAUSSPHERE_SURFEL_OFFSET_H
#define VCG_EXT_GAUSSPHERE_SURFEL_OFFSET_H

#include <algorithm>
#include <cmath>
#include <vector>

#include <vcg/space/point3.h>
#include <vcg_ext/surfel/blended_surface.h>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>
#include <vcg_ext/gaussphere/clustering/clustering.h>
#include <vcg_ext/gaussphere/surfels/surfel_generation.h>

namespace vcg {
namespace gaussphere {


/// Neighbours of a point whose clusters' surfels are blended at it (with its own): the nearest
/// ones, as many as the metric blends surfels.
constexpr int kOffsetNeighbors = 8;
/// Members of a cluster compared with the blend, evenly spread over its member list.
constexpr int kOffsetSamples = 2;

struct SurfelOffsetResult
{
    int moved = 0;        ///< surfels moved
    double largest = 0;   ///< the longest move, model units
};

/// The points of cluster c's members [begin, end) (in increasing order) that FitSurfelOffsets
/// compares with the blend: kOffsetSamples of them, evenly spread.
template <class Visit>
void ForEachOffsetSample(const int *begin, const int *end, Visit &&visit)
{
    const int size = int(end - begin), stride = std::max(1, (size + kOffsetSamples - 1) / kOffsetSamples);
    for (int t = 0; t < size; t += stride) visit(begin[t]);
}

/// The clusters whose surfels are blended at point i with cluster c's (FitSurfelOffsets): those of
/// its first kOffsetNeighbors neighbour slots facing its side, without repeats, after c itself.
/// Returns how many were written to `around` (room for kOffsetNeighbors + 1).
inline int BlendedAroundSample(const PointArray &normals, const NeighborGraph &graph, const IndexArray &label,
                               const std::vector<Surfel> &surfels, int c, int i, int *around)
{
    int blended = 1;
    around[0] = c;
    const int *q = graph.begin(i), *end = q + std::min<int>(graph.found[i], kOffsetNeighbors);
    for (; q != end; ++q) {
        const int l = label[*q];
        // Thin parts: surfels facing away belong to the other sheet.
        if (l >= 0 && std::find(around, around + blended, l) == around + blended && surfels[l].normal.dot(normals[i]) > 0)
            around[blended++] = l;
    }
    return blended;
}

/// Whether FitSurfelOffsets leaves cluster c (members [begin, end)) in place: a narrowed blend or
/// a member flagged in creasePoints (null: none).
inline bool StaysAtCrease(const FlatVector<char> *creasePoints, const std::vector<Surfel> &surfels, int c,
                          const int *begin, const int *end)
{
    return surfels[c].blendScale < 1 ||
           (creasePoints && std::any_of(begin, end, [creasePoints](int i) { return (*creasePoints)[i] != 0; }));
}

/// The move along its normal that FitSurfelOffsets gives the surfel of cluster c (members
/// [begin, end), in increasing order), from the unfitted `surfels` of every cluster and
/// `weightOf(l)`, the BlendWeight of surfels[l]. 0 for a cluster that stays (narrowed blend,
/// a member flagged in creasePoints, or no move within maxPlaneDistance).
/// With `atCreases`, the move is computed for crease clusters and narrowed blends too (the
/// crease fit after the exchanges of ExchangeForMaxError keeps it only where the measure allows).
template <class WeightOf>
float SurfelOffsetOf(const PointArray &points, const PointArray &normals, const NeighborGraph &graph,
                     const IndexArray &label, const FlatVector<char> *creasePoints, const std::vector<Surfel> &surfels,
                     WeightOf &&weightOf, int c, const int *begin, const int *end, double maxPlaneDistance,
                     bool atCreases = false)
{
    // Crease clusters and narrowed blends stay (file header).
    if (begin == end || (!atCreases && StaysAtCrease(creasePoints, surfels, c, begin, end))) return 0.f;
    int around[kOffsetNeighbors + 1]; // surfels blended at a point
    float exponent[kOffsetNeighbors + 1];
    double sum = 0;
    int sampled = 0;
    ForEachOffsetSample(begin, end, [&](int i) {
        ++sampled;
        const vcg::Point3f &p = points[i];
        const int blended = BlendedAroundSample(normals, graph, label, surfels, c, i, around);
        float smallest = 0; // exponent of the heaviest surfel: the weights are relative to it
        for (int t = 0; t < blended; ++t) {
            exponent[t] = weightOf(around[t]).Exponent(surfels[around[t]].position, p);
            smallest = t == 0 ? exponent[t] : std::min(smallest, exponent[t]);
        }
        float weightSum = 0;
        vcg::Point3f centre(0, 0, 0), normal(0, 0, 0);
        for (int t = 0; t < blended; ++t) {
            const float w = std::exp(smallest - exponent[t]);
            weightSum += w;
            centre += surfels[around[t]].position * w;
            normal += surfels[around[t]].normal * w;
        }
        const float length = normal.Norm();
        if (length > 0) sum += (p - centre / weightSum).dot(normal / length);
    });
    double move = sum / sampled;
    if (maxPlaneDistance > 0) {
        // Members at heights h above the plane stay within the bound for moves in
        // [max h - bound, min h + bound], which holds 0. With 1 % kept in hand, a member
        // in the last 1 % may make the move one that brings it back (or, with members in
        // the last 1 % on both sides, the surfel stays).
        double lowest = 0, highest = 0;
        for (const int *m = begin; m != end; ++m) {
            const double h = (points[*m] - surfels[c].position).dot(surfels[c].normal);
            lowest = m == begin ? h : std::min(lowest, h);
            highest = m == begin ? h : std::max(highest, h);
        }
        const double room = 0.99 * maxPlaneDistance; // the float position rounds the move
        const double least = highest - room, most = lowest + room;
        move = least <= most ? std::max(least, std::min(move, most)) : 0.0;
    }
    return float(move);
}

/// Applies a move from SurfelOffsetOf to a surfel.
inline void MoveSurfel(Surfel &s, float offset)
{
    if (offset == 0) return;
    s.position += s.normal * offset;
    s.fitOffset += offset;
}

/// Moves each surfel along its normal by the mean signed distance of sampled members of its
/// cluster to the blended plane at them (file header). Surfels of clusters with a point marked
/// in `creasePoints` (null: none) stay, and so do those whose blend is narrowed (blendScale < 1).
/// With maxPlaneDistance > 0 no member ends farther than that from its surfel's plane (none is on
/// entry: the error bound's own-plane stage holds): a move is cut short so that every member
/// stays within 0.99 x maxPlaneDistance (the rest absorbs the rounding of the float position),
/// and where none can, the surfel stays.
/// \pre surfels[c] is the surfel of cluster c of `clusters` (GenerateSurfels); members =
///      ClusterMembers(clusters); `graph` is the neighbour graph of `points` (unit `normals`);
///      creasePoints, if given, has one flag per point.
/// \post Only positions change, each surfel's fitOffset by the same move; the result does not
///       depend on the thread count.
inline SurfelOffsetResult FitSurfelOffsets(const PointArray &points, const PointArray &normals,
                                           const NeighborGraph &graph, const Clustering &clusters,
                                           const ClusterMembers &members, const FlatVector<char> *creasePoints,
                                           std::vector<Surfel> &surfels, double maxPlaneDistance = 0)
{
    const int count = clusters.clusterCount;
    std::vector<BlendWeight> weight(count);
#pragma omp parallel for schedule(static)
    for (int c = 0; c < count; ++c) weight[c] = BlendWeight(surfels[c]);
    std::vector<float> offset(count, 0.f);
#pragma omp parallel for schedule(dynamic, 256)
    for (int c = 0; c < count; ++c)
        offset[c] = SurfelOffsetOf(points, normals, graph, clusters.label, creasePoints, surfels,
                                   [&weight](int l) -> const BlendWeight & { return weight[l]; }, c,
                                   members.begin(c), members.end(c), maxPlaneDistance);
    SurfelOffsetResult result;
    for (int c = 0; c < count; ++c) {
        if (offset[c] == 0) continue;
        MoveSurfel(surfels[c], offset[c]);
        ++result.moved;
        result.largest = std::max(result.largest, double(std::abs(offset[c])));
    }
    return result;
}
/// The same, the member lists built here.
inline SurfelOffsetResult FitSurfelOffsets(const PointArray &points, const PointArray &normals,
                                           const NeighborGraph &graph, const Clustering &clusters,
                                           const FlatVector<char> *creasePoints, std::vector<Surfel> &surfels,
                                           double maxPlaneDistance = 0)
{
    return FitSurfelOffsets(points, normals, graph, clusters, ClusterMembers(clusters), creasePoints, surfels,
                            maxPlaneDistance);
}

} // namespace gaussphere
} // namespace vcg

#endif
