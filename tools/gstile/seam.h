// The seam step of a tiled run with a target (docs/tiling.md, "The seam step").
//
// A tile measures its points near a face on its own clusters beyond it, which are not the
// surfels the neighbouring tile keeps there: its exchanges can lower a point's distance through
// surfels no tile keeps. Once every tile ran at its share, `gstile adjust` snapshots each tile's
// kept surfels (`tile_NNNNNN.seam`) and every tile runs once more with its neighbours' snapshots
// around it (ResamplingParams::surroundingSurfels): after its exchanges and crease fit, seam
// rounds of exchanges measure its points on the neighbours' snapshots in place of the clusters it
// does not keep (what the neighbours kept before their own seam rounds). The snapshots are written
// once and only read after, so the tiles' runs may go in any order, or at once, with the same result.
#ifndef GSTILE_SEAM_H
#define GSTILE_SEAM_H

#include <string>
#include <vector>

#include <vcg_ext/surfel/surfel.h>

#include "manifest.h"

namespace gstile {

/// How far beyond its core box a tile takes its neighbours' surfels, in halo widths: its halo, and
/// the surfels that blend at the halo's outer points (a projection blends the 8 nearest surfels,
/// a few surfel spacings, which at the halo's default width of 24 sample spacings is 1 to 10 % of
/// a target's surfels within one more halo width).
constexpr double kSurroundHalos = 2.0;

/// The snapshot of the surfels the merge keeps for border points (border_points.h): they belong to
/// no tile's clusters, so every tile takes those near it, its own too.
std::string RescuedSnapshotPath(const std::string &dir);

/// Copies every tile's result into its seam snapshot (`tile_NNNNNN.seam`), and the spare surfels
/// the merge keeps into RescuedSnapshotPath(dir).
bool SnapshotForSeam(const std::string &dir, const Manifest &manifest, std::string &error);

/// The surfels the other tiles' seam snapshots and the rescued ones hold within kSurroundHalos halo
/// widths of tile `id`'s core box, in tile order. An error names a missing or damaged snapshot.
bool ReadSurround(const std::string &dir, const Manifest &manifest, int id, std::vector<vcg::gaussphere::Surfel> &surround,
                  std::string &error);

} // namespace gstile

#endif
