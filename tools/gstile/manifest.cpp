#include "manifest.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "tile_files.h"

namespace gstile {

namespace {

constexpr const char *kFormat = "gstile-manifest 3";
using nlohmann::json;

json TilesToJson(const std::vector<TileEntry> &tiles)
{
    json list = json::array();
    for (const TileEntry &t : tiles)
        list.push_back({{"id", t.id}, {"core_points", t.corePoints}, {"halo_points", t.haloPoints},
                        {"core_checksum", t.coreChecksum}, {"halo_checksum", t.haloChecksum}});
    return list;
}

json ToJson(const Manifest &m)
{
    json options = json::array();
    for (const auto &o : m.options) options.push_back({o.first, o.second});
    return {{"format", kFormat},
            {"input", m.input},
            {"points", m.points},
            {"skipped", m.skipped},
            {"double_coordinates", m.doubleCoordinates},
            {"origin", m.origin},
            {"box_min", m.boxMin},
            {"box_max", m.boxMax},
            {"diagonal", m.diagonal},
            {"spacing", m.spacing},
            {"halo_spacings", m.haloSpacings},
            {"halo", m.halo},
            {"grid", {{"origin", m.grid.origin}, {"edge", m.grid.edge}, {"dims", m.grid.dims}}},
            {"options", options},
            {"max_error_of_diagonal", m.maxErrorOfDiagonal},
            {"target_count", m.targetCount},
            {"tiles", TilesToJson(m.tiles)}};
}

void FromJson(const json &j, Manifest &m)
{
    if (j.at("format").get<std::string>() != kFormat) throw std::runtime_error("not a " + std::string(kFormat));
    m.input = j.at("input").get<std::string>();
    m.points = j.at("points").get<std::uint64_t>();
    m.skipped = j.at("skipped").get<std::uint64_t>();
    m.doubleCoordinates = j.at("double_coordinates").get<bool>();
    m.origin = j.at("origin").get<std::array<double, 3>>();
    m.boxMin = j.at("box_min").get<std::array<double, 3>>();
    m.boxMax = j.at("box_max").get<std::array<double, 3>>();
    m.diagonal = j.at("diagonal").get<double>();
    m.spacing = j.at("spacing").get<double>();
    m.haloSpacings = j.at("halo_spacings").get<double>();
    m.halo = j.at("halo").get<double>();
    const json &grid = j.at("grid");
    m.grid.origin = grid.at("origin").get<std::array<double, 3>>();
    m.grid.edge = grid.at("edge").get<double>();
    m.grid.dims = grid.at("dims").get<GridCell>();
    m.options.clear();
    for (const json &o : j.at("options")) m.options.emplace_back(o.at(0).get<std::string>(), o.at(1).get<std::string>());
    m.maxErrorOfDiagonal = j.at("max_error_of_diagonal").get<double>();
    m.targetCount = j.at("target_count").get<std::uint64_t>();
    m.tiles.clear();
    for (const json &t : j.at("tiles")) {
        TileEntry e;
        e.id = t.at("id").get<int>();
        e.corePoints = t.at("core_points").get<std::uint64_t>();
        e.haloPoints = t.at("halo_points").get<std::uint64_t>();
        e.coreChecksum = t.at("core_checksum").get<std::string>();
        e.haloChecksum = t.at("halo_checksum").get<std::string>();
        m.tiles.push_back(e);
    }
}

} // namespace

const TileEntry *Manifest::Find(int id) const
{
    for (const TileEntry &t : tiles)
        if (t.id == id) return &t;
    return nullptr;
}

bool WriteJsonFile(const std::string &path, const json &j, std::string &error)
{
    return WriteAtomically(path, [&j](std::ostream &out, std::string &) {
        out << j.dump(1) << "\n";
        return bool(out);
    }, error);
}

bool ReadJsonFile(const std::string &path, const std::string &missingHint, json &j, std::string &error)
{
    std::ifstream in(path);
    if (!in) {
        error = "cannot open " + path + " (" + missingHint + ")";
        return false;
    }
    try {
        j = json::parse(in);
    } catch (const std::exception &e) {
        error = path + " is not valid JSON: " + e.what();
        return false;
    }
    return true;
}

bool WriteManifest(const std::string &dir, const Manifest &manifest, std::string &error)
{
    return WriteJsonFile(ManifestPath(dir), ToJson(manifest), error);
}

bool ReadManifest(const std::string &dir, Manifest &manifest, std::string &error)
{
    const std::string path = ManifestPath(dir);
    json j;
    if (!ReadJsonFile(path, "is " + dir + " a tile directory made by gstile split?", j, error)) return false;
    try {
        FromJson(j, manifest);
    } catch (const std::exception &e) {
        error = path + " is not a valid manifest: " + e.what();
        return false;
    }
    return true;
}

} // namespace gstile
