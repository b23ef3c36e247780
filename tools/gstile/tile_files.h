// The files of a tile directory (docs/tiling.md):
//   manifest.json          the grid, the global parameters, each tile's counts and checksums
//   tile_NNNNNN.core       the points whose tile this is, as TilePoint records
//   tile_NNNNNN.halo       the points of other tiles within the halo width of its core box
//   tile_NNNNNN.surfel     the tile's result: the surfels it owns (gstile run), written atomically
// Point files are raw arrays of 32-byte records in input order, in the byte order of the machine
// that split them (little-endian x86-64 and arm64 alike).
#ifndef GSTILE_TILE_FILES_H
#define GSTILE_TILE_FILES_H

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace gstile {

struct TilePoint
{
    float position[3];
    float normal[3];
    std::uint64_t index; ///< the point's vertex index in the input file
};
static_assert(sizeof(TilePoint) == 32, "tile records are 32 bytes");

/// A 64-bit FNV-1a over the bytes of a file, updated chunk by chunk.
class Checksum
{
public:
    void Add(const void *bytes, std::size_t size);
    std::uint64_t Value() const { return value_; }
    std::string Hex() const;

private:
    std::uint64_t value_ = 0xcbf29ce484222325ull;
};

/// `dir`/tile_NNNNNN`suffix`, e.g. TilePath("t", 7, ".core") = "t/tile_000007.core".
std::string TilePath(const std::string &dir, int id, const char *suffix);
std::string ManifestPath(const std::string &dir);

/// "tile `id`: `reason` (run `gstile run` on it again)": a tile's file missing or damaged.
std::string RerunError(int id, const std::string &reason);

/// Reads the records of `path`, which must hold exactly `count` of them with checksum
/// `checksumHex`; otherwise false with a reason naming the file.
bool ReadTilePoints(const std::string &path, std::uint64_t count, const std::string &checksumHex,
                    std::vector<TilePoint> &points, std::string &error);

/// Writes `path` through a FileReplacement (io_surfel/file_replacement.h), renamed over `path`
/// when `write` succeeded: a reader never sees a half-written file, and two processes writing the
/// same file (a retried task beside its lost first run) each write a temporary file of their own.
bool WriteAtomically(const std::string &path, const std::function<bool(std::ostream &, std::string &)> &write,
                     std::string &error);

} // namespace gstile

#endif
