#include "border_points.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <utility>

#include "point_tree.h"
#include "tile_files.h"

namespace gstile {

namespace {

// .border: this magic, the count and indices of the taken-over points, the count of spare
// surfels, then per spare surfel the count and LeftPoint records of its core points; in the
// machine's byte order, like the point files.
constexpr char kBorderMagic[8] = {'g', 's', 'b', 'o', 'r', 'd', 'e', '1'};

void Put(std::ostream &out, std::uint64_t value) { out.write(reinterpret_cast<const char *>(&value), sizeof value); }

template <class Record>
void PutList(std::ostream &out, const std::vector<Record> &list)
{
    Put(out, list.size());
    out.write(reinterpret_cast<const char *>(list.data()), std::streamsize(list.size() * sizeof(Record)));
}

/// Reads the values of a .border file in order, refusing counts beyond the bytes left.
class BorderReader
{
public:
    explicit BorderReader(std::vector<char> bytes) : bytes_(std::move(bytes)) {}

    bool Magic()
    {
        if (bytes_.size() < sizeof kBorderMagic || std::memcmp(bytes_.data(), kBorderMagic, sizeof kBorderMagic) != 0)
            return false;
        at_ = sizeof kBorderMagic;
        return true;
    }
    bool Value(std::uint64_t &value)
    {
        if (bytes_.size() - at_ < sizeof value) return false;
        std::memcpy(&value, bytes_.data() + at_, sizeof value);
        at_ += sizeof value;
        return true;
    }
    template <class Record>
    bool List(std::vector<Record> &list)
    {
        std::uint64_t count = 0;
        if (!Value(count) || count > (bytes_.size() - at_) / sizeof(Record)) return false;
        list.resize(count);
        if (count > 0) std::memcpy(static_cast<void *>(list.data()), bytes_.data() + at_, count * sizeof(Record));
        at_ += count * sizeof(Record);
        return true;
    }
    bool AtEnd() const { return at_ == bytes_.size(); }
    std::uint64_t ValuesLeft() const { return (bytes_.size() - at_) / sizeof(std::uint64_t); }

private:
    std::vector<char> bytes_;
    std::size_t at_ = 0;
};

} // namespace

bool WriteBorder(const std::string &dir, int id, const TileBorder &border, std::string &error)
{
    return WriteAtomically(TilePath(dir, id, ".border"), [&border](std::ostream &out, std::string &) {
        out.write(kBorderMagic, sizeof kBorderMagic);
        PutList(out, border.takenOver);
        Put(out, border.leftPoints.size());
        for (const std::vector<LeftPoint> &points : border.leftPoints) PutList(out, points);
        return bool(out);
    }, error);
}

bool ReadBorder(const std::string &dir, int id, TileBorder &border, std::string &error)
{
    const std::string path = TilePath(dir, id, ".border");
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = RerunError(id, "cannot open " + path);
        return false;
    }
    BorderReader reader{std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>())};
    std::uint64_t spares = 0;
    // Each spare surfel takes at least its count's 8 bytes.
    bool ok = reader.Magic() && reader.List(border.takenOver) && reader.Value(spares) && spares <= reader.ValuesLeft();
    border.leftPoints.clear();
    for (std::uint64_t s = 0; ok && s < spares; ++s) {
        border.leftPoints.emplace_back();
        ok = reader.List(border.leftPoints.back());
        for (const LeftPoint &p : border.leftPoints.back())
            ok = ok && std::isfinite(p.position[0]) && std::isfinite(p.position[1]) && std::isfinite(p.position[2]);
    }
    if (!ok || !reader.AtEnd() || !std::is_sorted(border.takenOver.begin(), border.takenOver.end())) {
        error = RerunError(id, path + " is damaged");
        return false;
    }
    return true;
}

bool EllipseCovers(const surfel_io::SurfelRecord &s, const float q[3])
{
    double d[3], a2 = 0, b2 = 0, da = 0, db = 0, dn = 0;
    for (int k = 0; k < 3; ++k) {
        d[k] = double(q[k]) - s.position[k];
        a2 += double(s.majorAxis[k]) * s.majorAxis[k];
        b2 += double(s.minorAxis[k]) * s.minorAxis[k];
        da += d[k] * s.majorAxis[k];
        db += d[k] * s.minorAxis[k];
        dn += d[k] * s.normal[k];
    }
    if (!(a2 > 0 && b2 > 0)) return false;
    const double u = da / a2, v = db / b2;
    return u * u + v * v <= 1 && dn * dn <= a2;
}

namespace {

/// The orphans of every tile: left points no tile took over, with their tile and spare surfel.
struct Orphans
{
    std::vector<std::array<float, 3>> positions;
    std::vector<std::pair<std::size_t, std::size_t>> owner; ///< (tile of the manifest, spare surfel)
};

/// Reads the border records twice, first for the taken-over points, then for the left ones, so
/// that only the orphans stay in memory.
bool FindOrphans(const std::string &dir, const Manifest &manifest, Orphans &orphans, std::string &error)
{
    std::vector<std::uint64_t> takenOver;
    TileBorder border;
    for (const TileEntry &tile : manifest.tiles) {
        if (!ReadBorder(dir, tile.id, border, error)) return false;
        takenOver.insert(takenOver.end(), border.takenOver.begin(), border.takenOver.end());
    }
    std::sort(takenOver.begin(), takenOver.end());
    for (std::size_t t = 0; t < manifest.tiles.size(); ++t) {
        if (!ReadBorder(dir, manifest.tiles[t].id, border, error)) return false;
        for (std::size_t s = 0; s < border.leftPoints.size(); ++s)
            for (const LeftPoint &p : border.leftPoints[s]) {
                if (std::binary_search(takenOver.begin(), takenOver.end(), p.index)) continue;
                orphans.positions.push_back({{p.position[0], p.position[1], p.position[2]}});
                orphans.owner.push_back({t, s});
            }
    }
    return true;
}

/// Marks the orphans some kept surfel's ellipse covers, reading the tiles' results one at a time.
bool MarkCovered(const std::string &dir, const Manifest &manifest, const Orphans &orphans, std::vector<bool> &covered,
                 std::string &error)
{
    covered.assign(orphans.positions.size(), false);
    if (orphans.positions.empty()) return true;
    const PointCloud cloud{orphans.positions};
    PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    std::vector<surfel_io::SurfelRecord> records;
    std::vector<std::pair<unsigned, float>> near;
    for (const TileEntry &tile : manifest.tiles) {
        std::string reason;
        if (!surfel_io::readSurfelFile(TilePath(dir, tile.id, ".surfel"), records, reason)) {
            error = RerunError(tile.id, reason);
            return false;
        }
        for (const surfel_io::SurfelRecord &s : records) {
            double a2 = 0;
            for (int k = 0; k < 3; ++k) a2 += double(s.majorAxis[k]) * s.majorAxis[k];
            // Covered points lie within the major semi-axis in the plane and off it: sqrt(2) of it.
            near.clear();
            tree.radiusSearch(s.position.data(), float(2 * a2), near, nanoflann::SearchParams());
            for (const auto &hit : near)
                if (!covered[hit.first]) covered[hit.first] = EllipseCovers(s, orphans.positions[hit.first].data());
        }
    }
    return true;
}

} // namespace

bool FindRescues(const std::string &dir, const Manifest &manifest, Rescues &rescues, std::string &error)
{
    Orphans orphans;
    std::vector<bool> covered;
    if (!FindOrphans(dir, manifest, orphans, error) || !MarkCovered(dir, manifest, orphans, covered, error)) return false;
    rescues = Rescues();
    rescues.spares.resize(manifest.tiles.size());
    rescues.orphans = orphans.positions.size();
    for (std::size_t o = 0; o < covered.size(); ++o) {
        if (covered[o]) continue;
        ++rescues.uncovered;
        rescues.spares[orphans.owner[o].first].push_back(orphans.owner[o].second);
    }
    for (std::vector<std::size_t> &spares : rescues.spares) {
        std::sort(spares.begin(), spares.end());
        spares.erase(std::unique(spares.begin(), spares.end()), spares.end());
        rescues.surfels += spares.size();
    }
    return true;
}

bool ReadTileOutput(const std::string &dir, int id, const std::vector<std::size_t> &rescued,
                    std::vector<surfel_io::SurfelRecord> &records, std::string &error)
{
    const auto fail = [&](const std::string &reason) {
        error = RerunError(id, reason);
        return false;
    };
    std::string reason;
    if (!surfel_io::readSurfelFile(TilePath(dir, id, ".surfel"), records, reason)) return fail(reason);
    if (rescued.empty()) return true;
    std::vector<surfel_io::SurfelRecord> spares;
    if (!surfel_io::readSurfelFile(TilePath(dir, id, ".spare"), spares, reason)) return fail(reason);
    for (const std::size_t s : rescued) {
        if (s >= spares.size()) return fail(TilePath(dir, id, ".spare") + " has fewer surfels than its .border");
        records.push_back(spares[s]);
    }
    return true;
}

} // namespace gstile
