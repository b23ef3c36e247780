#include "target_share.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>

#include <nlohmann/json.hpp>

#include "border_points.h"
#include "tile_files.h"

using nlohmann::json;

namespace gstile {

namespace {

constexpr const char *kRunProbeAndShare = "with a target, run `gstile probe` on every tile, then `gstile share`";

} // namespace

std::string SharesPath(const std::string &dir) { return dir + "/shares.json"; }

std::vector<TileShare> ShareTarget(const Manifest &manifest, const std::vector<TileProbe> &probes)
{
    std::uint64_t ownedSum = 0;
    for (const TileProbe &p : probes) ownedSum += p.owned;
    std::vector<TileShare> shares(probes.size());
    // Exact in integers: target x owned fits 128 bits.
    std::vector<std::pair<std::uint64_t, std::size_t>> remainders; // (remainder of the division, tile)
    std::uint64_t given = 0;
    for (std::size_t t = 0; t < probes.size(); ++t) {
        const unsigned __int128 product = (unsigned __int128)manifest.targetCount * probes[t].owned;
        shares[t].id = probes[t].id;
        shares[t].owned = ownedSum ? std::uint64_t(product / ownedSum) : 0;
        given += shares[t].owned;
        remainders.push_back({ownedSum ? std::uint64_t(product % ownedSum) : 0, t});
    }
    // Ties by tile order: the same probes give the same shares.
    std::stable_sort(remainders.begin(), remainders.end(),
                     [](const auto &a, const auto &b) { return a.first > b.first; });
    for (std::size_t r = 0; given < manifest.targetCount && r < remainders.size(); ++r, ++given)
        ++shares[remainders[r].second].owned;
    for (std::size_t t = 0; t < probes.size(); ++t) {
        const TileEntry &tile = manifest.tiles[t];
        const double madePerOwned = probes[t].owned ? double(probes[t].clusters) / double(probes[t].owned) : 1;
        const auto target = std::uint64_t(std::llround(double(shares[t].owned) * madePerOwned));
        shares[t].target = shares[t].owned ? std::min(target, tile.corePoints + tile.haloPoints) : 0;
    }
    return shares;
}

bool WriteProbe(const std::string &dir, const TileProbe &probe, std::string &error)
{
    return WriteJsonFile(TilePath(dir, probe.id, ".probe"), {{"clusters", probe.clusters}, {"owned", probe.owned}}, error);
}

bool ReadProbe(const std::string &dir, int id, TileProbe &probe, std::string &error)
{
    json j;
    if (!ReadJsonFile(TilePath(dir, id, ".probe"), kRunProbeAndShare, j, error)) return false;
    try {
        probe.id = id;
        probe.clusters = j.at("clusters").get<std::uint64_t>();
        probe.owned = j.at("owned").get<std::uint64_t>();
    } catch (const std::exception &e) {
        error = TilePath(dir, id, ".probe") + " is not valid: " + e.what();
        return false;
    }
    return true;
}

namespace {

bool WriteShareList(const std::string &dir, const Manifest &manifest, const std::vector<TileShare> &shares,
                    std::string &error)
{
    json list = json::array();
    for (const TileShare &s : shares) {
        json tried = json::array();
        for (const TileTrial &t : s.tried) tried.push_back({t.target, t.owned});
        list.push_back({{"id", s.id}, {"owned", s.owned}, {"target", s.target}, {"tried", tried}});
    }
    return WriteJsonFile(SharesPath(dir), {{"target", manifest.targetCount}, {"tiles", list}}, error);
}

bool ReadShareList(const std::string &dir, std::vector<TileShare> &shares, std::string &error)
{
    json j;
    if (!ReadJsonFile(SharesPath(dir), kRunProbeAndShare, j, error)) return false;
    try {
        shares.clear();
        for (const json &t : j.at("tiles")) {
            TileShare share;
            share.id = t.at("id").get<int>();
            share.owned = t.at("owned").get<std::uint64_t>();
            share.target = t.at("target").get<std::uint64_t>();
            for (const json &trial : t.value("tried", json::array()))
                share.tried.push_back({trial.at(0).get<std::uint64_t>(), trial.at(1).get<std::uint64_t>()});
            shares.push_back(share);
        }
    } catch (const std::exception &e) {
        error = SharesPath(dir) + " is not valid: " + e.what();
        return false;
    }
    return true;
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

bool WriteShares(const std::string &dir, const Manifest &manifest, std::vector<TileShare> &shares, std::string &error)
{
    std::vector<TileProbe> probes(manifest.tiles.size());
    for (std::size_t t = 0; t < probes.size(); ++t)
        if (!ReadProbe(dir, manifest.tiles[t].id, probes[t], error)) return false;
    shares = ShareTarget(manifest, probes);
    return WriteShareList(dir, manifest, shares, error);
}

bool ReadShare(const std::string &dir, int id, TileShare &share, std::string &error)
{
    std::vector<TileShare> shares;
    if (!ReadShareList(dir, shares, error)) return false;
    for (const TileShare &s : shares) {
        if (s.id != id) continue;
        share = s;
        return true;
    }
    error = SharesPath(dir) + " has no share for tile " + std::to_string(id);
    return false;
}

bool WriteOutcome(const std::string &dir, int id, const TileOutcome &outcome, std::string &error)
{
    return WriteJsonFile(TilePath(dir, id, ".kept"), {{"target", outcome.target}, {"owned", outcome.owned}}, error);
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
    if (!tried) share.tried.push_back(outcome);
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

bool AdjustShares(const std::string &dir, const Manifest &manifest, AdjustFigures &figures, std::string &error)
{
    std::vector<TileShare> shares;
    if (!ReadShareList(dir, shares, error)) return false;
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
    // What the merge keeps of a tile: its result and its rescued spare surfels (border_points.h).
    Rescues rescues;
    if (!FindRescues(dir, manifest, rescues, error)) return false;
    for (std::size_t s = 0; s < shares.size(); ++s) {
        const TileEntry *tile = manifest.Find(shares[s].id);
        outcomes[s].owned += rescues.spares[std::size_t(tile - manifest.tiles.data())].size();
        figures.kept += outcomes[s].owned;
        if (AdjustShare(shares[s], outcomes[s], tile->corePoints + tile->haloPoints)) figures.rerun.push_back(shares[s].id);
    }
    return WriteShareList(dir, manifest, shares, error);
}

bool PendingTiles(const std::string &dir, const Manifest &manifest, std::vector<int> &pending, std::string &error)
{
    std::vector<TileShare> shares;
    if (manifest.targetCount > 0 && !ReadShareList(dir, shares, error)) return false;
    pending.clear();
    for (const TileEntry &tile : manifest.tiles) {
        bool done = std::ifstream(TilePath(dir, tile.id, ".surfel")) && std::ifstream(TilePath(dir, tile.id, ".border"));
        if (done && manifest.targetCount > 0) {
            const auto share = std::find_if(shares.begin(), shares.end(), [&tile](const TileShare &s) { return s.id == tile.id; });
            TileOutcome outcome;
            done = share != shares.end() && ReadOutcome(dir, tile.id, outcome, error) && outcome.target == share->target;
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
