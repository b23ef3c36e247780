#include "tile_run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <limits>

#include <vcg_ext/gaussphere/oriented_point_mesh.h>
#include <vcg_ext/gaussphere/surfels/surfel_mesh.h>
#include <io_surfel/surfel_records_mesh.h>

#include "seam.h"
#include "tile_params.h"

template vcg::gaussphere::ResamplingResult vcg::gaussphere::ResamplePointSet<vcg::gaussphere::OrientedPointMesh>(
    const vcg::gaussphere::OrientedPointMesh &, const vcg::gaussphere::ResamplingParams &, vcg::CallBackPos *);

using namespace vcg::gaussphere;

namespace gstile {

namespace {

bool LoadTilePoints(const std::string &dir, const TileEntry &tile, std::vector<TilePoint> &points, std::string &error)
{
    std::vector<TilePoint> halo;
    if (!ReadTilePoints(TilePath(dir, tile.id, ".core"), tile.corePoints, tile.coreChecksum, points, error) ||
        !ReadTilePoints(TilePath(dir, tile.id, ".halo"), tile.haloPoints, tile.haloChecksum, halo, error))
        return false;
    points.insert(points.end(), halo.begin(), halo.end());
    return true;
}

/// The points as a mesh, and the diagonal of their bounding box as the resampler measures it.
double FillMesh(const std::vector<TilePoint> &points, OrientedPointMesh &mesh)
{
    auto v = vcg::tri::Allocator<OrientedPointMesh>::AddVertices(mesh, points.size());
    std::array<float, 3> lo{{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                             std::numeric_limits<float>::max()}};
    std::array<float, 3> hi{{-lo[0], -lo[1], -lo[2]}};
    for (const TilePoint &p : points) {
        v->P() = vcg::Point3f(p.position[0], p.position[1], p.position[2]);
        v->N() = vcg::Point3f(p.normal[0], p.normal[1], p.normal[2]);
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], p.position[a]);
            hi[a] = std::max(hi[a], p.position[a]);
        }
        ++v;
    }
    return ResamplerDiagonal(lo, hi);
}

/// The tile's points into `mesh` (their input indices into `indices`) and its parameters.
bool LoadTile(const std::string &dir, const TileEntry &tile, OrientedPointMesh &mesh, std::vector<std::uint64_t> &indices,
              ResamplingParams &param, const Manifest &manifest, std::string &error)
{
    std::vector<TilePoint> points;
    if (!LoadTilePoints(dir, tile, points, error)) return false;
    const double diagonal = FillMesh(points, mesh);
    indices.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) indices[i] = points[i].index;
    return TileParams(manifest, diagonal, param, error);
}

bool WriteResult(const std::string &path, const std::vector<Surfel> &surfels, std::string &error)
{
    OrientedPointMesh mesh;
    WriteSurfels(surfels, mesh);
    const std::vector<surfel_io::SurfelRecord> records = surfel_io::recordsFromMesh(mesh);
    return WriteAtomically(path, [&records](std::ostream &out, std::string &reason) {
        return surfel_io::writeSurfels(out, records, reason);
    }, error);
}

} // namespace

namespace {

/// Whether anchor a (a vertex, or indices.size() for none) has a smaller input index than anchor b.
bool AnchorBefore(std::size_t a, std::size_t b, const std::vector<std::uint64_t> &indices)
{
    return a != indices.size() && (b == indices.size() || indices[a] < indices[b]);
}

/// Per cluster of `representative` (each vertex's cluster, -1 for none), its anchor: the vertex of
/// its member with the smallest input index (indices.size() for a cluster without members).
std::vector<std::size_t> Anchors(const IndexArray &representative, std::size_t clusters,
                                 const std::vector<std::uint64_t> &indices)
{
    std::vector<std::size_t> anchor(clusters, indices.size());
    for (std::size_t v = 0; v < indices.size(); ++v) {
        const int s = representative[v];
        if (s < 0) continue;
        std::size_t &a = anchor[std::size_t(s)];
        if (AnchorBefore(v, a, indices)) a = v;
    }
    return anchor;
}

} // namespace

std::vector<bool> OwnedSurfels(const ResamplingResult &result, const std::vector<std::uint64_t> &indices,
                               std::uint64_t corePoints)
{
    const std::vector<std::size_t> anchor = Anchors(result.representative, result.surfels.size(), indices);
    std::vector<bool> owned(anchor.size());
    for (std::size_t s = 0; s < anchor.size(); ++s) owned[s] = anchor[s] < corePoints;
    return owned;
}

TileBorder BorderOf(const ResamplingResult &result, const std::vector<std::uint64_t> &indices,
                    const OrientedPointMesh &points, std::uint64_t corePoints, const std::vector<bool> &owned,
                    std::vector<int> &spares)
{
    TileBorder border;
    std::vector<int> spareOf(result.surfels.size(), -1); // position in `spares`
    spares.clear();
    for (std::size_t v = 0; v < indices.size(); ++v) {
        const int s = result.representative[v];
        if (s < 0) continue;
        if (v >= corePoints) {
            if (owned[std::size_t(s)]) border.takenOver.push_back(indices[v]);
            continue;
        }
        if (owned[std::size_t(s)]) continue;
        if (spareOf[std::size_t(s)] < 0) {
            spareOf[std::size_t(s)] = int(spares.size());
            spares.push_back(s);
            border.leftPoints.emplace_back();
        }
        LeftPoint left;
        left.index = indices[v];
        for (int k = 0; k < 3; ++k) left.position[k] = points.vert[v].cP()[k];
        border.leftPoints[std::size_t(spareOf[std::size_t(s)])].push_back(left);
    }
    std::sort(border.takenOver.begin(), border.takenOver.end());
    return border;
}

namespace {

/// One tile resampled: its points' input indices, the result and which surfels it owns.
struct ResampledTile
{
    OrientedPointMesh mesh; ///< the tile's points, core first
    std::vector<std::uint64_t> indices;
    ResamplingResult result;
    std::vector<bool> owned;
};

/// Resamples `tile` with the manifest's parameters as `adapt` changes them.
bool ResampleTile(const std::string &dir, const Manifest &manifest, const TileEntry &tile,
                  const std::function<void(ResamplingParams &)> &adapt, ResampledTile &out, std::string &error)
{
    ResamplingParams param;
    if (!LoadTile(dir, tile, out.mesh, out.indices, param, manifest, error)) return false;
    adapt(param);
    if (!param.surroundingSurfels.empty()) param.anchorKeys = out.indices; // the ownership rule's
    try {
        out.result = ResamplePointSet(out.mesh, param);
    } catch (const std::exception &e) {
        error = std::string("the resampling failed: ") + e.what();
        return false;
    }
    out.owned = OwnedSurfels(out.result, out.indices, tile.corePoints);
    return true;
}

/// The run of a share: at the shared level, to the share's count.
std::function<void(ResamplingParams &)> AtShare(int level, std::uint64_t count)
{
    return [level, count](ResamplingParams &param) {
        param.subdivisionLevel = level;
        param.searchLevel = false;
        param.targetCount = int(count);
    };
}

/// The manifest's entry of tile `id`, or null with an error naming the tile.
const TileEntry *FindTile(const std::string &dir, const Manifest &manifest, int id, std::string &error)
{
    const TileEntry *tile = manifest.Find(id);
    if (tile == nullptr)
        error = "tile " + std::to_string(id) + " is not in " + ManifestPath(dir) + " (it owns no points, or the id is wrong)";
    return tile;
}

} // namespace

namespace {

/// The split record of a tile resampled to a count without exchanges: for each split, whether
/// the cluster it added is owned, found by undoing the splits from the last (a split's two parts
/// were one cluster, anchored at the smaller of their anchors); the priorities as SplitKey keeps
/// them, never rising.
std::vector<SplitKey> SplitKeys(const ResampledTile &tile, std::uint64_t corePoints)
{
    const ResamplingResult &result = tile.result;
    std::vector<std::size_t> anchor = Anchors(result.representative, result.surfels.size(), tile.indices);
    const std::vector<CountSplit> &splits = result.targetRecord.splits;
    std::vector<SplitKey> keys(splits.size());
    for (std::size_t k = keys.size(); k-- > 0;) {
        const CountSplit &split = splits[k];
        const std::size_t kept = anchor[std::size_t(split.cluster)], added = anchor[std::size_t(split.added)];
        const bool addedFirst = AnchorBefore(added, kept, tile.indices);
        // The part holding the whole cluster's anchor keeps the cluster's ownership; the other is the one added.
        const std::size_t other = addedFirst ? kept : added;
        keys[k] = {split.error, split.size, other < corePoints};
        anchor[std::size_t(split.cluster)] = addedFirst ? added : kept;
    }
    for (std::size_t k = 1; k < keys.size(); ++k) {
        const SplitKey &before = keys[k - 1];
        SplitKey &key = keys[k];
        if (SplitBefore(key, before)) {
            key.error = before.error;
            key.size = before.size;
        }
    }
    return keys;
}

/// The merge record of a tile resampled to a count without exchanges: for each merge, whether it
/// took away an owned cluster, found by following the anchors of the level's clusters through the
/// merges (the merged cluster's anchor is the smaller of its parts'); the costs as MergeKey keeps
/// them, never falling.
std::vector<MergeKey> MergeKeys(const ResampledTile &tile, std::uint64_t corePoints)
{
    const CountRecord &record = tile.result.targetRecord;
    const IndexArray &level = record.levelRepresentative;
    const int clusters = level.empty() ? 0 : *std::max_element(level.begin(), level.end()) + 1;
    std::vector<std::size_t> anchor = Anchors(level, std::size_t(clusters), tile.indices);
    std::vector<MergeKey> keys;
    for (const CountMerge &merge : record.merges) {
        std::size_t first = anchor[std::size_t(merge.kept)], second = anchor[std::size_t(merge.gone)];
        if (AnchorBefore(second, first, tile.indices)) std::swap(first, second);
        anchor[std::size_t(merge.kept)] = first;
        keys.push_back({keys.empty() ? merge.cost : std::max(merge.cost, keys.back().cost), second < corePoints});
    }
    return keys;
}

} // namespace

bool ProbeTile(const std::string &dir, const Manifest &manifest, int id, ProbeFigures &figures, std::string &error)
{
    const auto start = std::chrono::steady_clock::now();
    figures = ProbeFigures();
    figures.id = id;
    const TileEntry *entry = FindTile(dir, manifest, id, error);
    if (entry == nullptr) return false;
    ShareDecision decision;
    std::vector<TileProbe> probes;
    if (!DecideFromProbes(dir, manifest, probes, decision, error)) {
        error = "tile " + std::to_string(id) + ": " + error;
        return false;
    }
    const std::size_t index = std::size_t(entry - manifest.tiles.data());
    TileProbe &probe = probes[index]; // as the decision read it
    if (decision.shared || Satisfies(probe, decision.needs[index])) return true;
    const ProbeNeed need = figures.need = decision.needs[index];
    bool ok = true;
    ResampledTile tile;
    if (need.recordCap == 0) {
        ok = ResampleTile(dir, manifest, *entry, [&need](ResamplingParams &param) {
            param.subdivisionLevel = need.level;
            param.fitOffsets = false; // the counts are the clusters'
        }, tile, error);
        if (ok) {
            figures.counts = {need.level, tile.owned.size(), std::uint64_t(std::count(tile.owned.begin(), tile.owned.end(), true))};
            probe.levels.push_back(figures.counts);
        }
    } else {
        // The decision asks for steps at a level only once every tile has its counts there.
        const std::uint64_t points = entry->corePoints + entry->haloPoints, made = probe.At(need.level)->clusters;
        std::uint64_t count = std::min(points, made + need.recordCap);
        if (need.merges) count = made > need.recordCap ? made - need.recordCap : std::min<std::uint64_t>(made, 1);
        ok = ResampleTile(dir, manifest, *entry, [&](ResamplingParams &param) {
            AtShare(need.level, count)(param);
            param.maxErrorExchanges = 0; // the steps alone, recorded
            param.recordCountSteps = true;
            param.fitOffsets = false;
        }, tile, error);
        if (ok) {
            probe.recordLevel = need.level;
            probe.recordCap = need.recordCap;
            probe.splits = SplitKeys(tile, entry->corePoints);
            probe.merges = MergeKeys(tile, entry->corePoints);
            figures.steps = probe.Steps();
        }
    }
    ok = ok && WriteProbe(dir, probe, error);
    if (!ok) error = "tile " + std::to_string(id) + ": " + error;
    figures.probed = ok;
    figures.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return ok;
}

std::string ProbeLine(const ProbeFigures &f, std::size_t position, std::size_t tileCount)
{
    char line[200];
    if (!f.probed)
        std::snprintf(line, sizeof line, "[probe] %zu/%zu: tile %d has what the share needs", position, tileCount, f.id);
    else if (f.need.recordCap == 0)
        std::snprintf(line, sizeof line, "[probe] %zu/%zu: tile %d, level %d: %llu clusters, %llu owned, %.2f s", position,
                      tileCount, f.id, f.need.level, (unsigned long long)f.counts.clusters,
                      (unsigned long long)f.counts.owned, f.seconds);
    else
        std::snprintf(line, sizeof line, "[probe] %zu/%zu: tile %d, level %d: %zu %s recorded of %llu asked, %.2f s",
                      position, tileCount, f.id, f.need.level, f.steps, f.need.merges ? "merges" : "splits",
                      (unsigned long long)f.need.recordCap, f.seconds);
    return line;
}

bool RunTile(const std::string &dir, const Manifest &manifest, int id, TileRunFigures &figures, std::string &error)
{
    const auto start = std::chrono::steady_clock::now();
    const std::string name = "tile " + std::to_string(id);
    const TileEntry *entry = FindTile(dir, manifest, id, error);
    if (entry == nullptr) return false;
    Shares shares;
    TileShare share;
    if (manifest.targetCount > 0 && !ReadShare(dir, id, shares, share, error)) {
        error = name + ": " + error;
        return false;
    }
    ResampledTile tile;
    // With a target, a tile whose share is 0 keeps nothing and needs no run.
    const bool run = manifest.targetCount == 0 || share.target > 0;
    std::vector<Surfel> surround;
    if (run && shares.seam && !ReadSurround(dir, manifest, id, surround, error)) {
        error = name + ": " + error;
        return false;
    }
    const auto adapt = [&manifest, &shares, &share, &surround, entry](ResamplingParams &param) {
        if (manifest.targetCount == 0) return;
        AtShare(shares.level, share.target)(param);
        // The tile's part of the whole run's exchanges, for the largest distance among its core
        // points (its halo's are the other tiles' core points), and the whole scan's crease fit
        // limits, from the reports of every tile's highest figures.
        param.exchangeRounds = share.rounds;
        param.countedVertices = int(entry->corePoints);
        param.creaseFitLimits = shares.creaseFitLimits;
        param.reportHighestAtCreaseFit = int(std::min<std::size_t>(HighestToReport(manifest.points), entry->corePoints));
        // After the seam step, its neighbours' kept surfels beyond its faces (seam.h).
        param.surroundingSurfels = std::move(surround);
        param.seamTarget = share.seamTarget;
    };
    if (run && !ResampleTile(dir, manifest, *entry, adapt, tile, error)) {
        error = name + ": " + error;
        return false;
    }
    std::vector<Surfel> kept, spare;
    for (std::size_t s = 0; s < tile.owned.size(); ++s) {
        if (!tile.owned[s]) continue;
        kept.push_back(tile.result.surfels[s]);
        figures.ownedMembers += std::uint64_t(tile.result.surfels[s].memberCount);
    }
    std::vector<int> spares;
    const TileBorder border = run ? BorderOf(tile.result, tile.indices, tile.mesh, entry->corePoints, tile.owned, spares) : TileBorder();
    for (const int s : spares) spare.push_back(tile.result.surfels[std::size_t(s)]);
    // The result last: it marks the tile done (merge.h).
    if (!WriteBorder(dir, id, border, error) || !WriteResult(TilePath(dir, id, ".spare"), spare, error) ||
        !WriteResult(TilePath(dir, id, ".surfel"), kept, error) ||
        (manifest.targetCount > 0 &&
         !WriteOutcome(dir, id, {share.target, kept.size(), share.rounds, tile.result.exchangeMaxima,
                                 shares.creaseFitLimits, tile.result.creaseFitEntry, shares.seam}, error))) {
        error = name + ": " + error;
        return false;
    }
    figures.id = id;
    figures.corePoints = entry->corePoints;
    figures.haloPoints = entry->haloPoints;
    figures.clusters = int(tile.result.surfels.size());
    figures.owned = int(kept.size());
    figures.stats = tile.result.stats;
    figures.seam = shares.seam && run;
    figures.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return true;
}

std::string FiguresLine(const TileRunFigures &f, std::size_t position, std::size_t tileCount)
{
    char line[300];
    int length = std::snprintf(line, sizeof line,
                  "[run] %zu/%zu: tile %d, %llu core + %llu halo points -> %d surfels, %d owned (%llu points), "
                  "level %d, %.2f s",
                  position, tileCount, f.id, (unsigned long long)f.corePoints, (unsigned long long)f.haloPoints, f.clusters,
                  f.owned, (unsigned long long)f.ownedMembers, f.stats.levelUsed, f.seconds);
    if (f.seam && length > 0 && length < int(sizeof line))
        std::snprintf(line + length, sizeof line - std::size_t(length),
                      "; beside its neighbours' surfels: largest distance %.4g -> %.4g (model units), %d exchanges, "
                      "%d points set aside",
                      f.stats.seamMaxBefore * f.stats.diagonal, f.stats.seamMaxAfter * f.stats.diagonal,
                      f.stats.seamExchanges, f.stats.seamSetAside);
    return line;
}

} // namespace gstile
