// Writes surfels into a vcg mesh: positions, normals, radius (when the mesh has the
// radius component enabled), quality = member count (when present), and the per-vertex
// attributes EllipseMajorAxis / EllipseMinorAxis (docs/surfel_format.md).
#ifndef VCG_EXT_GAUSSPHERE_SURFEL_MESH_H
#define VCG_EXT_GAUSSPHERE_SURFEL_MESH_H

#include <vector>

#include <vcg/complex/complex.h>

#include "surfel_generation.h"

namespace vcg {
namespace gaussphere {

constexpr const char *kMajorAxisAttribute = "EllipseMajorAxis";
constexpr const char *kMinorAxisAttribute = "EllipseMinorAxis";
constexpr const char *kRepresentativeAttribute = "SurfelIndex";

/// Replaces the content of `mesh` with one vertex per surfel.
template <class MeshType>
void WriteSurfels(const std::vector<Surfel> &surfels, MeshType &mesh)
{
    typedef typename MeshType::CoordType Coord;
    typedef typename MeshType::VertexIterator VertexIterator;
    mesh.Clear();
    VertexIterator vi = vcg::tri::Allocator<MeshType>::AddVertices(mesh, surfels.size());
    auto major = vcg::tri::Allocator<MeshType>::template GetPerVertexAttribute<Coord>(mesh, kMajorAxisAttribute);
    auto minor = vcg::tri::Allocator<MeshType>::template GetPerVertexAttribute<Coord>(mesh, kMinorAxisAttribute);
    for (const Surfel &s : surfels) {
        vi->P() = Coord::Construct(s.position);
        vi->N() = Coord::Construct(s.normal);
        if (vcg::tri::HasPerVertexRadius(mesh)) vi->R() = s.majorAxis.Norm();
        if (vcg::tri::HasPerVertexQuality(mesh)) vi->Q() = s.memberCount;
        major[vi] = Coord::Construct(s.majorAxis);
        minor[vi] = Coord::Construct(s.minorAxis);
        ++vi;
    }
    vcg::tri::UpdateBounding<MeshType>::Box(mesh);
}

} // namespace gaussphere
} // namespace vcg

#endif
