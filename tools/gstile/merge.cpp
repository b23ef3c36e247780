#include "merge.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <io_surfel/surfel_file.h>
#include <vcg_ext/gaussphere/usable_points.h>

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

/// The PLY header: x y z in double when the input's were (`doubleCoordinates`), else float.
void WritePlyHeader(std::ostream &out, std::uint64_t count, bool doubleCoordinates)
{
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << count << "\n";
    for (const char *name : {"x", "y", "z"}) out << "property " << (doubleCoordinates ? "double " : "float ") << name << "\n";
    for (const char *name : {"nx", "ny", "nz", "radius", "quality"}) out << "property float " << name << "\n";
    out << "end_header\n";
}

/// Appends `value`'s bytes, little-endian like the rest of the project's files.
template <class T>
void AppendBytes(std::vector<char> &bytes, T value)
{
    const char *p = reinterpret_cast<const char *>(&value);
    bytes.insert(bytes.end(), p, p + sizeof value);
}

/// x y z nx ny nz radius quality of each record, the position moved back by the manifest's origin.
bool WritePlyRecords(std::ostream &out, const std::vector<surfel_io::SurfelRecord> &records, const Manifest &manifest)
{
    std::vector<char> bytes;
    bytes.reserve(records.size() * (manifest.doubleCoordinates ? 44 : 32));
    for (const surfel_io::SurfelRecord &r : records) {
        for (int a = 0; a < 3; ++a) {
            if (manifest.doubleCoordinates) AppendBytes(bytes, double(r.position[size_t(a)]) + manifest.origin[size_t(a)]);
            else AppendBytes(bytes, r.position[size_t(a)]);
        }
        for (float v : r.normal) AppendBytes(bytes, v);
        AppendBytes(bytes, r.radius);
        AppendBytes(bytes, r.quality);
    }
    out.write(bytes.data(), std::streamsize(bytes.size()));
    return bool(out);
}

/// The records moved back by the manifest's origin, in the .surfel format's float coordinates.
void MoveToInputOrigin(const Manifest &manifest, std::vector<surfel_io::SurfelRecord> &records)
{
    for (surfel_io::SurfelRecord &r : records)
        for (int a = 0; a < 3; ++a) r.position[size_t(a)] = float(double(r.position[size_t(a)]) + manifest.origin[size_t(a)]);
}

bool AppendTiles(const std::string &dir, const Manifest &manifest, const Rescues &rescues, bool surfelFormat,
                 std::ostream &out, MergeFigures &figures, std::string &error)
{
    std::vector<surfel_io::SurfelRecord> records;
    for (std::size_t t = 0; t < manifest.tiles.size(); ++t) {
        const int id = manifest.tiles[t].id;
        if (!ReadTileOutput(dir, id, rescues.spares[t], records, error)) return false;
        for (const surfel_io::SurfelRecord &r : records) figures.members += std::uint64_t(std::llround(r.quality));
        if (surfelFormat) MoveToInputOrigin(manifest, records);
        std::string reason;
        const bool written = surfelFormat ? surfel_io::writeSurfelRecords(out, records, reason)
                                          : WritePlyRecords(out, records, manifest);
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
    if (surfelFormat && manifest.doubleCoordinates) {
        double farthest = 0;
        for (int a = 0; a < 3; ++a)
            farthest = std::max({farthest, std::abs(manifest.origin[size_t(a)] + manifest.boxMin[size_t(a)]),
                                 std::abs(manifest.origin[size_t(a)] + manifest.boxMax[size_t(a)])});
        figures.coarseStep = vcg::gaussphere::CoarseFloatStep(farthest, manifest.diagonal);
    }
    return WriteAtomically(output, [&](std::ostream &out, std::string &reason) {
        if (surfelFormat) surfel_io::writeSurfelHeader(out, figures.surfels);
        else WritePlyHeader(out, figures.surfels, manifest.doubleCoordinates);
        return AppendTiles(dir, manifest, rescues, surfelFormat, out, figures, reason);
    }, error);
}

} // namespace gstile
