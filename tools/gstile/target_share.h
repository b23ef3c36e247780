// A target count shared out over the tiles as the whole run would spend it (docs/tiling.md,
// "Size controls").
//
// The whole run reaches its target from the clusters of one Gaussian sphere level, split where
// the L2,1 error is largest or merged where neighbours are most alike, in one queue over the
// whole input: a detailed region gets more surfels than a flat one of as many points. The tiles
// follow it:
//   1. `gstile probe`, in rounds: each tile counts the clusters it makes and owns at the levels
//      the level search asks for (LevelSearch over the tiles' summed owned counts: the level the
//      whole input gives), then records, at that level, its splits (or, when the level gives too
//      many, its merges) in order: their priorities and which of them add (take away) a cluster
//      it owns;
//   2. `gstile share`: the steps of all tiles taken in priority order until the owned counts
//      sum to the target (one threshold on the priority for every tile, as in the whole run's
//      single queue); each tile runs at the level with its clusters plus its splits taken (less
//      its merges taken), and should keep its clusters owned plus (less) the owned ones its steps
//      add (take away).
// `gstile run` then resamples each tile at the level to its count and keeps what it owns. It
// records what it kept (TileOutcome), and
//   3. `gstile adjust`: the first time, the whole run's rounds of exchanges for the largest
//      error are shared over the tiles, from the largest distance among its core points each
//      tile's run recorded before and after each of its exchanges (ShareExchangeRounds); the
//      tiles that kept more than their part run again with it. The next time, once every tile
//      ran at its part, the limits the crease fit after the exchanges is judged against are
//      shared, from each tile's report of its highest figures on entry to it
//      (WholeScanCreaseFitLimits, crease_fit_limits.h): every tile runs again with them. Each
//      tile whose kept surfels (its
//      result and the spare surfels the merge keeps for its border points, border_points.h)
//      missed its share (the exchanges and the rescued surfels move a few) gets a new run count,
//      interpolated between the counts tried (or extrapolated by the made-to-owned ratio of the
//      last one), up to kAdjustRounds times a tile, and only those tiles run again; `all` and the
//      Dask driver adjust until no tile is left to run.
// What a probe does next is decided from the probes written so far (DecideShares), so any
// number of workers can probe in any order, and a stopped run resumes where it stopped.
#ifndef GSTILE_TARGET_SHARE_H
#define GSTILE_TARGET_SHARE_H

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <vcg_ext/gaussphere/size_control/crease_fit_limits.h>

#include "manifest.h"

namespace gstile {

/// A tile's clusters at one level.
struct LevelCount
{
    int level = 0;
    std::uint64_t clusters = 0; ///< clusters the tile's points make at the level, halo included
    std::uint64_t owned = 0;    ///< ... of which the tile owns (tile_run.h)
};

/// One of a tile's splits towards a count (vcg::gaussphere::CountSplit): its priority, and whether
/// the cluster it adds is one the tile owns. Along a record the priorities (error, then size)
/// never rise: the recorded priority is the lowest so far (rounding in the float normals can put
/// a part's computed error a hair above its cluster's).
struct SplitKey
{
    double error = 0;
    int size = 0;
    bool addsOwned = false;
};

/// Whether split a comes before split b: the larger error, then the larger cluster.
inline bool SplitBefore(const SplitKey &a, const SplitKey &b)
{
    return a.error != b.error ? a.error > b.error : a.size > b.size;
}

/// One of a tile's merges towards a count (vcg::gaussphere::CountMerge): its cost, and whether it
/// takes away a cluster the tile owns (of the two merged, the one whose anchor comes second: the
/// merged cluster keeps the first anchor). Along a record the costs never fall: the recorded cost
/// is the highest so far (a merged cluster's pairs can cost less than a merge before them).
struct MergeKey
{
    double cost = 0;
    bool removesOwned = false;
};

/// Whether merge a comes before merge b: the lower cost.
inline bool MergeBefore(const MergeKey &a, const MergeKey &b) { return a.cost < b.cost; }

/// What a tile's probes found.
struct TileProbe
{
    int id = 0;
    std::vector<LevelCount> levels;
    int recordLevel = 0;           ///< the level of `splits` or `merges` (0: none recorded)
    std::uint64_t recordCap = 0;   ///< the steps asked for
    std::vector<SplitKey> splits;  ///< in order; fewer than recordCap when the tile had no more
    std::vector<MergeKey> merges;  ///< ... when the level gives more clusters than the target

    const LevelCount *At(int level) const;
    std::size_t Steps() const { return splits.size() + merges.size(); }
};

/// What the next probe of a tile must find: its counts at `level` (recordCap 0), or its first
/// recordCap steps (splits or merges, as the level's count lies below or above the target) there.
struct ProbeNeed
{
    int level = 0;
    std::uint64_t recordCap = 0;
    bool merges = false; ///< the steps are merges
};

/// Whether `probe` holds what `need` asks for.
bool Satisfies(const TileProbe &probe, const ProbeNeed &need);

/// A run count tried and the surfels the run kept.
struct TileTrial
{
    std::uint64_t target = 0, owned = 0;
};

struct TileShare
{
    int id = 0;
    int rounds = -1;          ///< rounds of exchanges its runs make (-1: the whole run's, not shared yet)
    std::uint64_t owned = 0;  ///< the surfels the tile should keep; the shares sum to the target
                              ///< (less when the tiles have fewer clusters to split)
    std::uint64_t target = 0; ///< the count its run resamples to, halo included (0: it keeps nothing)
    std::vector<TileTrial> tried; ///< the runs adjusted from, in the order run
    /// From the seam step on (seam.h): the largest distance its seam rounds lower to, model units,
    /// the largest the other tiles' rounds reached (0: its own).
    double seamTarget = 0;
};

/// The shares, once the probes hold all they need: the level every tile runs at and each tile's share.
struct Shares
{
    std::uint64_t target = 0;
    int level = 0;
    std::vector<TileShare> tiles;
    /// The whole scan's figures every tile's crease fit is judged against (WholeScanCreaseFitLimits),
    /// given once the rounds of exchanges are shared.
    vcg::gaussphere::CreaseFitLimits creaseFitLimits;
    /// Whether the seam step was taken (seam.h): every tile runs with its neighbours' snapshots
    /// around it from then on.
    bool seam = false;
    /// Whether the tiles' rounds of exchanges are shared (ShareExchangeRounds gives every tile
    /// its rounds at once).
    bool RoundsShared() const
    {
        return std::any_of(tiles.begin(), tiles.end(), [](const TileShare &t) { return t.rounds >= 0; });
    }
};

/// The decision the probes so far allow: the next probe, or the shares.
struct ShareDecision
{
    bool shared = false;
    std::vector<ProbeNeed> needs; ///< when not shared: one per tile of the manifest, in its order
    Shares shares;                ///< when shared
};

/// The fewest steps a tile records: a tile owning a small part of the scan still records enough
/// to take its part of the threshold.
constexpr std::uint64_t kMinRecordCap = 64;

/// Decides from `probes` (one per tile of `manifest`, in its order; a tile not probed yet has no
/// levels) with the level search of the tiles' parameters (start level, mergeWithin). At the level
/// found, each tile records twice its part of the clusters missing or in excess (by the clusters
/// it owns there) times its ratio of made to owned clusters, at least kMinRecordCap: its record
/// interleaves steps on its halo's clusters with its own. A record cut short by its cap and taken
/// whole may hide steps before the threshold: that tile records twice as many, until the
/// threshold falls inside every cut record.
ShareDecision DecideShares(const Manifest &manifest, int startLevel, double mergeWithin,
                           const std::vector<TileProbe> &probes);

/// What `gstile run` kept of a tile with a target, beside its result.
struct TileOutcome
{
    std::uint64_t target = 0, owned = 0; ///< the run's count and the surfels it kept (a TileTrial)
    int rounds = -1;                     ///< its rounds of exchanges (TileShare::rounds)
    /// The largest distance of its core points to the blended surface before the exchanges and
    /// after each it kept (vcg::gaussphere::ResamplingResult::exchangeMaxima), never rising.
    std::vector<double> maxima;
    vcg::gaussphere::CreaseFitLimits limits; ///< what its crease fit was judged against (Shares::creaseFitLimits)
    /// Its core points' highest figures on entry to the crease fit, HighestToReport of each.
    vcg::gaussphere::CreaseFitEntry entry;
    bool seam = false; ///< run with its neighbours' seam snapshots around it (Shares::seam)
};

/// The highest figures of its core points a tile reports on entry to its crease fit, for a scan of
/// `points` points: the points at and above the nearest rank of the 99.9th percentile, so that the
/// reports of all tiles hold the whole scan's percentile.
std::size_t HighestToReport(std::uint64_t points);

/// The whole scan's crease fit limits, the 99.9th percentiles of its `points` points, from the
/// reports of the tiles' runs at their part of the rounds of exchanges (`outcomes`; those without
/// a report are passed over). Not from runs with the whole run's rounds: 13 tiles that each take
/// 16 exchanges lower the dragon's 99.9th percentile of the distance at 10,000 surfels by 11 %.
vcg::gaussphere::CreaseFitLimits WholeScanCreaseFitLimits(const std::vector<TileOutcome> &outcomes, std::uint64_t points);

/// The whole run's `rounds` of exchanges shared over the tiles, from each tile's `maxima` (its
/// TileOutcome's, with the whole run's rounds): the whole run's next exchange is at its worst
/// point, so each round goes to the tile whose largest distance is highest after the rounds it has,
/// and the sharing ends when that tile kept no more exchanges (the whole run would find none).
/// Returns each tile's rounds.
std::vector<int> ShareExchangeRounds(const std::vector<std::vector<double>> &maxima, int rounds);

/// Whether `outcome` is of a run at share.rounds: made with them, or with the whole run's rounds
/// (-1, before they were shared) and no more exchanges kept than share.rounds.
bool RanAtRounds(const TileOutcome &outcome, const TileShare &share);

/// New run counts a tile gets at most: one or two bring nearly every tile onto its share
/// (docs/tiling.md), and each costs a run of the tile.
constexpr std::size_t kAdjustRounds = 3;

bool WriteProbe(const std::string &dir, const TileProbe &probe, std::string &error);
/// False, with no error, when the tile has no probe yet.
bool ReadProbe(const std::string &dir, int id, TileProbe &probe, std::string &error);
/// Every tile's probe, in the manifest's order (a tile without one has only its id set).
bool ReadProbes(const std::string &dir, const Manifest &manifest, std::vector<TileProbe> &probes, std::string &error);

/// DecideShares on the probes in `dir` (read into `probes`), with the parameters of the manifest.
bool DecideFromProbes(const std::string &dir, const Manifest &manifest, std::vector<TileProbe> &probes,
                      ShareDecision &decision, std::string &error);

/// The tiles whose probe lacks what the decision needs; none once the shares are written.
bool TilesToProbe(const std::string &dir, const Manifest &manifest, std::vector<int> &ids, std::string &error);

/// Writes SharesPath(dir) from the probes when they allow it and it does not exist yet (`written`
/// then true; the shares adjusted so far are not lost to a second `gstile share`). `decision`
/// receives the shares, or what the probes still need.
bool WriteShares(const std::string &dir, const Manifest &manifest, ShareDecision &decision, bool &written,
                 std::string &error);
bool ReadShares(const std::string &dir, Shares &shares, std::string &error);
/// The shares, and the share of tile `id`, from SharesPath(dir); an error says to probe and share first.
bool ReadShare(const std::string &dir, int id, Shares &shares, TileShare &share, std::string &error);

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
    std::vector<int> rerun;   ///< tiles to run again: a new count, rounds of exchanges or crease fit limits
    vcg::gaussphere::CreaseFitLimits sharedLimits; ///< the crease fit limits this round shared (not given: none)
    bool seamTaken = false; ///< this round took the seam step
};

/// Reads every tile's outcome, border record and the shares, adjusts the tiles whose kept surfels
/// (rescued ones included) missed their share and writes SharesPath(dir). The first time it also
/// shares the rounds of exchanges (ShareExchangeRounds; none at --exchanges 0): a tile that kept
/// more exchanges than its part runs again (RanAtRounds); the second time the crease fit limits;
/// the first time after that when no tile has to run again, it takes the seam step (seam.h: the
/// snapshots, then every tile runs again). It writes no outcome, so a stop before SharesPath(dir)
/// is written leaves the tile directory as it found it. An error names a tile that has not run at
/// its share's count.
bool AdjustShares(const std::string &dir, const Manifest &manifest, AdjustFigures &figures, std::string &error);

/// The tiles whose result or border record is missing, or whose run was at another count, rounds
/// of exchanges, crease fit limits or seam step than their share's.
bool PendingTiles(const std::string &dir, const Manifest &manifest, std::vector<int> &pending, std::string &error);

/// False, with an error naming the first of them, when PendingTiles lists a tile.
bool RequireRunAtShares(const std::string &dir, const Manifest &manifest, std::string &error);

} // namespace gstile

#endif
