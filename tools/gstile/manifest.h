// The manifest of a tile directory (manifest.json): what `gstile split` decided and what every
// tile's run must share, so that tiles resample as parts of one input.
#ifndef GSTILE_MANIFEST_H
#define GSTILE_MANIFEST_H

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "tile_grid.h"

namespace gstile {

struct TileEntry
{
    int id = 0;
    std::uint64_t corePoints = 0, haloPoints = 0;
    std::string coreChecksum, haloChecksum; ///< Checksum::Hex of the point files
};

struct Manifest
{
    std::string input;
    std::uint64_t points = 0;  ///< usable points of the input
    std::uint64_t skipped = 0; ///< points the resampler would skip (non-finite position, bad normal)
    bool doubleCoordinates = false; ///< the input's x, y or z is double
    std::array<double, 3> origin{}; ///< tile positions (and all below) are the input's minus this
    std::array<double, 3> boxMin{}, boxMax{};
    double diagonal = 0;       ///< of the usable points, as the resampler measures it (tile_params.h)
    double spacing = 0;        ///< the sample spacing estimate (spacing.h)
    double haloSpacings = 0;   ///< the halo width in spacings
    double halo = 0;           ///< ... in model units
    TileGrid grid;
    /// gsresample's options for every tile's run, as text (`--weight-width` fixed to the whole
    /// input's h, no target: see targetCount, no error bound: see maxErrorOfDiagonal).
    std::vector<std::pair<std::string, std::string>> options;
    double maxErrorOfDiagonal = 0; ///< the error bound as a fraction of the whole input's diagonal (0 = off)
    std::uint64_t targetCount = 0; ///< the exact count wanted of the whole input, shared out by target_share.h (0 = off)
    std::vector<TileEntry> tiles;  ///< the tiles that own points, by id

    const TileEntry *Find(int id) const;
};

bool WriteManifest(const std::string &dir, const Manifest &manifest, std::string &error);
/// The tile directory's JSON files (the manifest, target_share.h's probes and shares): written
/// atomically (WriteAtomically), read with an error naming the file (`missingHint` when absent).
bool WriteJsonFile(const std::string &path, const nlohmann::json &j, std::string &error);
bool ReadJsonFile(const std::string &path, const std::string &missingHint, nlohmann::json &j, std::string &error);
bool ReadManifest(const std::string &dir, Manifest &manifest, std::string &error);

} // namespace gstile

#endif
