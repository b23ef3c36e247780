// Crease points: points whose k nearest neighbours include a normal turned by more than
// a crease angle, as on the sharp edges of CAD parts or the ridges of a scan.
//
// Why: the surface a set of surfels defines is a blend of the surfels near each point
// (an MLS projection, as in the error metric of section 5.2 or a splat renderer). Across
// a crease the blend mixes the two faces, and it reaches as far from the crease as the
// surfels next to it are wide, so large flat clusters beside a crease round it off (on
// CAD parts such clusters along the edges set the largest error).
// Cluster normalization keeps the clusters that hold a crease point small; see
// ClusterNormalizationParams::creaseClusterSize. The neighbour search marks them
// (AdaptiveNeighborParams::creaseAngle), while each point's neighbours are at hand.
//
// Normals more than 120 degrees apart are not taken as a crease: they are the two sheets
// of a thin part (the dragon's claws), whose surfels face away from each other and are
// never blended together.
#ifndef VCG_EXT_GAUSSPHERE_CREASE_POINTS_H
#define VCG_EXT_GAUSSPHERE_CREASE_POINTS_H

#include <cmath>

namespace vcg {
namespace gaussphere {

/// Whether two unit normals, given their dot product, meet at a crease: turned by more than
/// the crease angle and by less than 120 degrees. Precondition: 0 < creaseAngleDegrees < 120.
class CreaseTest
{
public:
    explicit CreaseTest(double creaseAngleDegrees)
    {
        const double degree = std::acos(-1.0) / 180.0;
        maxDot_ = float(std::cos(creaseAngleDegrees * degree));
        minDot_ = float(std::cos(120.0 * degree));
    }
    bool operator()(float dot) const { return dot < maxDot_ && dot > minDot_; }

private:
    float maxDot_, minDot_;
};

} // namespace gaussphere
} // namespace vcg

#endif
