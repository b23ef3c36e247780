#include "point_stream.h"

#include <algorithm>
#include <cstring>

#include <vcg_ext/gaussphere/oriented_point_mesh.h>
#include <vcg_ext/gaussphere/usable_points.h>

#include <tools/gsresample/ply_input.h>

namespace gstile {

constexpr std::size_t PointStream::kChunkPoints; // C++14: its odr-uses (std::min) need a definition

bool IsUsable(const OrientedPoint &point)
{
    vcg::gaussphere::OrientedPointVertex v; // the resampler's own test, on a detached vertex
    v.P() = vcg::Point3f(point.position[0], point.position[1], point.position[2]);
    v.N() = vcg::Point3f(point.normal[0], point.normal[1], point.normal[2]);
    return vcg::gaussphere::ClassifyVertex(v) == vcg::gaussphere::VertexUse::kUsable;
}

namespace {

/// Bytes of one record of `element`, which has no list property (checked by the caller).
std::size_t RecordBytes(const gsresample::HeaderElement &element)
{
    std::size_t bytes = 0;
    for (const gsresample::HeaderProperty &p : element.properties) bytes += std::size_t(gsresample::TypeSize(p.type));
    return bytes;
}

bool HasList(const gsresample::HeaderElement &element)
{
    return std::any_of(element.properties.begin(), element.properties.end(),
                       [](const gsresample::HeaderProperty &p) { return p.isList; });
}

} // namespace

bool PointStream::Open(const std::string &path, std::string &error)
{
    gsresample::PlyHeader header;
    if (!gsresample::ReadOrientedPointHeader(path, header, error)) return false;
    if (!header.binary || header.bigEndian) {
        error = "only binary little-endian PLY is streamed; convert the file first (e.g. with MeshLab)";
        return false;
    }
    std::uint64_t skip = header.bodyOffset;
    const gsresample::HeaderElement *vertex = nullptr;
    for (const gsresample::HeaderElement &e : header.elements) {
        if (e.name == "vertex") {
            vertex = &e;
            break;
        }
        if (HasList(e)) {
            error = "element '" + e.name + "' before the vertices has a list property; put the vertices first";
            return false;
        }
        skip += e.count * RecordBytes(e);
    }
    recordBytes_ = RecordBytes(*vertex);
    const char *names[6] = {"x", "y", "z", "nx", "ny", "nz"};
    for (int f = 0; f < 6; ++f) {
        std::size_t offset = 0;
        for (const gsresample::HeaderProperty &p : vertex->properties) {
            if (p.name == names[f]) break;
            offset += std::size_t(gsresample::TypeSize(p.type));
        }
        offsets_[f] = offset;
        isDouble_[f] = gsresample::TypeSize(vertex->Find(names[f])->type) == 8;
    }
    count_ = vertex->count;
    in_.open(path, std::ios::binary);
    in_.seekg(std::streamoff(skip));
    if (!in_) {
        error = "cannot seek to the vertices";
        return false;
    }
    return true;
}

bool PointStream::Next(std::vector<OrientedPoint> &chunk, std::string &error)
{
    error.clear();
    const std::size_t n = std::size_t(std::min<std::uint64_t>(count_ - read_, kChunkPoints));
    chunk.resize(n);
    if (n == 0) return false;
    bytes_.resize(n * recordBytes_);
    if (!in_.read(bytes_.data(), std::streamsize(bytes_.size()))) {
        error = "read error after " + std::to_string(read_) + " vertices";
        return false;
    }
    for (std::size_t i = 0; i < n; ++i) {
        double fields[6];
        Decode(i, fields);
        for (int a = 0; a < 3; ++a) {
            chunk[i].position[a] = float(fields[a] - origin_[size_t(a)]);
            chunk[i].normal[a] = float(fields[3 + a]);
        }
    }
    read_ += n;
    return true;
}

void PointStream::Decode(std::size_t i, double fields[6]) const
{
    const char *record = &bytes_[i * recordBytes_];
    for (int f = 0; f < 6; ++f) {
        if (isDouble_[f]) {
            std::memcpy(&fields[f], record + offsets_[f], sizeof(double));
        } else {
            float single;
            std::memcpy(&single, record + offsets_[f], sizeof single);
            fields[f] = single;
        }
    }
}

bool PointStream::FirstUsablePosition(std::array<double, 3> &position, std::string &error)
{
    std::vector<OrientedPoint> chunk;
    while (Next(chunk, error)) {
        for (std::size_t i = 0; i < chunk.size(); ++i) {
            if (!IsUsable(chunk[i])) continue;
            double fields[6];
            Decode(i, fields);
            position = {{fields[0], fields[1], fields[2]}};
            return true;
        }
    }
    return false;
}

} // namespace gstile
