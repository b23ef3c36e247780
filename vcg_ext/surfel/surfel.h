// The surfel record: what the resampler makes, the .surfel file stores and the renderer draws
// (docs/surfel_format.md). A leaf: it depends on vcglib's points alone.
#ifndef VCG_EXT_SURFEL_SURFEL_H
#define VCG_EXT_SURFEL_SURFEL_H

#include <vcg/space/point3.h>

namespace vcg {
namespace gaussphere {

struct Surfel
{
    vcg::Point3f position;
    vcg::Point3f normal;     ///< unit length
    vcg::Point3f majorAxis;  ///< semi-axis vector, tangent
    vcg::Point3f minorAxis;  ///< semi-axis vector, tangent, orthogonal to majorAxis, not longer
    int memberCount = 0;
    /// Factor in (0, 1] on the axes for blending only (surfels around creases, crease_blend.h; the
    /// error bound's one-point surfels, surface_error_bound.h); the axes keep covering the surface.
    float blendScale = 1.f;
    /// How far FitSurfelOffsets moved `position` along `normal` (surfel_offset.h): position -
    /// fitOffset * normal is where the surfel stood on the sampled surface. 0: not moved.
    float fitOffset = 0.f;
};

} // namespace gaussphere
} // namespace vcg

#endif
