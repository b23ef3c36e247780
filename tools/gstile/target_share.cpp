#include "target_share.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include <vcg_ext/gaussphere/size_control/level_search.h>
#include <vcg_ext/surfel/percentile.h>

#include "border_points.h"
#include "seam.h"
#include "tile_files.h"
#include "tile_params.h"

using nlohmann::json;

namespace gstile {

namespace {

/// Bound on the counts a probe file may hold: far beyond any scan, far below overflow when doubled.
constexpr std::uint64_t kMaxCount = std::uint64_t(1) << 48;

using vcg::gaussphere::LevelSearch;

constexpr const char *kRunProbeAndShare =
    "with a target, run `gstile probe` on the tiles `gstile tiles DIR --to-probe` lists until it lists none, then `gstile share`";

} // namespace

std::string SharesPath(const std::string &dir) { return dir + "/shares.json"; }

const LevelCount *TileProbe::At(int level) const
{
    for (const LevelCount &c : levels)
        if (c.level == level) return &c;
    return nullptr;
}

bool Satisfies(const TileProbe &probe, const ProbeNeed &need)
{
    if (need.recordCap == 0) return probe.At(need.level) != nullptr;
    // A record of the other kind (a stale or edited file) holds none of the steps asked for.
    if (need.merges ? !probe.splits.empty() : !probe.merges.empty()) return false;
    // A record shorter than its cap holds every step the tile has.
    return probe.recordLevel == need.level && (probe.recordCap >= need.recordCap || probe.Steps() < probe.recordCap);
}

namespace {

/// The positions (in the manifest's order) of the tiles whose probe lacks what `needs` asks.
std::vector<std::size_t> TilesLacking(const std::vector<TileProbe> &probes, const std::vector<ProbeNeed> &needs)
{
    std::vector<std::size_t> lacking;
    for (std::size_t t = 0; t < probes.size(); ++t)
        if (!Satisfies(probes[t], needs[t])) lacking.push_back(t);
    return lacking;
}

/// The tiles' steps at the level (`steps` of each probe: its splits or its merges) taken in
/// priority order (`before`; ties by tile, then by order within it) until the owned clusters reach
/// the target, or the records run out: `taken` and `changedOwned` (the steps that add or take
/// away an owned cluster, `changesOwned`) per tile.
template <class Key, class Before>
void TakeSteps(const std::vector<TileProbe> &probes, std::vector<Key> TileProbe::*steps, bool Key::*changesOwned,
               Before before, std::uint64_t owned, std::uint64_t target, std::vector<std::uint64_t> &taken,
               std::vector<std::uint64_t> &changedOwned)
{
    struct Entry
    {
        const Key *key;
        std::size_t tile, order;
    };
    std::vector<Entry> entries;
    for (std::size_t t = 0; t < probes.size(); ++t)
        for (std::size_t k = 0; k < (probes[t].*steps).size(); ++k) entries.push_back({&(probes[t].*steps)[k], t, k});
    // Along a tile's record no step comes before the one ahead of it (SplitKey, MergeKey), so what
    // the order takes of each tile is a prefix of its record: the steps its run at the count makes.
    std::sort(entries.begin(), entries.end(), [&before](const Entry &a, const Entry &b) {
        if (before(*a.key, *b.key)) return true;
        if (before(*b.key, *a.key)) return false;
        return a.tile != b.tile ? a.tile < b.tile : a.order < b.order;
    });
    taken.assign(probes.size(), 0);
    changedOwned.assign(probes.size(), 0);
    const bool up = owned < target;
    for (std::size_t e = 0; e < entries.size() && owned != target; ++e) {
        ++taken[entries[e].tile];
        if (entries[e].key->*changesOwned) {
            ++changedOwned[entries[e].tile];
            owned = up ? owned + 1 : owned - 1;
        }
    }
}

} // namespace

ShareDecision DecideShares(const Manifest &manifest, int startLevel, double mergeWithin,
                           const std::vector<TileProbe> &probes)
{
    ShareDecision decision;
    const auto lacking = [&probes, &decision]() { return !TilesLacking(probes, decision.needs).empty(); };
    LevelSearch search(manifest.targetCount, startLevel);
    while (const int level = search.Next()) {
        decision.needs.assign(probes.size(), ProbeNeed{level, 0});
        if (lacking()) return decision;
        std::uint64_t owned = 0;
        for (const TileProbe &p : probes) owned += p.At(level)->owned;
        search.Tell(owned);
    }
    const int level = search.Level(mergeWithin);
    std::vector<LevelCount> counts;
    std::uint64_t owned = 0;
    for (const TileProbe &p : probes) {
        counts.push_back(*p.At(level));
        owned += counts.back().owned;
    }
    decision.shares.target = manifest.targetCount;
    decision.shares.level = level;
    const bool merging = owned > manifest.targetCount;
    if (owned != manifest.targetCount) {
        const std::uint64_t off = merging ? owned - manifest.targetCount : manifest.targetCount - owned;
        decision.needs.clear();
        for (std::size_t t = 0; t < probes.size(); ++t) {
            // Its part of the clusters missing or in excess (by its owned ones) times its made-to-owned ratio.
            const unsigned __int128 part = owned ? ((unsigned __int128)off * counts[t].clusters + owned - 1) / owned : off;
            std::uint64_t cap = std::max(kMinRecordCap, std::uint64_t(std::min<unsigned __int128>(2 * part, kMaxCount)));
            if (probes[t].recordLevel == level) cap = std::max(cap, probes[t].recordCap); // grown before
            decision.needs.push_back({level, cap, merging});
        }
        if (lacking()) return decision;
    }
    std::vector<std::uint64_t> taken(probes.size(), 0), changedOwned(probes.size(), 0);
    if (merging)
        TakeSteps(probes, &TileProbe::merges, &MergeKey::removesOwned, MergeBefore, owned, manifest.targetCount, taken,
                  changedOwned);
    else if (owned < manifest.targetCount)
        TakeSteps(probes, &TileProbe::splits, &SplitKey::addsOwned, SplitBefore, owned, manifest.targetCount, taken,
                  changedOwned);
    bool grows = false;
    for (std::size_t t = 0; t < probes.size(); ++t) {
        const TileProbe &p = probes[t];
        if (taken[t] > 0 && taken[t] == p.Steps() && p.Steps() == p.recordCap) {
            decision.needs[t].recordCap = 2 * p.recordCap;
            grows = true;
        }
    }
    if (grows) return decision;
    for (std::size_t t = 0; t < probes.size(); ++t) {
        TileShare share;
        share.id = manifest.tiles[t].id;
        share.owned = merging ? counts[t].owned - changedOwned[t] : counts[t].owned + changedOwned[t];
        const TileEntry &tile = manifest.tiles[t];
        const std::uint64_t made = merging ? counts[t].clusters - taken[t] : counts[t].clusters + taken[t];
        share.target = share.owned ? std::min(made, tile.corePoints + tile.haloPoints) : 0;
        decision.shares.tiles.push_back(share);
    }
    decision.shared = true;
    return decision;
}

bool WriteProbe(const std::string &dir, const TileProbe &probe, std::string &error)
{
    json levels = json::array(), errors = json::array(), sizes = json::array(), addsOwned = json::array(),
         costs = json::array(), removesOwned = json::array();
    for (const LevelCount &c : probe.levels) levels.push_back({c.level, c.clusters, c.owned});
    for (const SplitKey &k : probe.splits) {
        errors.push_back(k.error);
        sizes.push_back(k.size);
        addsOwned.push_back(k.addsOwned ? 1 : 0);
    }
    for (const MergeKey &k : probe.merges) {
        costs.push_back(k.cost);
        removesOwned.push_back(k.removesOwned ? 1 : 0);
    }
    return WriteJsonFile(TilePath(dir, probe.id, ".probe"),
                         {{"levels", levels},
                          {"record_level", probe.recordLevel},
                          {"record_cap", probe.recordCap},
                          {"split_error", errors},
                          {"split_size", sizes},
                          {"split_adds_owned", addsOwned},
                          {"merge_cost", costs},
                          {"merge_removes_owned", removesOwned}},
                         error);
}

bool ReadProbe(const std::string &dir, int id, TileProbe &probe, std::string &error)
{
    const std::string path = TilePath(dir, id, ".probe");
    probe = TileProbe();
    probe.id = id;
    if (!std::ifstream(path)) return false;
    json j;
    if (!ReadJsonFile(path, kRunProbeAndShare, j, error)) return false;
    try {
        for (const json &c : j.at("levels")) {
            const LevelCount count{c.at(0).get<int>(), c.at(1).get<std::uint64_t>(), c.at(2).get<std::uint64_t>()};
            if (count.level < LevelSearch::kMinLevel || count.level > LevelSearch::kMaxLevel ||
                count.owned > count.clusters || count.clusters > kMaxCount)
                throw std::runtime_error("a level's counts are out of range");
            probe.levels.push_back(count);
        }
        probe.recordLevel = j.at("record_level").get<int>();
        probe.recordCap = j.at("record_cap").get<std::uint64_t>();
        if (probe.recordCap > kMaxCount) throw std::runtime_error("the record cap is out of range");
        const json &errors = j.at("split_error"), &sizes = j.at("split_size"), &addsOwned = j.at("split_adds_owned");
        const json &costs = j.at("merge_cost"), &removesOwned = j.at("merge_removes_owned");
        if (errors.size() != sizes.size() || errors.size() != addsOwned.size() || costs.size() != removesOwned.size())
            throw std::runtime_error("the step records differ in length");
        if ((!errors.empty() && !costs.empty()) || errors.size() + costs.size() > probe.recordCap)
            throw std::runtime_error("the step records hold both splits and merges, or exceed their cap");
        for (std::size_t k = 0; k < errors.size(); ++k) {
            const SplitKey key{errors[k].get<double>(), sizes[k].get<int>(), addsOwned[k].get<int>() != 0};
            if (k > 0 && SplitBefore(key, probe.splits.back()))
                throw std::runtime_error("the split priorities rise"); // JSON numbers are finite
            probe.splits.push_back(key);
        }
        for (std::size_t k = 0; k < costs.size(); ++k) {
            const MergeKey key{costs[k].get<double>(), removesOwned[k].get<int>() != 0};
            if (k > 0 && MergeBefore(key, probe.merges.back())) throw std::runtime_error("the merge costs fall");
            probe.merges.push_back(key);
        }
        if (!probe.merges.empty()) { // merges take clusters away: no more than the level has
            const LevelCount *level = probe.At(probe.recordLevel);
            const auto ownedTaken = std::uint64_t(std::count_if(probe.merges.begin(), probe.merges.end(),
                                                                [](const MergeKey &m) { return m.removesOwned; }));
            if (level == nullptr || probe.merges.size() >= level->clusters || ownedTaken > level->owned)
                throw std::runtime_error("the merges do not fit the clusters of their level");
        }
    } catch (const std::exception &e) {
        error = path + " is not valid: " + e.what();
        return false;
    }
    return true;
}

bool ReadProbes(const std::string &dir, const Manifest &manifest, std::vector<TileProbe> &probes, std::string &error)
{
    probes.assign(manifest.tiles.size(), TileProbe());
    for (std::size_t t = 0; t < probes.size(); ++t)
        if (!ReadProbe(dir, manifest.tiles[t].id, probes[t], error) && !error.empty()) return false;
    return true;
}

bool DecideFromProbes(const std::string &dir, const Manifest &manifest, std::vector<TileProbe> &probes,
                      ShareDecision &decision, std::string &error)
{
    vcg::gaussphere::ResamplingParams param;
    if (!TileParams(manifest, 0, param, error) || !ReadProbes(dir, manifest, probes, error)) return false;
    decision = DecideShares(manifest, param.subdivisionLevel, param.tuning.mergeWithin, probes);
    return true;
}

bool TilesToProbe(const std::string &dir, const Manifest &manifest, std::vector<int> &ids, std::string &error)
{
    ids.clear();
    if (std::ifstream(SharesPath(dir))) return true;
    std::vector<TileProbe> probes;
    ShareDecision decision;
    if (!DecideFromProbes(dir, manifest, probes, decision, error)) return false;
    if (decision.shared) return true;
    for (const std::size_t t : TilesLacking(probes, decision.needs)) ids.push_back(manifest.tiles[t].id);
    return true;
}

namespace {

json LimitsJson(const vcg::gaussphere::CreaseFitLimits &limits)
{
    return {{"distance", limits.distance}, {"normal_error", limits.normalError}};
}

/// The limits of `j` (not given when absent).
vcg::gaussphere::CreaseFitLimits LimitsOf(const json &j)
{
    vcg::gaussphere::CreaseFitLimits limits;
    if (j.is_null()) return limits;
    limits.given = true;
    limits.distance = j.at("distance").get<double>();
    limits.normalError = j.at("normal_error").get<double>();
    if (!(limits.distance >= 0 && limits.normalError >= 0))
        throw std::runtime_error("the crease fit limits are negative");
    return limits;
}

bool WriteShareList(const std::string &dir, const Shares &shares, std::string &error)
{
    json list = json::array();
    for (const TileShare &s : shares.tiles) {
        json tried = json::array();
        for (const TileTrial &t : s.tried) tried.push_back({t.target, t.owned});
        list.push_back({{"id", s.id}, {"owned", s.owned}, {"target", s.target}, {"rounds", s.rounds}, {"tried", tried}});
        if (s.seamTarget > 0) list.back()["seam_target"] = s.seamTarget;
    }
    json j = {{"target", shares.target}, {"level", shares.level}, {"tiles", list}};
    if (shares.creaseFitLimits.given) j["crease_fit_limits"] = LimitsJson(shares.creaseFitLimits);
    if (shares.seam) j["seam"] = true;
    return WriteJsonFile(SharesPath(dir), j, error);
}

/// The trial that kept the count nearest to the share (the latest of equals).
const TileTrial &NearestTrial(const TileShare &share)
{
    const auto miss = [&share](const TileTrial &t) {
        return t.owned > share.owned ? t.owned - share.owned : share.owned - t.owned;
    };
    const TileTrial *nearest = &share.tried.front();
    for (const TileTrial &t : share.tried)
        if (miss(t) <= miss(*nearest)) nearest = &t;
    return *nearest;
}

} // namespace

bool ReadShares(const std::string &dir, Shares &shares, std::string &error)
{
    json j;
    if (!ReadJsonFile(SharesPath(dir), kRunProbeAndShare, j, error)) return false;
    try {
        shares = Shares();
        shares.target = j.at("target").get<std::uint64_t>();
        shares.level = j.at("level").get<int>();
        shares.creaseFitLimits = LimitsOf(j.value("crease_fit_limits", json()));
        shares.seam = j.value("seam", false);
        for (const json &t : j.at("tiles")) {
            TileShare share;
            share.id = t.at("id").get<int>();
            share.owned = t.at("owned").get<std::uint64_t>();
            share.target = t.at("target").get<std::uint64_t>();
            share.rounds = t.at("rounds").get<int>();
            if (share.rounds < -1) throw std::runtime_error("a tile's rounds of exchanges are out of range");
            share.seamTarget = t.value("seam_target", 0.0);
            if (!(share.seamTarget >= 0)) throw std::runtime_error("a tile's seam target is negative");
            for (const json &trial : t.value("tried", json::array()))
                share.tried.push_back({trial.at(0).get<std::uint64_t>(), trial.at(1).get<std::uint64_t>()});
            shares.tiles.push_back(share);
        }
    } catch (const std::exception &e) {
        error = SharesPath(dir) + " is not valid: " + e.what();
        return false;
    }
    return true;
}

bool WriteShares(const std::string &dir, const Manifest &manifest, ShareDecision &decision, bool &written,
                 std::string &error)
{
    written = false;
    if (std::ifstream(SharesPath(dir))) {
        decision = ShareDecision();
        decision.shared = true;
        return ReadShares(dir, decision.shares, error);
    }
    std::vector<TileProbe> probes;
    if (!DecideFromProbes(dir, manifest, probes, decision, error)) return false;
    if (!decision.shared) return true;
    written = WriteShareList(dir, decision.shares, error);
    return written;
}

bool ReadShare(const std::string &dir, int id, Shares &shares, TileShare &share, std::string &error)
{
    if (!ReadShares(dir, shares, error)) return false;
    for (const TileShare &s : shares.tiles) {
        if (s.id != id) continue;
        share = s;
        return true;
    }
    error = SharesPath(dir) + " has no share for tile " + std::to_string(id);
    return false;
}

bool WriteOutcome(const std::string &dir, int id, const TileOutcome &outcome, std::string &error)
{
    json j = {{"target", outcome.target}, {"owned", outcome.owned}, {"rounds", outcome.rounds},
              {"maxima", outcome.maxima}, {"highest_distances", outcome.entry.distances},
              {"highest_normal_errors", outcome.entry.normalErrors}};
    if (outcome.limits.given) j["crease_fit_limits"] = LimitsJson(outcome.limits);
    if (outcome.seam) j["seam"] = true;
    return WriteJsonFile(TilePath(dir, id, ".kept"), j, error);
}

bool ReadOutcome(const std::string &dir, int id, TileOutcome &outcome, std::string &error)
{
    const std::string path = TilePath(dir, id, ".kept");
    if (!std::ifstream(path)) return false;
    json j;
    if (!ReadJsonFile(path, "", j, error)) return false;
    try {
        outcome.target = j.at("target").get<std::uint64_t>();
        outcome.owned = j.at("owned").get<std::uint64_t>();
        outcome.rounds = j.at("rounds").get<int>();
        outcome.maxima = j.at("maxima").get<std::vector<double>>();
        outcome.limits = LimitsOf(j.value("crease_fit_limits", json()));
        outcome.seam = j.value("seam", false);
        outcome.entry.distances = j.at("highest_distances").get<std::vector<double>>();
        outcome.entry.normalErrors = j.at("highest_normal_errors").get<std::vector<double>>();
        if (outcome.rounds < -1) throw std::runtime_error("its rounds of exchanges are out of range");
        for (const std::vector<double> *highest : {&outcome.entry.distances, &outcome.entry.normalErrors})
            for (std::size_t k = 0; k < highest->size(); ++k)
                if (!((*highest)[k] >= 0) || (k > 0 && (*highest)[k] > (*highest)[k - 1]))
                    throw std::runtime_error("its highest figures are negative or not highest first");
        for (std::size_t k = 0; k < outcome.maxima.size(); ++k)
            if (!(outcome.maxima[k] >= 0) || (k > 0 && outcome.maxima[k] > outcome.maxima[k - 1]))
                throw std::runtime_error("its largest distances are negative or rise");
    } catch (const std::exception &e) {
        error = path + " is not valid: " + e.what();
        return false;
    }
    return true;
}

bool AdjustShare(TileShare &share, const TileOutcome &outcome, std::uint64_t points)
{
    const bool tried = std::any_of(share.tried.begin(), share.tried.end(),
                                   [&outcome](const TileTrial &t) { return t.target == outcome.target; });
    if (!tried) share.tried.push_back({outcome.target, outcome.owned});
    if (outcome.owned == share.owned) return false;
    if (share.tried.size() > kAdjustRounds) { // no new count: the nearest one tried
        share.target = NearestTrial(share).target;
        return share.target != outcome.target;
    }
    // The nearest counts that kept too few and too many.
    const TileTrial *low = nullptr, *high = nullptr;
    for (const TileTrial &t : share.tried) {
        if (t.owned == share.owned) { // runs are deterministic: that count again
            share.target = t.target;
            return share.target != outcome.target;
        }
        if (t.owned < share.owned && (low == nullptr || t.target > low->target)) low = &t;
        if (t.owned > share.owned && (high == nullptr || t.target < high->target)) high = &t;
    }
    std::uint64_t next;
    if (low != nullptr && high != nullptr) {
        if (high->target <= low->target + 1) { // nothing left between (or a count keeping fewer above one keeping more)
            share.target = NearestTrial(share).target;
            return share.target != outcome.target;
        }
        const double step = double(share.owned - low->owned) / double(high->owned - low->owned);
        next = low->target + std::uint64_t(std::llround(step * double(high->target - low->target)));
        next = std::min(std::max(next, low->target + 1), high->target - 1);
    } else {
        // One side only: the made-to-owned ratio of the last run carries the miss over to the count.
        const double madePerOwned = outcome.owned ? double(outcome.target) / double(outcome.owned) : 2.0;
        const auto change = std::uint64_t(std::ceil(
            madePerOwned * double(outcome.owned < share.owned ? share.owned - outcome.owned : outcome.owned - share.owned)));
        next = outcome.owned < share.owned ? std::min(points, outcome.target + std::max<std::uint64_t>(1, change))
                                           : outcome.target - std::min(outcome.target - 1, std::max<std::uint64_t>(1, change));
    }
    if (next == outcome.target) return false;
    share.target = next;
    return true;
}

bool RanAtRounds(const TileOutcome &outcome, const TileShare &share)
{
    // A run with the whole run's rounds that kept no more exchanges than the tile's part is the
    // run at its part (the exchanges come one after the other).
    return outcome.rounds == share.rounds ||
           (outcome.rounds == -1 && share.rounds >= 0 && outcome.maxima.size() <= std::size_t(share.rounds) + 1);
}

std::size_t HighestToReport(std::uint64_t points)
{
    return points == 0 ? 0 : std::size_t(points) - vcg::gaussphere::NearestRank(std::size_t(points), 99.9) + 1;
}

namespace {

/// The `rank`-th highest (from 1) of `values`, or the lowest of them when there are fewer.
/// \pre values not empty.
double HighestAt(std::vector<double> values, std::size_t rank)
{
    rank = std::min(rank, values.size());
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(rank - 1), values.end(), std::greater<double>());
    return values[rank - 1];
}

} // namespace

vcg::gaussphere::CreaseFitLimits WholeScanCreaseFitLimits(const std::vector<TileOutcome> &outcomes, std::uint64_t points)
{
    vcg::gaussphere::CreaseFitLimits limits;
    std::vector<double> distances, normalErrors;
    for (const TileOutcome &o : outcomes) {
        if (o.entry.distances.empty()) continue;
        distances.insert(distances.end(), o.entry.distances.begin(), o.entry.distances.end());
        normalErrors.insert(normalErrors.end(), o.entry.normalErrors.begin(), o.entry.normalErrors.end());
    }
    if (distances.empty() || normalErrors.empty()) return limits; // nothing reported: each tile judges by its own
    limits.given = true;
    const std::size_t rank = HighestToReport(points);
    limits.distance = HighestAt(std::move(distances), rank);
    limits.normalError = HighestAt(std::move(normalErrors), rank);
    return limits;
}

std::vector<int> ShareExchangeRounds(const std::vector<std::vector<double>> &maxima, int rounds)
{
    std::vector<int> taken(maxima.size(), 0);
    // The largest distance of tile t after the rounds it has taken.
    const auto current = [&](std::size_t t) { return maxima[t][std::size_t(taken[t])]; };
    for (int round = 0; round < rounds; ++round) {
        std::size_t worst = maxima.size();
        for (std::size_t t = 0; t < maxima.size(); ++t)
            if (!maxima[t].empty() && (worst == maxima.size() || current(t) > current(worst))) worst = t;
        // The worst tile kept no more exchanges: neither would the whole run, at the same point.
        if (worst == maxima.size() || std::size_t(taken[worst]) + 1 >= maxima[worst].size()) break;
        ++taken[worst];
    }
    return taken;
}

bool AdjustShares(const std::string &dir, const Manifest &manifest, AdjustFigures &figures, std::string &error)
{
    Shares all;
    if (!ReadShares(dir, all, error)) return false;
    std::vector<TileShare> &shares = all.tiles;
    figures = AdjustFigures();
    if (!RequireRunAtShares(dir, manifest, error)) return false;
    std::vector<TileOutcome> outcomes(shares.size());
    for (std::size_t s = 0; s < shares.size(); ++s) {
        if (manifest.Find(shares[s].id) == nullptr) {
            error = SharesPath(dir) + " has a share for tile " + std::to_string(shares[s].id) + ", which is not in the manifest";
            return false;
        }
        if (!ReadOutcome(dir, shares[s].id, outcomes[s], error)) return false;
    }
    std::vector<bool> rerun(shares.size(), false);
    if (!all.RoundsShared()) {
        vcg::gaussphere::ResamplingParams param;
        if (!TileParams(manifest, 0, param, error)) return false;
        std::vector<std::vector<double>> maxima;
        for (const TileOutcome &o : outcomes) maxima.push_back(o.maxima);
        const std::vector<int> rounds = ShareExchangeRounds(maxima, param.maxErrorExchanges);
        for (std::size_t s = 0; s < shares.size(); ++s) {
            shares[s].rounds = rounds[s];
            rerun[s] = !RanAtRounds(outcomes[s], shares[s]);
        }
    } else if (!all.creaseFitLimits.given) {
        // Every tile ran at its rounds (RequireRunAtShares): their figures are the whole run's.
        figures.sharedLimits = all.creaseFitLimits = WholeScanCreaseFitLimits(outcomes, manifest.points);
    }
    // What the merge keeps of a tile: its result and its rescued spare surfels (border_points.h).
    Rescues rescues;
    if (!FindRescues(dir, manifest, rescues, error)) return false;
    for (std::size_t s = 0; s < shares.size(); ++s) {
        const TileEntry *tile = manifest.Find(shares[s].id);
        outcomes[s].owned += rescues.spares[std::size_t(tile - manifest.tiles.data())].size();
        figures.kept += outcomes[s].owned;
        // With its rounds changed, the tile's owned count is not known: it runs at the same count
        // first. New crease fit limits move surfels, not the clusters it owns: its count is adjusted.
        const bool newCount = !rerun[s] && AdjustShare(shares[s], outcomes[s], tile->corePoints + tile->haloPoints);
        if (rerun[s] || newCount || outcomes[s].limits != all.creaseFitLimits) figures.rerun.push_back(shares[s].id);
    }
    if (figures.rerun.empty() && all.creaseFitLimits.given && !all.seam) {
        // Every tile ran at its share: the snapshots of what they keep, and every tile again.
        if (!SnapshotForSeam(dir, manifest, error)) return false;
        all.seam = figures.seamTaken = true;
        // What a count kept before the seam step is no guide after it: the border points the
        // merge rescues move with the surfels (border_points.h). A tile's seam rounds lower its
        // points to the largest the other tiles' rounds reached: the scan's largest after the
        // rounds, and below it for the tile that holds it.
        for (std::size_t s = 0; s < shares.size(); ++s) {
            shares[s].tried.clear();
            shares[s].seamTarget = 0;
            for (std::size_t o = 0; o < shares.size(); ++o)
                if (o != s && !outcomes[o].maxima.empty())
                    shares[s].seamTarget = std::max(shares[s].seamTarget, outcomes[o].maxima.back());
            figures.rerun.push_back(shares[s].id);
        }
    }
    return WriteShareList(dir, all, error);
}

bool PendingTiles(const std::string &dir, const Manifest &manifest, std::vector<int> &pending, std::string &error)
{
    Shares all;
    if (manifest.targetCount > 0 && !ReadShares(dir, all, error)) return false;
    const std::vector<TileShare> &shares = all.tiles;
    pending.clear();
    for (const TileEntry &tile : manifest.tiles) {
        bool done = std::ifstream(TilePath(dir, tile.id, ".surfel")) && std::ifstream(TilePath(dir, tile.id, ".border"));
        if (done && manifest.targetCount > 0) {
            const auto share = std::find_if(shares.begin(), shares.end(), [&tile](const TileShare &s) { return s.id == tile.id; });
            TileOutcome outcome;
            done = share != shares.end() && ReadOutcome(dir, tile.id, outcome, error) && outcome.target == share->target &&
                   RanAtRounds(outcome, *share) && outcome.limits == all.creaseFitLimits && outcome.seam == all.seam;
            if (!error.empty()) return false;
        }
        if (!done) pending.push_back(tile.id);
    }
    return true;
}

bool RequireRunAtShares(const std::string &dir, const Manifest &manifest, std::string &error)
{
    std::vector<int> pending;
    if (!PendingTiles(dir, manifest, pending, error)) return false;
    if (pending.empty()) return true;
    error = "tile " + std::to_string(pending.front()) + " has not run at its share's count (gstile run " + dir + " " +
            std::to_string(pending.front()) + "; gstile tiles " + dir + " --pending lists them all)";
    return false;
}

} // namespace gstile
