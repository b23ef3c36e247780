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

#include "double_point_mesh.h"

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
/// The first spelling of a PLY scalar type ("int32" -> "int"), empty for an unknown name.
std::string CanonicalType(const std::string &type);
/// Whether vcglib's ImporterPLY reads list `property` of `element` as face corners (vertex indices).
bool IsReadCornerList(const HeaderElement &element, const HeaderProperty &property);

/// Reads the header of `path` and checks what ReadOrientedPoints needs: a vertex element with
/// float or double x y z nx ny nz and no lists, a body at least as long as the counts announce,
/// and in a binary file faces of at least 3 corners that are vertices. The records of an ASCII body are
/// checked by CheckAsciiBody. On failure returns false with `error` as ReadOrientedPoints gives it.
bool ReadOrientedPointHeader(const std::string &path, PlyHeader &header, std::string &error);

/// Checks the body of an ASCII file whose header ReadOrientedPointHeader read, streaming it:
/// the records of every element in header order, one a line (line ends "\n" or "\r\n"),
/// their values separated by spaces or tabs, exactly as many as the properties take (a list: its
/// count, then that many items), each a whole number of its property's type: a decimal integer in
/// the type's range for integer types; for float and double a decimal or hexadecimal number
/// (1e999 reads as infinity) or nan, inf, infinity in any case, optionally signed. A list count
/// is not negative, a face has at least 3 corners and each names a vertex. Blank lines are
/// passed over between the records and after the last one; anything else after it is refused. On failure returns false with
/// `error` naming the line, the record ("vertex 12", counted from 0), the property and the text.
bool CheckAsciiBody(const std::string &path, const PlyHeader &header, std::string &error);

/// Reads an oriented point set (x y z nx ny nz per vertex) from a PLY file. On failure returns false and
/// sets `error` to one line (at most 200 characters, printable ASCII only) naming the reason.
/// With `info`, double coordinates are read in double and moved by the centre of their bounding
/// box before they become float, so they keep their precision however far from the origin they
/// lie; `info` says so, gives the move and whether the vertices have colours. Without it, or for
/// float coordinates, the coordinates are converted as they are.
bool ReadOrientedPoints(const std::string &path, vcg::gaussphere::OrientedPointMesh &mesh, std::string &error,
                        InputInfo *info = nullptr);

} // namespace gsresample

#endif
