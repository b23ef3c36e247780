// A target count shared out over the tiles by their detail (docs/tiling.md, "Size controls").
//
// The whole run reaches its target from the clusters of one Gaussian sphere level, split or merged
// where the error is largest: a detailed region gets more surfels than a flat one of as many
// points. The tiles follow it in two rounds:
//   1. `gstile probe`: each tile at the level, counting the clusters it makes and those it owns;
//   2. `gstile share`: the target shared out in proportion to the owned counts (largest remainder,
//      so the shares sum to the target exactly), each share turned into a count for the tile's
//      whole run, halo included, by the tile's ratio of made to owned clusters.
// `gstile run` then resamples each tile to its count and keeps what it owns: about its share.
#ifndef GSTILE_TARGET_SHARE_H
#define GSTILE_TARGET_SHARE_H

#include <cstdint>
#include <string>
#include <vector>

#include "manifest.h"

namespace gstile {

struct TileProbe
{
    int id = 0;
    std::uint64_t clusters = 0; ///< clusters the tile's points make at the level, halo included
    std::uint64_t owned = 0;    ///< ... of which the tile owns (tile_run.h)
};

struct TileShare
{
    int id = 0;
    std::uint64_t owned = 0;  ///< the surfels the tile should keep; the shares sum to the target
    std::uint64_t target = 0; ///< the count its run resamples to, halo included (0: it keeps nothing)
};

/// The shares of manifest.targetCount over `probes` (one per tile of the manifest, in its order),
/// each tile's run count capped by its points.
std::vector<TileShare> ShareTarget(const Manifest &manifest, const std::vector<TileProbe> &probes);

bool WriteProbe(const std::string &dir, const TileProbe &probe, std::string &error);
bool ReadProbe(const std::string &dir, int id, TileProbe &probe, std::string &error);

/// Reads every tile's probe, shares the target and writes SharesPath(dir).
bool WriteShares(const std::string &dir, const Manifest &manifest, std::vector<TileShare> &shares, std::string &error);
/// The share of tile `id`, from SharesPath(dir); an error says to run probe and share first.
bool ReadShare(const std::string &dir, int id, TileShare &share, std::string &error);

std::string SharesPath(const std::string &dir);

} // namespace gstile

#endif
