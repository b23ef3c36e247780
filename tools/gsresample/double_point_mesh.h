// Oriented points in double precision, for PLY files whose coordinates are double: read here
// before they are moved near the origin and become float (ply_input.h), and written from here
// with that move undone (gsresample's PLY output), so georeferenced coordinates, millions of
// units from the origin, keep their precision through a float resampler.
#ifndef GSRESAMPLE_DOUBLE_POINT_MESH_H
#define GSRESAMPLE_DOUBLE_POINT_MESH_H

#include <vcg/complex/complex.h>

namespace gsresample {

class DoublePointVertex;
class DoublePointFace;
struct DoublePointTypes : public vcg::UsedTypes<vcg::Use<DoublePointVertex>::AsVertexType,
                                                vcg::Use<DoublePointFace>::AsFaceType> {};
class DoublePointVertex
    : public vcg::Vertex<DoublePointTypes, vcg::vertex::Coord3d, vcg::vertex::Normal3d, vcg::vertex::Radiusf,
                         vcg::vertex::Qualityd, vcg::vertex::Color4b, vcg::vertex::BitFlags> {}; // Qualityd: vcglib's
                                                                          // PLY writer types quality as the coordinates
// A face type, though no face is kept: every vcglib's PLY writer needs one (a mesh without
// leaves it a const pointer it cannot assign).
class DoublePointFace : public vcg::Face<DoublePointTypes, vcg::face::VertexRef, vcg::face::BitFlags> {};
class DoublePointMesh : public vcg::tri::TriMesh<std::vector<DoublePointVertex>, std::vector<DoublePointFace>>
{
public:
    DoublePointMesh() = default;
    DoublePointMesh(const DoublePointMesh &) = delete;
    DoublePointMesh &operator=(const DoublePointMesh &) = delete;
    ~DoublePointMesh() { ClearAttributes(); }
};

/// What ReadOrientedPoints found in the file, and where it put the points.
struct InputInfo
{
    bool doubleCoordinates = false; ///< the file's x, y or z is double
    vcg::Point3d origin{0, 0, 0};   ///< the mesh holds each point minus this: for double coordinates the
                                    ///< centre of their bounding box, else 0
    bool vertexColours = false;     ///< the vertices have colours
};

} // namespace gsresample

#endif
