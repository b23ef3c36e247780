// Pass 2 of `gstile split`: points appended to the core or halo file of their tiles through one
// bounded buffer per file, each flushed by appending when full, so that memory stays bounded
// whatever the input's size and the number of tiles.
#ifndef GSTILE_TILE_WRITER_H
#define GSTILE_TILE_WRITER_H

#include <string>
#include <vector>

#include "manifest.h"
#include "tile_files.h"

namespace gstile {

class TileWriter
{
public:
    /// `bufferBytes` is shared by the buffers of all tiles, at least 64 points each.
    TileWriter(const std::string &dir, int tileCount, std::size_t bufferBytes);
    /// False once a write failed (then `Error()` says why); later points are dropped.
    bool Add(int tile, bool core, const TilePoint &point);
    /// Flushes every buffer, deletes the halo files of tiles without core points and fills
    /// `tiles` with the tiles that have core points, by id.
    bool Finish(std::vector<TileEntry> &tiles);
    const std::string &Error() const { return error_; }

private:
    struct Bucket
    {
        std::vector<TilePoint> buffer;
        std::uint64_t written = 0;
        Checksum checksum;
    };
    bool Flush(int tile, bool core);
    Bucket &BucketOf(int tile, bool core) { return buckets_[2 * std::size_t(tile) + (core ? 0 : 1)]; }

    std::string dir_;
    std::size_t capacity_;
    std::vector<Bucket> buckets_;
    std::string error_;
};

} // namespace gstile

#endif
