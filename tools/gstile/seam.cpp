#include "seam.h"

#include <cmath>

#include <io_surfel/surfel_file.h>

#include "border_points.h"
#include "tile_files.h"

namespace gstile {
namespace {

/// Whether `p` lies within `margin` of the core box of the tile at `cell` (per axis).
bool NearCore(const TileGrid &grid, const GridCell &cell, double margin, const float p[3])
{
    for (int a = 0; a < 3; ++a) {
        const double lo = grid.origin[a] + cell[a] * grid.edge, hi = lo + grid.edge;
        if (!(double(p[a]) >= lo - margin && double(p[a]) <= hi + margin)) return false;
    }
    return true;
}

/// Whether `r` is a surfel as a tile's run writes it: a unit normal, a member count, a finite
/// positive blend scale and a finite fit offset (surfel_io checks that its geometry is finite).
bool WrittenByARun(const surfel_io::SurfelRecord &r)
{
    const double squaredNormal = double(r.normal[0]) * r.normal[0] + double(r.normal[1]) * r.normal[1] +
                                 double(r.normal[2]) * r.normal[2];
    return std::abs(squaredNormal - 1) <= 1e-3 && std::isfinite(r.quality) && r.quality >= 0 &&
           r.quality <= 2147483520.f && std::isfinite(r.blendScale) && r.blendScale > 0 && std::isfinite(r.fitOffset);
}

vcg::gaussphere::Surfel SurfelOf(const surfel_io::SurfelRecord &r)
{
    const auto point = [](const surfel_io::Vec3f &v) { return vcg::Point3f(v[0], v[1], v[2]); };
    vcg::gaussphere::Surfel s;
    s.position = point(r.position);
    s.normal = point(r.normal);
    s.majorAxis = point(r.majorAxis);
    s.minorAxis = point(r.minorAxis);
    s.memberCount = int(r.quality);
    s.blendScale = r.blendScale;
    s.fitOffset = r.fitOffset;
    return s;
}

} // namespace

std::string RescuedSnapshotPath(const std::string &dir) { return dir + "/seam_rescued.surfel"; }

bool SnapshotForSeam(const std::string &dir, const Manifest &manifest, std::string &error)
{
    Rescues rescues;
    if (!FindRescues(dir, manifest, rescues, error)) return false;
    std::vector<surfel_io::SurfelRecord> rescued;
    const auto write = [&error](const std::string &path, const std::vector<surfel_io::SurfelRecord> &records) {
        return WriteAtomically(path, [&records](std::ostream &out, std::string &reason) {
            return surfel_io::writeSurfels(out, records, reason);
        }, error);
    };
    for (std::size_t t = 0; t < manifest.tiles.size(); ++t) {
        const int id = manifest.tiles[t].id;
        std::vector<surfel_io::SurfelRecord> records;
        if (!ReadTileOutput(dir, id, {}, records, error)) return false;
        const std::size_t kept = records.size();
        if (!ReadTileOutput(dir, id, rescues.spares[t], records, error) || !write(TilePath(dir, id, ".seam"), {records.begin(), records.begin() + kept}))
            return false;
        rescued.insert(rescued.end(), records.begin() + kept, records.end());
    }
    return write(RescuedSnapshotPath(dir), rescued);
}

bool ReadSurround(const std::string &dir, const Manifest &manifest, int id, std::vector<vcg::gaussphere::Surfel> &surround,
                  std::string &error)
{
    surround.clear();
    const GridCell home = manifest.grid.CellOfId(id);
    const double margin = kSurroundHalos * manifest.halo;
    // The tiles' results the snapshots were taken from are the seam runs' by now: a lost snapshot
    // is not taken again, the target's steps start again from the share.
    const std::string startAgain = " (the seam step cannot go on without it: remove shares.json and the tiles' "
                                   "results, tile_*.surfel, .border, .spare and .kept, from " + dir +
                                   " and run the tiles from gstile share on)";
    const auto read = [&](const std::string &path) {
        std::vector<surfel_io::SurfelRecord> records;
        std::string reason;
        if (!surfel_io::readSurfelFile(path, records, reason)) {
            error = "the seam snapshot " + reason + startAgain;
            return false;
        }
        for (std::size_t i = 0; i < records.size(); ++i) {
            const surfel_io::SurfelRecord &r = records[i];
            if (!WrittenByARun(r)) {
                error = "the seam snapshot " + path + ": surfel " + std::to_string(i) +
                        " is not one a tile's run writes (a unit normal, a member count, a finite blend)" + startAgain;
                return false;
            }
            if (NearCore(manifest.grid, home, margin, r.position.data())) surround.push_back(SurfelOf(r));
        }
        return true;
    };
    for (const TileEntry &tile : manifest.tiles) {
        if (tile.id == id) continue;
        // Only the tiles whose kept surfels can come within the margin of the home tile's core box:
        // a tile keeps surfels up to a halo outside its own core box.
        const GridCell cell = manifest.grid.CellOfId(tile.id);
        bool near = true;
        for (int a = 0; a < 3; ++a)
            near = near && std::abs(cell[a] - home[a]) * manifest.grid.edge <= margin + manifest.halo + manifest.grid.edge;
        if (!near) continue;
        if (!read(TilePath(dir, tile.id, ".seam"))) return false;
    }
    return read(RescuedSnapshotPath(dir));
}

} // namespace gstile
