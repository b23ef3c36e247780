// Points along the faces between tiles that no tile keeps (docs/tiling.md, "Border points").
//
// A cluster is kept by the tile whose core holds its anchor (tile_run.h). Where two tiles cluster
// a border region differently, a core point of tile A can lie in a cluster that A leaves to tile
// B, while B, which sees the point in its halo, puts it in a cluster that B leaves to A: no kept
// surfel represents the point (an orphan), and where no kept ellipse covers it either, the splats
// leave a hole. So each run records, beside its result (`.border`):
//  - the input indices of the halo points its kept surfels represent (the points it takes over);
//  - for each surfel it leaves to another tile that holds some of its own core points, those
//    points with their positions (the surfels themselves go to `.spare`, a .surfel file, in the
//    same order).
// The merge finds the orphans (left points no tile took over), checks them against the ellipses of
// every kept surfel, and keeps after all ("rescues") each spare surfel holding an orphan that no
// ellipse covers: each such point is represented again, by the surfel of its own tile's cluster,
// at the cost of a few surfels doubled along the faces. Memory: the taken-over indices and the
// orphans, not the tiles' surfels.
#ifndef GSTILE_BORDER_POINTS_H
#define GSTILE_BORDER_POINTS_H

#include <cstdint>
#include <string>
#include <vector>

#include <io_surfel/surfel_file.h>

#include "manifest.h"

namespace gstile {

/// A core point in a surfel its tile leaves to another tile.
struct LeftPoint
{
    std::uint64_t index = 0;
    float position[3] = {0, 0, 0};
    float unused = 0; ///< 24 bytes in the file, no padding left undefined
};
static_assert(sizeof(LeftPoint) == 24, "left points are 24-byte records");

struct TileBorder
{
    std::vector<std::uint64_t> takenOver;          ///< halo points the kept surfels represent, sorted
    std::vector<std::vector<LeftPoint>> leftPoints; ///< per spare surfel, the core points it holds
};

/// Whether the ellipse of `s` covers `q`: within the ellipse in its plane, and at most its major
/// semi-axis off the plane (the splats' reach).
bool EllipseCovers(const surfel_io::SurfelRecord &s, const float q[3]);

bool WriteBorder(const std::string &dir, int id, const TileBorder &border, std::string &error);
bool ReadBorder(const std::string &dir, int id, TileBorder &border, std::string &error);

struct Rescues
{
    std::vector<std::vector<std::size_t>> spares; ///< per tile of the manifest, the spare surfels kept
    std::uint64_t surfels = 0;                    ///< their count
    std::uint64_t orphans = 0;                    ///< core points no tile took over
    std::uint64_t uncovered = 0;                  ///< ... of which no kept ellipse covers
};

/// Reads every tile's border and result and finds the spare surfels to keep.
bool FindRescues(const std::string &dir, const Manifest &manifest, Rescues &rescues, std::string &error);

/// Tile `id`'s part of the merged output: its result, then its spare surfels `rescued`.
bool ReadTileOutput(const std::string &dir, int id, const std::vector<std::size_t> &rescued,
                    std::vector<surfel_io::SurfelRecord> &records, std::string &error);

} // namespace gstile

#endif
