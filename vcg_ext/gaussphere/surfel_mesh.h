// Writes surfels into a vcg mesh: positions, normals, radius (when the mesh has the
// radius component enabled), quality = member count (when present), the per-vertex
// attributes EllipseMajorAxis / EllipseMinorAxis, and SurfelBlendScale when some surfel's blend
// scale is not 1 (docs/surfel_format.md).
#ifndef VCG_EXT_GAUSSPHERE_SURFEL_MESH_H
#define VCG_EXT_GAUSSPHERE_SURFEL_MESH_H

#include <algorithm>
#include <vector>

#include <vcg/complex/complex.h>

#include "surfel_generation.h"

namespace vcg {
namespace gaussphere {

constexpr const char *kMajorAxisAttribute = "EllipseMajorAxis";
constexpr const char *kMinorAxisAttribute = "EllipseMinorAxis";
constexpr const char *kRepresentativeAttribute = "SurfelIndex";
constexpr const char *kBlendScaleAttribute = "SurfelBlendScale";

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
    const bool narrowed =
        std::any_of(surfels.begin(), surfels.end(), [](const Surfel &s) { return s.blendScale != 1.f; });
    typename MeshType::template PerVertexAttributeHandle<float> blend;
    if (narrowed)
        blend = vcg::tri::Allocator<MeshType>::template GetPerVertexAttribute<float>(mesh, kBlendScaleAttribute);
    else if (vcg::tri::HasPerVertexAttribute(mesh, kBlendScaleAttribute)) // Clear() keeps attributes
        vcg::tri::Allocator<MeshType>::DeletePerVertexAttribute(mesh, kBlendScaleAttribute);
    for (const Surfel &s : surfels) {
        vi->P() = Coord::Construct(s.position);
        vi->N() = Coord::Construct(s.normal);
        if (vcg::tri::HasPerVertexRadius(mesh)) vi->R() = s.majorAxis.Norm();
        if (vcg::tri::HasPerVertexQuality(mesh)) vi->Q() = s.memberCount;
        major[vi] = Coord::Construct(s.majorAxis);
        minor[vi] = Coord::Construct(s.minorAxis);
        if (narrowed) blend[vi] = s.blendScale;
        ++vi;
    }
    vcg::tri::UpdateBounding<MeshType>::Box(mesh);
}

} // namespace gaussphere
} // namespace vcg

#endif
