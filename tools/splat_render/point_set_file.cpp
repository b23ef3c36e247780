#include "point_set_file.h"

#include <io_surfel/printable_text.h>
#include <wrap/ply/plylib.h>

#include <algorithm>
#include <cstddef>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace splat {
namespace {

struct VertexRecord
{
    float position[3];
    float normal[3];
    float radius;
    float majorAxis[3];
    float minorAxis[3];
    float fitOffset;
    unsigned char color[4];
};

constexpr int kMaxPolygonVertices = 512;
struct FaceRecord
{
    int count;
    int indices[kMaxPolygonVertices];
};

int typeBytes(int plyType)
{
    switch (plyType) {
    case vcg::ply::T_CHAR: case vcg::ply::T_UCHAR: return 1;
    case vcg::ply::T_SHORT: case vcg::ply::T_USHORT: return 2;
    case vcg::ply::T_INT: case vcg::ply::T_UINT: case vcg::ply::T_FLOAT: return 4;
    case vcg::ply::T_DOUBLE: return 8;
    default: return 0;
    }
}

bool isFloating(int plyType) { return plyType == vcg::ply::T_FLOAT || plyType == vcg::ply::T_DOUBLE; }

// Reads the header as plylib will (lines of at most 510 bytes, in the first 64 KiB) and refuses
// what plylib does not survive: NUL bytes (plylib's header text stops at them, its parse does
// not), longer lines (plylib parses them in pieces), element lines without a count of digits
// (plylib calls atoi on a missing token, asserts on a negative count). True for a binary body.
bool checkHeader(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    std::string text(1 << 16, '\0');
    in.read(&text[0], std::streamsize(text.size()));
    text.resize(std::size_t(in.gcount()));
    bool binary = false;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = text.find('\n', start);
        if (end == std::string::npos)
            throw std::runtime_error(path + ": no end_header in the first 64 KiB");
        const std::string line = text.substr(start, end - start);
        start = end + 1;
        if (line.find('\0') != std::string::npos || line.size() >= 500)
            throw std::runtime_error(path + ": header line with a NUL byte or of 500 bytes or more");
        std::istringstream tokens(line);
        std::string keyword, first, second, extra;
        tokens >> keyword >> first >> second;
        if (keyword == "end_header")
            return binary;
        if (keyword == "format")
            binary = first.compare(0, 6, "binary") == 0;
        if (keyword == "element" &&
            (second.empty() || second.size() > 9 || second.find_first_not_of("0123456789") != std::string::npos ||
             (tokens >> extra)))
            throw std::runtime_error(path + ": element line '" + surfel_io::printableText(line, 60) +
                                     "' needs a name and a count of digits");
    }
}

// plylib skips a list it does not read, in a binary file, through a 512-byte buffer, its count
// read as one byte whatever its type: other binary lists pass only with one-byte counts and items
// of at most two bytes (ASCII lists are skipped item by item). `corners` is the one list read.
void checkSkippedLists(const vcg::ply::PlyFile &file, bool binary, const vcg::ply::PlyProperty *corners,
                       const std::string &path)
{
    if (!binary) return;
    for (const vcg::ply::PlyElement &element : file.elements) {
        for (const vcg::ply::PlyProperty &p : element.props) {
            if (!p.islist || &p == corners || (typeBytes(p.tipoindex) == 1 && typeBytes(p.tipo) <= 2)) continue;
            throw std::runtime_error(path + ": list property '" + surfel_io::printableText(p.name, 40) +
                                     "' of element '" + surfel_io::printableText(element.name, 40) +
                                     "' is not supported (binary lists need one-byte counts and items of at "
                                     "most two bytes)");
        }
    }
}

vcg::ply::PlyElement *findElement(vcg::ply::PlyFile &file, const char *name)
{
    for (vcg::ply::PlyElement &element : file.elements)
        if (element.name == name)
            return &element;
    return nullptr;
}

// Asks plylib to store a scalar property (whatever its type in the file) at `offset` as
// `memoryType`; false when the element has no such scalar property.
bool readScalar(vcg::ply::PlyFile &file, vcg::ply::PlyElement &element, const char *property, int memoryType,
                std::size_t offset)
{
    vcg::ply::PlyProperty *found = element.FindProp(property);
    // plylib converts binary floating-point values only into floating-point memory.
    if (found == nullptr || found->islist || (isFloating(found->tipo) && !isFloating(memoryType)))
        return false;
    return file.AddToRead(element.name.c_str(), property, found->tipo, memoryType, offset, 0, 0, 0, 0, 0) ==
           vcg::ply::E_NOERROR;
}

bool readAll(vcg::ply::PlyFile &file, vcg::ply::PlyElement &element, const std::vector<const char *> &properties,
             std::size_t firstOffset)
{
    bool all = true;
    for (std::size_t i = 0; i < properties.size(); ++i)
        all = readScalar(file, element, properties[i], vcg::ply::T_FLOAT, firstOffset + i * sizeof(float)) && all;
    return all;
}

// The optional vertex properties plylib was asked to store (the file has them).
struct VertexProperties
{
    bool normals = false;
    bool radius = false;
    bool ellipses = false;
    bool fitOffsets = false;
    bool colors = false;
};

// Asks plylib to store the vertex properties of a VertexRecord the file has; x, y and z are needed.
VertexProperties requestVertexProperties(vcg::ply::PlyFile &file, vcg::ply::PlyElement &vertexElement,
                                         const std::string &path)
{
    if (!readAll(file, vertexElement, {"x", "y", "z"}, offsetof(VertexRecord, position)))
        throw std::runtime_error(path + ": vertices lack x, y or z");
    VertexProperties has;
    has.normals = readAll(file, vertexElement, {"nx", "ny", "nz"}, offsetof(VertexRecord, normal));
    has.radius = readScalar(file, vertexElement, "radius", vcg::ply::T_FLOAT, offsetof(VertexRecord, radius));
    has.ellipses =
        readAll(file, vertexElement, {"major_x", "major_y", "major_z"}, offsetof(VertexRecord, majorAxis)) &&
        readAll(file, vertexElement, {"minor_x", "minor_y", "minor_z"}, offsetof(VertexRecord, minorAxis));
    has.fitOffsets =
        readScalar(file, vertexElement, "fit_offset", vcg::ply::T_FLOAT, offsetof(VertexRecord, fitOffset));
    has.colors = true;
    const char *const channels[3] = {"red", "green", "blue"};
    for (int c = 0; c < 3; ++c)
        has.colors = readScalar(file, vertexElement, channels[c], vcg::ply::T_UCHAR,
                                offsetof(VertexRecord, color) + c) && has.colors;
    readScalar(file, vertexElement, "alpha", vcg::ply::T_UCHAR, offsetof(VertexRecord, color) + 3); // else opaque
    return has;
}

// Asks plylib to store the face element's corner list as a FaceRecord, in binary files whose
// corners are integers counted by one byte (at most 255 of the record's 512; in ASCII plylib reads
// any count, so ASCII faces are not read); the list stored, or null.
vcg::ply::PlyProperty *requestFaces(vcg::ply::PlyFile &file, bool binary, vcg::ply::PlyElement &faceElement)
{
    if (!binary)
        return nullptr;
    for (const char *name : {"vertex_indices", "vertex_index"}) {
        vcg::ply::PlyProperty *list = faceElement.FindProp(name);
        if (list != nullptr && list->islist && typeBytes(list->tipoindex) == 1 && !isFloating(list->tipo) &&
            file.AddToRead("face", name, list->tipo, vcg::ply::T_INT, offsetof(FaceRecord, indices), 1, 0,
                           list->tipoindex, vcg::ply::T_INT, offsetof(FaceRecord, count)) == vcg::ply::E_NOERROR)
            return list;
    }
    return nullptr;
}

// Reads `count` vertex records of the current element into `result` (fit offsets apart).
void readVertices(vcg::ply::PlyFile &file, int count, const VertexProperties &has, const std::string &path,
                  PointSetFile &result, std::vector<float> &fitOffsets)
{
    SurfelArrays &s = result.surfels;
    for (int i = 0; i < count; ++i) {
        VertexRecord v = {};
        v.color[3] = 255;
        if (file.Read(&v) == -1)
            throw std::runtime_error(path + ": truncated vertex data");
        s.positions.insert(s.positions.end(), v.position, v.position + 3);
        if (has.normals)
            s.normals.insert(s.normals.end(), v.normal, v.normal + 3);
        if (has.radius)
            result.radii.push_back(v.radius);
        if (has.ellipses) {
            s.majorAxes.insert(s.majorAxes.end(), v.majorAxis, v.majorAxis + 3);
            s.minorAxes.insert(s.minorAxes.end(), v.minorAxis, v.minorAxis + 3);
        }
        if (has.colors)
            s.colors.insert(s.colors.end(), v.color, v.color + 4);
        if (has.fitOffsets)
            fitOffsets.push_back(v.fitOffset);
    }
}

// Reads `count` face records of the current element, fanned into triangles.
void readFaces(vcg::ply::PlyFile &file, int count, const std::string &path, std::vector<unsigned> &triangles)
{
    for (int i = 0; i < count; ++i) {
        FaceRecord f;
        if (file.Read(&f) == -1 || f.count > kMaxPolygonVertices)
            throw std::runtime_error(path + ": bad face data");
        for (int k = 2; k < f.count; ++k) // fan triangulation
            triangles.insert(triangles.end(), {unsigned(f.indices[0]), unsigned(f.indices[k - 1]), unsigned(f.indices[k])});
    }
}

} // namespace

PointSetFile readPointSetFile(const std::string &path)
{
    const bool binary = checkHeader(path);
    vcg::ply::PlyFile file;
    if (file.Open(path.c_str(), vcg::ply::PlyFile::MODE_READ) != 0)
        throw std::runtime_error("cannot read " + path + " as PLY (plylib error " + std::to_string(file.GetError()) + ")");
    vcg::ply::PlyElement *vertexElement = findElement(file, "vertex");
    if (vertexElement == nullptr)
        throw std::runtime_error(path + " has no vertex element");
    const VertexProperties has = requestVertexProperties(file, *vertexElement, path);
    vcg::ply::PlyElement *faceElement = findElement(file, "face");
    vcg::ply::PlyProperty *corners = faceElement != nullptr ? requestFaces(file, binary, *faceElement) : nullptr;
    const bool hasFaces = corners != nullptr;
    checkSkippedLists(file, binary, corners, path);

    PointSetFile result;
    std::vector<float> fitOffsets;
    for (std::size_t e = 0; e < file.elements.size(); ++e) {
        file.SetCurElement(int(e));
        const int count = file.elements[e].number;
        if (&file.elements[e] == vertexElement) {
            readVertices(file, count, has, path, result, fitOffsets);
        } else if (&file.elements[e] == faceElement && hasFaces) {
            readFaces(file, count, path, result.triangles);
        } else {
            char skipped[1 << 12];
            for (int i = 0; i < count; ++i)
                file.Read(skipped); // no property of this element is stored
        }
    }
    SurfelArrays &s = result.surfels;
    undoFitOffsets(s, fitOffsets);
    result.hasNormals = has.normals && std::any_of(s.normals.begin(), s.normals.end(), [](float v) { return v != 0.0f; });
    const unsigned vertexCount = unsigned(s.size());
    if (std::any_of(result.triangles.begin(), result.triangles.end(), [&](unsigned i) { return i >= vertexCount; }))
        throw std::runtime_error(path + ": face index out of range");
    return result;
}

} // namespace splat
