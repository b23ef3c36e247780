// Reading an oriented point set from a PLY file, safely on any input: the header is read and
// checked here before vcglib's ImporterPLY sees the file, because that reader trusts it (it
// allocates what the counts announce and reads lists into fixed-size buffers). Qt-free.
// The checked header is public too, for readers that stream the records themselves (gstile).
#ifndef GSRESAMPLE_PLY_INPUT_H
#define GSRESAMPLE_PLY_INPUT_H

#include <cstdint>
#include <string>
#include <vector>

#include <vcg_ext/gaussphere/oriented_point_mesh.h>

namespace gsresample {

struct HeaderProperty
{
    std::string name;
    std::string type;      // items' type for a list
    bool isList = false;
    std::string countType; // lists only
};

struct HeaderElement
{
    std::string name;
    std::uint64_t count = 0;
    std::vector<HeaderProperty> properties;

    const HeaderProperty *Find(const std::string &property) const
    {
        for (const HeaderProperty &p : properties)
            if (p.name == property) return &p;
        return nullptr;
    }
};

struct PlyHeader
{
    bool binary = false;
    bool bigEndian = false; // binary files only
    std::vector<HeaderElement> elements;
    std::vector<std::string> comments; ///< the text after `comment` and `obj_info`, as vcglib keeps it
    std::uint64_t bodyOffset = 0;
};

/// Bytes of one value of a PLY scalar type (both spellings), 0 for an unknown name.
int TypeSize(const std::string &type);
bool IsFloatingType(const std::string &type);

/// Reads the header of `path` and checks what ReadOrientedPoints needs: a vertex element with
/// float or double x y z nx ny nz and no lists, and a body at least as long as the counts
/// announce. On failure returns false with `error` as ReadOrientedPoints gives it.
bool ReadOrientedPointHeader(const std::string &path, PlyHeader &header, std::string &error);

/// Reads an oriented point set (x y z nx ny nz per vertex) from a PLY file. On failure returns false and
/// sets `error` to one line (at most 200 characters, printable ASCII only) naming the reason.
bool ReadOrientedPoints(const std::string &path, vcg::gaussphere::OrientedPointMesh &mesh, std::string &error);

} // namespace gsresample

#endif
