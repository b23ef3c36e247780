#include "target_share.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <nlohmann/json.hpp>

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

bool WriteShares(const std::string &dir, const Manifest &manifest, std::vector<TileShare> &shares, std::string &error)
{
    std::vector<TileProbe> probes(manifest.tiles.size());
    for (std::size_t t = 0; t < probes.size(); ++t)
        if (!ReadProbe(dir, manifest.tiles[t].id, probes[t], error)) return false;
    shares = ShareTarget(manifest, probes);
    json list = json::array();
    for (const TileShare &s : shares) list.push_back({{"id", s.id}, {"owned", s.owned}, {"target", s.target}});
    return WriteJsonFile(SharesPath(dir), {{"target", manifest.targetCount}, {"tiles", list}}, error);
}

bool ReadShare(const std::string &dir, int id, TileShare &share, std::string &error)
{
    json j;
    if (!ReadJsonFile(SharesPath(dir), kRunProbeAndShare, j, error)) return false;
    try {
        for (const json &t : j.at("tiles")) {
            if (t.at("id").get<int>() != id) continue;
            share.id = id;
            share.owned = t.at("owned").get<std::uint64_t>();
            share.target = t.at("target").get<std::uint64_t>();
            return true;
        }
    } catch (const std::exception &e) {
        error = SharesPath(dir) + " is not valid: " + e.what();
        return false;
    }
    error = SharesPath(dir) + " has no share for tile " + std::to_string(id);
    return false;
}

} // namespace gstile
