// `gstile merge`: the tiles' results concatenated in tile order into one .surfel file or PLY,
// one tile's surfels in memory at a time, each tile's rescued spare surfels after its result
// (border_points.h). A tile without a complete result (never run, or killed before its result
// was renamed into place; with a target, also one not run at its share's count) stops the merge
// with its id.
#ifndef GSTILE_MERGE_H
#define GSTILE_MERGE_H

#include <cstdint>
#include <string>

#include "manifest.h"

namespace gstile {

struct MergeFigures
{
    std::uint64_t surfels = 0;  ///< rescued ones included
    std::uint64_t rescued = 0;   ///< surfels kept after all for border points no tile kept nor covered
    std::uint64_t uncovered = 0; ///< ... those points
    std::uint64_t members = 0; ///< points the surfels represent: the input's usable points when no
                               ///< border cluster is lost or kept twice (rescued ones are kept twice)
    double coarseStep = 0;     ///< a .surfel output of double input far from the origin: the step of
                               ///< its float coordinates there, when coarse (usable_points.h); else 0
};

/// Writes `output` (a .surfel file when its name ends in .surfel, else a PLY with normal, radius
/// and quality) through a temporary name.
bool Merge(const std::string &dir, const Manifest &manifest, const std::string &output, MergeFigures &figures,
           std::string &error);

} // namespace gstile

#endif
