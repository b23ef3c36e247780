// Crease points: points whose k nearest neighbours include a normal turned by more than
// a crease angle, as on the sharp edges of CAD parts or the ridges of a scan.
//
// Why: the surface a set of surfels defines is a blend of the surfels near each point
// (an MLS projection, as in the error metric of section 5.2 or a splat renderer). Across
// a crease the blend mixes the two faces, and it reaches as far from the crease as the
// surfels next to it are wide, so large flat clusters beside a crease round it off (on
// the block CAD part the largest error came from 27-point clusters touching an edge).
// Cluster normalization keeps the clusters that hold a crease point small; see
// ClusterNormalizationParams::creaseClusterSize.
//
// Normals more than 120 degrees apart are not taken as a crease: they are the two sheets
// of a thin part (the dragon's claws), whose surfels face away from each other and are
// never blended together.
#ifndef VCG_EXT_GAUSSPHERE_CREASE_POINTS_H
#define VCG_EXT_GAUSSPHERE_CREASE_POINTS_H

#include <cmath>
#include <vector>

#include <vcg/space/point3.h>

#include "adaptive_neighbors.h"

namespace vcg {
namespace gaussphere {

/// Per point: 1 when one of its neighbours in `graph` (all of the k nearest, inside the
/// cone of normals or not) has a normal between `creaseAngleDegrees` and 120 degrees away
/// from its own, else 0. Preconditions: unit normals; 0 < creaseAngleDegrees < 120.
inline FlatVector<char> MarkCreasePoints(const PointArray &normals, const NeighborGraph &graph,
                                          double creaseAngleDegrees)
{
    const double degree = std::acos(-1.0) / 180.0;
    const float maxDot = float(std::cos(creaseAngleDegrees * degree));
    const float minDot = float(std::cos(120.0 * degree));
    const int n = graph.Size();
    FlatVector<char> crease(n, 0);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
        const int *slot = graph.begin(i);
        for (int t = 0; t < graph.found[i]; ++t) {
            const float dot = normals[i].dot(normals[slot[t]]);
            if (dot < maxDot && dot > minDot) {
                crease[i] = 1;
                break;
            }
        }
    }
    return crease;
}

} // namespace gaussphere
} // namespace vcg

#endif
