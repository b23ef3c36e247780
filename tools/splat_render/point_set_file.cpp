#include "point_set_file.h"

#include <wrap/ply/plylib.h>

#include <algorithm>
#include <cstddef>
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
    if (found == nullptr || found->islist)
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

} // namespace

PointSetFile readPointSetFile(const std::string &path)
{
    vcg::ply::PlyFile file;
    if (file.Open(path.c_str(), vcg::ply::PlyFile::MODE_READ) != 0)
        throw std::runtime_error("cannot read " + path + " as PLY (plylib error " + std::to_string(file.GetError()) + ")");
    vcg::ply::PlyElement *vertexElement = findElement(file, "vertex");
    if (vertexElement == nullptr)
        throw std::runtime_error(path + " has no vertex element");

    if (!readAll(file, *vertexElement, {"x", "y", "z"}, offsetof(VertexRecord, position)))
        throw std::runtime_error(path + ": vertices lack x, y or z");
    const bool hasNormals = readAll(file, *vertexElement, {"nx", "ny", "nz"}, offsetof(VertexRecord, normal));
    const bool hasRadius = readScalar(file, *vertexElement, "radius", vcg::ply::T_FLOAT, offsetof(VertexRecord, radius));
    const bool hasEllipses =
        readAll(file, *vertexElement, {"major_x", "major_y", "major_z"}, offsetof(VertexRecord, majorAxis)) &&
        readAll(file, *vertexElement, {"minor_x", "minor_y", "minor_z"}, offsetof(VertexRecord, minorAxis));
    const bool hasFitOffsets =
        readScalar(file, *vertexElement, "fit_offset", vcg::ply::T_FLOAT, offsetof(VertexRecord, fitOffset));
    bool hasColors = true;
    const char *const channels[3] = {"red", "green", "blue"};
    for (int c = 0; c < 3; ++c)
        hasColors = readScalar(file, *vertexElement, channels[c], vcg::ply::T_UCHAR,
                               offsetof(VertexRecord, color) + c) && hasColors;
    readScalar(file, *vertexElement, "alpha", vcg::ply::T_UCHAR, offsetof(VertexRecord, color) + 3); // else opaque

    vcg::ply::PlyElement *faceElement = findElement(file, "face");
    bool hasFaces = false;
    if (faceElement != nullptr) {
        for (const char *name : {"vertex_indices", "vertex_index"}) {
            vcg::ply::PlyProperty *list = faceElement->FindProp(name);
            if (list != nullptr && list->islist) {
                hasFaces = file.AddToRead("face", name, list->tipo, vcg::ply::T_INT, offsetof(FaceRecord, indices), 1, 0,
                                          list->tipoindex, vcg::ply::T_INT, offsetof(FaceRecord, count)) ==
                           vcg::ply::E_NOERROR;
                break;
            }
        }
    }

    PointSetFile result;
    SurfelArrays &s = result.surfels;
    std::vector<float> fitOffsets;
    for (std::size_t e = 0; e < file.elements.size(); ++e) {
        file.SetCurElement(int(e));
        const int count = file.elements[e].number;
        if (&file.elements[e] == vertexElement) {
            for (int i = 0; i < count; ++i) {
                VertexRecord v = {};
                v.color[3] = 255;
                if (file.Read(&v) == -1)
                    throw std::runtime_error(path + ": truncated vertex data");
                s.positions.insert(s.positions.end(), v.position, v.position + 3);
                if (hasNormals)
                    s.normals.insert(s.normals.end(), v.normal, v.normal + 3);
                if (hasRadius)
                    result.radii.push_back(v.radius);
                if (hasEllipses) {
                    s.majorAxes.insert(s.majorAxes.end(), v.majorAxis, v.majorAxis + 3);
                    s.minorAxes.insert(s.minorAxes.end(), v.minorAxis, v.minorAxis + 3);
                }
                if (hasColors)
                    s.colors.insert(s.colors.end(), v.color, v.color + 4);
                if (hasFitOffsets)
                    fitOffsets.push_back(v.fitOffset);
            }
        } else if (&file.elements[e] == faceElement && hasFaces) {
            for (int i = 0; i < count; ++i) {
                FaceRecord f;
                if (file.Read(&f) == -1 || f.count > kMaxPolygonVertices)
                    throw std::runtime_error(path + ": bad face data");
                for (int k = 2; k < f.count; ++k) // fan triangulation
                    result.triangles.insert(result.triangles.end(),
                                            {unsigned(f.indices[0]), unsigned(f.indices[k - 1]), unsigned(f.indices[k])});
            }
        } else {
            char skipped[1 << 12];
            for (int i = 0; i < count; ++i)
                file.Read(skipped); // no property of this element is stored
        }
    }
    undoFitOffsets(s, fitOffsets);
    result.hasNormals = hasNormals && std::any_of(s.normals.begin(), s.normals.end(), [](float v) { return v != 0.0f; });
    const unsigned vertexCount = unsigned(s.size());
    if (std::any_of(result.triangles.begin(), result.triangles.end(), [&](unsigned i) { return i >= vertexCount; }))
        throw std::runtime_error(path + ": face index out of range");
    return result;
}

} // namespace splat
