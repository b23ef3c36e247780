// What the crease fit after the exchanges (max_error_exchange.h) judges its trials against.
//
// A run judges them against its figures on entry to the fit: its largest distance to the blended
// surface, and the 99.9th percentiles of that distance and of the blended normal error. A tile of
// a tiled run holds part of the scan, whose percentiles lie below the whole scan's, so it would
// drop moves the whole run keeps (the dragon at 10,000 surfels in 13 tiles: Delta* RMS 1.6 % above
// the whole run's). Its runs take the whole scan's percentiles instead (tools/gstile:
// target_share.h), gathered from every tile's report of its highest figures. A tile keeps its own
// largest distance as the limit: a point beside a face lies higher in the merged output than the
// tile sees it, and with the whole scan's largest distance the dragon's tiled Delta* max at 4,000
// surfels rose 16 % above the whole run's.
#ifndef VCG_EXT_GAUSSPHERE_CREASE_FIT_LIMITS_H
#define VCG_EXT_GAUSSPHERE_CREASE_FIT_LIMITS_H

#include <vector>

namespace vcg {
namespace gaussphere {

/// The percentiles beyond which a crease fit trial may not bring more points.
struct CreaseFitLimits
{
    bool given = false;      ///< false: the run's own percentiles on entry to the fit
    double distance = 0;     ///< the 99.9th percentile of the distances to the blended surface
    double normalError = 0;  ///< the 99.9th percentile of the blended normal errors

    bool operator==(const CreaseFitLimits &o) const
    {
        return given == o.given && distance == o.distance && normalError == o.normalError;
    }
    bool operator!=(const CreaseFitLimits &o) const { return !(*this == o); }
};

/// The highest figures of a run's points that count, on entry to its crease fit, highest first.
struct CreaseFitEntry
{
    std::vector<double> distances;     ///< distances to the blended surface
    std::vector<double> normalErrors;  ///< blended normal errors
};

} // namespace gaussphere
} // namespace vcg

#endif
