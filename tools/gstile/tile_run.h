// `gstile run`: one tile resampled on its own, its owned surfels written as its result.
//
// Ownership rule: a cluster (and its surfel) belongs to the tile whose core holds the cluster's
// anchor, its member with the smallest input index. Every point lies in exactly one core, so
// where the tiles cluster a region alike (far enough inside their halos) each cluster is kept by
// exactly one tile; the rule reads integers the split stored, never float positions, so no
// rounding can make two tiles both keep, or both drop, the same cluster.
#ifndef GSTILE_TILE_RUN_H
#define GSTILE_TILE_RUN_H

#include <cstdint>
#include <string>
#include <vector>

#include <vcg_ext/gaussphere/oriented_point_mesh.h>
#include <vcg_ext/gaussphere/resampling.h>

#include "border_points.h"
#include "manifest.h"
#include "target_share.h"
#include "tile_files.h"

// The resampler on the tiles' meshes is compiled once, in tile_run.cpp, for every program and
// test that runs tiles.
extern template vcg::gaussphere::ResamplingResult vcg::gaussphere::ResamplePointSet<vcg::gaussphere::OrientedPointMesh>(
    const vcg::gaussphere::OrientedPointMesh &, const vcg::gaussphere::ResamplingParams &, vcg::CallBackPos *);

namespace gstile {

struct TileRunFigures
{
    int id = 0;
    std::uint64_t corePoints = 0, haloPoints = 0;
    int clusters = 0;             ///< surfels the resampler made from core and halo
    int owned = 0;                ///< ... of which the tile keeps
    std::uint64_t ownedMembers = 0; ///< points the kept surfels represent
    double seconds = 0;
    bool seam = false;            ///< run after the seam step, beside its neighbours' snapshots
    vcg::gaussphere::ResamplingStats stats;
};

/// For each surfel of `result`, whether its anchor is a core point: `indices` are the input
/// indices of the tile's core points followed by its halo points, in the resampler's vertex order.
std::vector<bool> OwnedSurfels(const vcg::gaussphere::ResamplingResult &result,
                               const std::vector<std::uint64_t> &indices, std::uint64_t corePoints);

/// The border record of a tile's run (border_points.h) from its points' input indices and the
/// points as resampled (core points first); `spares` receives the surfels it leaves to other tiles that hold
/// some of its core points, in the order of border.leftPoints.
TileBorder BorderOf(const vcg::gaussphere::ResamplingResult &result, const std::vector<std::uint64_t> &indices,
                    const vcg::gaussphere::OrientedPointMesh &points, std::uint64_t corePoints,
                    const std::vector<bool> &owned, std::vector<int> &spares);

/// Resamples tile `id` of the tile directory `dir` and writes its border record and spare surfels
/// (border_points.h), then TilePath(dir, id, ".surfel"). With a
/// target (manifest.targetCount), to the count of its share (ReadShare), and then its outcome
/// (WriteOutcome). Errors name the tile.
bool RunTile(const std::string &dir, const Manifest &manifest, int id, TileRunFigures &figures, std::string &error);

/// What a probe of a tile found.
struct ProbeFigures
{
    int id = 0;
    bool probed = false;  ///< false: the tile's probe held what the share needs already
    ProbeNeed need;
    LevelCount counts;    ///< need.recordCap == 0: the counts at need.level
    std::size_t steps = 0; ///< else: the splits or merges recorded
    double seconds = 0;
};

/// With a target: resamples tile `id` as the probes so far need (target_share.h: its counts at a
/// level, or its splits or merges at the level) and adds what it found to its probe; nothing when the tile
/// has it already or the shares are decided.
bool ProbeTile(const std::string &dir, const Manifest &manifest, int id, ProbeFigures &figures, std::string &error);

/// One line of figures for a probed tile, the `position`-th (from 1) of `tileCount`.
std::string ProbeLine(const ProbeFigures &figures, std::size_t position, std::size_t tileCount);

/// One line of figures for a finished tile, the `position`-th (from 1) of `tileCount`.
std::string FiguresLine(const TileRunFigures &figures, std::size_t position, std::size_t tileCount);

} // namespace gstile

#endif
