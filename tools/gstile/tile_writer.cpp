#include "tile_writer.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace gstile {

TileWriter::TileWriter(const std::string &dir, int tileCount, std::size_t bufferBytes)
    : dir_(dir), capacity_(std::max<std::size_t>(64, bufferBytes / sizeof(TilePoint) / (2 * std::size_t(tileCount)))),
      buckets_(2 * std::size_t(tileCount))
{
}

bool TileWriter::Add(int tile, bool core, const TilePoint &point)
{
    if (!error_.empty()) return false;
    Bucket &bucket = BucketOf(tile, core);
    if (bucket.buffer.capacity() < capacity_) bucket.buffer.reserve(capacity_);
    bucket.buffer.push_back(point);
    return bucket.buffer.size() < capacity_ || Flush(tile, core);
}

bool TileWriter::Flush(int tile, bool core)
{
    Bucket &bucket = BucketOf(tile, core);
    const std::string path = TilePath(dir_, tile, core ? ".core" : ".halo");
    // The first flush creates the file, so a file left by a previous split is replaced.
    std::FILE *file = std::fopen(path.c_str(), bucket.written == 0 ? "wb" : "ab");
    const std::size_t n = bucket.buffer.size();
    bool ok = file != nullptr && std::fwrite(bucket.buffer.data(), sizeof(TilePoint), n, file) == n;
    if (file != nullptr) ok = std::fclose(file) == 0 && ok;
    if (!ok) {
        error_ = "cannot write " + path + ": " + std::strerror(errno);
        return false;
    }
    bucket.checksum.Add(bucket.buffer.data(), n * sizeof(TilePoint));
    bucket.written += n;
    bucket.buffer.clear();
    return true;
}

bool TileWriter::Finish(std::vector<TileEntry> &tiles)
{
    tiles.clear();
    const int tileCount = int(buckets_.size() / 2);
    for (int id = 0; id < tileCount && error_.empty(); ++id) {
        const bool owns = BucketOf(id, true).written + BucketOf(id, true).buffer.size() > 0;
        if (!owns) {
            std::remove(TilePath(dir_, id, ".halo").c_str());
            continue;
        }
        for (bool core : {true, false})
            if (!Flush(id, core)) return false; // also creates an empty halo file
        TileEntry entry;
        entry.id = id;
        entry.corePoints = BucketOf(id, true).written;
        entry.haloPoints = BucketOf(id, false).written;
        entry.coreChecksum = BucketOf(id, true).checksum.Hex();
        entry.haloChecksum = BucketOf(id, false).checksum.Hex();
        tiles.push_back(entry);
    }
    return error_.empty();
}

} // namespace gstile
