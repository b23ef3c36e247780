// Streams the oriented points of a binary little-endian PLY file chunk by chunk, so that a scan
// of any size is read with one chunk in memory. The header is checked by gsresample's reader
// (ply_input.h); x y z nx ny nz may be float or double, other vertex properties are skipped.
// Positions are given relative to an origin (SetOrigin), subtracted in double before they become
// float: double coordinates far from the origin (georeferenced scans) keep their precision.
#ifndef GSTILE_POINT_STREAM_H
#define GSTILE_POINT_STREAM_H

#include <array>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace gstile {

struct OrientedPoint
{
    float position[3];
    float normal[3];
};

/// True when the resampler uses the point (usable_points.h: finite position, finite non-zero normal).
bool IsUsable(const OrientedPoint &point);

class PointStream
{
public:
    static constexpr std::size_t kChunkPoints = 1 << 18;

    /// Opens `path` and checks its header; false with a one-line reason.
    bool Open(const std::string &path, std::string &error);
    std::uint64_t Count() const { return count_; }
    /// Whether x, y or z is double in the file.
    bool HasDoubleCoordinates() const { return isDouble_[0] || isDouble_[1] || isDouble_[2]; }
    /// The positions Next gives from now on are the file's minus `origin` (0 until set).
    void SetOrigin(const std::array<double, 3> &origin) { origin_ = origin; }
    std::uint64_t ReadSoFar() const { return read_; }
    /// The next at most kChunkPoints points into `chunk`; false when none is left (`error` empty)
    /// or on a read error (`error` set).
    bool Next(std::vector<OrientedPoint> &chunk, std::string &error);
    /// Reads on to the first point that IsUsable and gives its position as the file holds it;
    /// false when there is none (`error` empty) or on a read error (`error` set).
    bool FirstUsablePosition(std::array<double, 3> &position, std::string &error);

private:
    /// The x y z nx ny nz of record i of the last chunk read.
    void Decode(std::size_t i, double fields[6]) const;

    std::ifstream in_;
    std::size_t recordBytes_ = 0;
    std::size_t offsets_[6] = {};
    bool isDouble_[6] = {};
    std::array<double, 3> origin_{{0, 0, 0}};
    std::uint64_t count_ = 0, read_ = 0;
    std::vector<char> bytes_;
};

} // namespace gstile

#endif
