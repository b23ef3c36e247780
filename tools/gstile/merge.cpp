#include "merge.h"

#include <cmath>
#include <cstring>
#include <vector>

#include <io_surfel/surfel_file.h>

#include "border_points.h"
#include "target_share.h"
#include "tile_files.h"

namespace gstile {

namespace {

bool EndsWith(const std::string &text, const std::string &suffix)
{
    return text.size() > suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// The surfels of all results, each checked complete first.
bool CountSurfels(const std::string &dir, const Manifest &manifest, std::uint64_t &total, std::string &error)
{
    total = 0;
    for (const TileEntry &tile : manifest.tiles) {
        std::uint64_t count = 0;
        std::string reason;
        if (!surfel_io::readSurfelCount(TilePath(dir, tile.id, ".surfel"), count, reason)) {
            error = RerunError(tile.id, "no complete result: " + reason);
            return false;
        }
        total += count;
    }
    return true;
}

void WritePlyHeader(std::ostream &out, std::uint64_t count)
{
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << count << "\n";
    for (const char *name : {"x", "y", "z", "nx", "ny", "nz", "radius", "quality"})
        out << "property float " << name << "\n";
    out << "end_header\n";
}

/// x y z nx ny nz radius quality of each record, little-endian like the rest of the project's files.
bool WritePlyRecords(std::ostream &out, const std::vector<surfel_io::SurfelRecord> &records)
{
    std::vector<float> values;
    values.reserve(records.size() * 8);
    for (const surfel_io::SurfelRecord &r : records) {
        values.insert(values.end(), r.position.begin(), r.position.end());
        values.insert(values.end(), r.normal.begin(), r.normal.end());
        values.push_back(r.radius);
        values.push_back(r.quality);
    }
    out.write(reinterpret_cast<const char *>(values.data()), std::streamsize(values.size() * sizeof(float)));
    return bool(out);
}

bool AppendTiles(const std::string &dir, const Manifest &manifest, const Rescues &rescues, bool surfelFormat,
                 std::ostream &out, MergeFigures &figures, std::string &error)
{
    std::vector<surfel_io::SurfelRecord> records;
    for (std::size_t t = 0; t < manifest.tiles.size(); ++t) {
        const int id = manifest.tiles[t].id;
        if (!ReadTileOutput(dir, id, rescues.spares[t], records, error)) return false;
        for (const surfel_io::SurfelRecord &r : records) figures.members += std::uint64_t(std::llround(r.quality));
        std::string reason;
        const bool written = surfelFormat ? surfel_io::writeSurfelRecords(out, records, reason) : WritePlyRecords(out, records);
        if (!written) {
            error = "write error after tile " + std::to_string(id) + (reason.empty() ? "" : ": " + reason);
            return false;
        }
    }
    return true;
}

} // namespace

bool Merge(const std::string &dir, const Manifest &manifest, const std::string &output, MergeFigures &figures,
           std::string &error)
{
    figures = MergeFigures();
    if (manifest.targetCount > 0 && !RequireRunAtShares(dir, manifest, error)) return false;
    Rescues rescues;
    if (!CountSurfels(dir, manifest, figures.surfels, error) || !FindRescues(dir, manifest, rescues, error)) return false;
    figures.surfels += rescues.surfels;
    figures.rescued = rescues.surfels;
    figures.uncovered = rescues.uncovered;
    const bool surfelFormat = EndsWith(output, ".surfel");
    return WriteAtomically(output, [&](std::ostream &out, std::string &reason) {
        if (surfelFormat) surfel_io::writeSurfelHeader(out, figures.surfels);
        else WritePlyHeader(out, figures.surfels);
        return AppendTiles(dir, manifest, rescues, surfelFormat, out, figures, reason);
    }, error);
}

} // namespace gstile
