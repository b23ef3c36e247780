// A target count shared out over the tiles by their detail (docs/tiling.md, "Size controls").
//
// The whole run reaches its target from the clusters of one Gaussian sphere level, split or merged
// where the error is largest: a detailed region gets more surfels than a flat one of as many
// points. The tiles follow it in two rounds:
//   1. `gstile probe`: each tile at the level, counting the clusters it makes and those it owns;
//   2. `gstile share`: the target shared out in proportion to the owned counts (largest remainder,
//      so the shares sum to the target exactly), each share turned into a count for the tile's
//      whole run, halo included, by the tile's ratio of made to owned clusters.
// `gstile run` then resamples each tile to its count and keeps what it owns, near its share: the
// ratio of made to owned clusters shifts between the level and the tile's count. It records what
// it kept (TileOutcome), and
//   3. `gstile adjust`: each tile whose kept surfels (its result and the spare surfels the merge
//      keeps for its border points, border_points.h) missed its share gets a new run count,
//      interpolated between the counts tried (or extrapolated by the made-to-owned ratio of the
//      last one), up to kAdjustRounds times a tile, and only those tiles run again; `all` and
//      the Dask driver adjust until no tile is left to run.
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

/// A run count tried and the surfels the run kept.
struct TileTrial
{
    std::uint64_t target = 0, owned = 0;
};

struct TileShare
{
    int id = 0;
    std::uint64_t owned = 0;  ///< the surfels the tile should keep; the shares sum to the target
    std::uint64_t target = 0; ///< the count its run resamples to, halo included (0: it keeps nothing)
    std::vector<TileTrial> tried; ///< the runs adjusted from, in the order run
};

/// What `gstile run` kept of a tile with a target, beside its result.
typedef TileTrial TileOutcome;

/// New run counts a tile gets at most: one or two bring nearly every tile onto its share
/// (docs/tiling.md), and each costs a run of the tile.
constexpr std::size_t kAdjustRounds = 3;

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

bool WriteOutcome(const std::string &dir, int id, const TileOutcome &outcome, std::string &error);
/// False, with no error, when the tile has no outcome yet.
bool ReadOutcome(const std::string &dir, int id, TileOutcome &outcome, std::string &error);

/// The next run count of `share` after `outcome` of its run at share.target (appended to tried
/// unless that count was tried before), at most `points`; returns whether the tile should run again
/// at the new share.target. After kAdjustRounds new counts, or when no untried count lies between
/// the counts that kept too few and too many, that is the count tried that came nearest (false
/// when the last run is that one).
bool AdjustShare(TileShare &share, const TileOutcome &outcome, std::uint64_t points);

struct AdjustFigures
{
    std::uint64_t kept = 0;   ///< surfels the merge keeps of the tiles' last runs, rescued ones included
    std::vector<int> rerun;   ///< tiles whose run count changed, to run again
};

/// Reads every tile's outcome, border record and the shares, adjusts the tiles whose kept surfels
/// (rescued ones included) missed their share and writes SharesPath(dir). An error names a tile
/// that has not run at its share's count.
bool AdjustShares(const std::string &dir, const Manifest &manifest, AdjustFigures &figures, std::string &error);

/// The tiles whose result or border record is missing, or whose run was at another count than
/// their share's.
bool PendingTiles(const std::string &dir, const Manifest &manifest, std::vector<int> &pending, std::string &error);

/// False, with an error naming the first of them, when PendingTiles lists a tile.
bool RequireRunAtShares(const std::string &dir, const Manifest &manifest, std::string &error);

} // namespace gstile

#endif
