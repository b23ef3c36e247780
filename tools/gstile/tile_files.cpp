#include "tile_files.h"

#include <io_surfel/file_replacement.h>

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace gstile {

void Checksum::Add(const void *bytes, std::size_t size)
{
    const unsigned char *b = static_cast<const unsigned char *>(bytes);
    for (std::size_t i = 0; i < size; ++i) value_ = (value_ ^ b[i]) * 0x100000001b3ull;
}

std::string Checksum::Hex() const
{
    char text[17];
    std::snprintf(text, sizeof text, "%016" PRIx64, value_);
    return text;
}

std::string RerunError(int id, const std::string &reason)
{
    return "tile " + std::to_string(id) + ": " + reason + " (run `gstile run` on it again)";
}

std::string TilePath(const std::string &dir, int id, const char *suffix)
{
    char name[32];
    std::snprintf(name, sizeof name, "tile_%06d", id);
    return dir + "/" + name + suffix;
}

std::string ManifestPath(const std::string &dir) { return dir + "/manifest.json"; }

bool ReadTilePoints(const std::string &path, std::uint64_t count, const std::string &checksumHex,
                    std::vector<TilePoint> &points, std::string &error)
{
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) {
        error = "cannot open " + path + ": " + std::strerror(errno);
        return false;
    }
    const std::uint64_t bytes = std::uint64_t(in.tellg());
    if (bytes != count * sizeof(TilePoint)) {
        error = path + " holds " + std::to_string(bytes) + " bytes, the manifest announces " + std::to_string(count) +
                " points of " + std::to_string(sizeof(TilePoint)) + " bytes";
        return false;
    }
    points.resize(count);
    in.seekg(0);
    if (count > 0 && !in.read(reinterpret_cast<char *>(points.data()), std::streamsize(bytes))) {
        error = "read error in " + path;
        return false;
    }
    Checksum checksum;
    checksum.Add(points.data(), bytes);
    if (checksum.Hex() != checksumHex) {
        error = path + " is corrupt: its checksum " + checksum.Hex() + " differs from the manifest's " + checksumHex;
        return false;
    }
    return true;
}

bool WriteAtomically(const std::string &path, const std::function<bool(std::ostream &, std::string &)> &write,
                     std::string &error)
{
    surfel_io::FileReplacement replacement;
    return replacement.open(path, error) && replacement.write(write, error);
}

} // namespace gstile
