// A plain vcg mesh type for oriented point sets (position, normal, radius, quality,
// colour), for programs that use the algorithms outside MeshLab.
#ifndef VCG_EXT_GAUSSPHERE_ORIENTED_POINT_MESH_H
#define VCG_EXT_GAUSSPHERE_ORIENTED_POINT_MESH_H

#include <vcg/complex/complex.h>

namespace vcg {
namespace gaussphere {

class OrientedPointVertex;
class OrientedPointFace;
struct OrientedPointTypes : public vcg::UsedTypes<vcg::Use<OrientedPointVertex>::AsVertexType,
                                                  vcg::Use<OrientedPointFace>::AsFaceType> {};
class OrientedPointVertex
    : public vcg::Vertex<OrientedPointTypes, vcg::vertex::Coord3f, vcg::vertex::Normal3f, vcg::vertex::Radiusf,
                         vcg::vertex::Qualityf, vcg::vertex::Color4b, vcg::vertex::BitFlags> {};
class OrientedPointFace
    : public vcg::Face<OrientedPointTypes, vcg::face::VertexRef, vcg::face::Normal3f, vcg::face::BitFlags> {};
/// vcglib 2020.09's ~TriMesh() leaves the per-vertex attributes allocated (its ClearAttributes()
/// call is commented out): this mesh frees them.
class OrientedPointMesh : public vcg::tri::TriMesh<std::vector<OrientedPointVertex>, std::vector<OrientedPointFace>>
{
public:
    OrientedPointMesh() = default;
    OrientedPointMesh(const OrientedPointMesh &) = delete;
    OrientedPointMesh &operator=(const OrientedPointMesh &) = delete;
    ~OrientedPointMesh() { ClearAttributes(); }
};

} // namespace gaussphere
} // namespace vcg

#endif
