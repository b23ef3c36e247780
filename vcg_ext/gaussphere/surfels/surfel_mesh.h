// Writes surfels into a vcg mesh: positions, normals, radius (when the mesh has the
// radius component enabled), quality = member count (when present), the per-vertex
// attributes EllipseMajorAxis / EllipseMinorAxis, SurfelBlendScale when some surfel's blend
// scale is not 1, and SurfelFitOffset when some surfel was fitted to the blend (docs/surfel_format.md).
#ifndef VCG_EXT_GAUSSPHERE_SURFEL_MESH_H
#define VCG_EXT_GAUSSPHERE_SURFEL_MESH_H

#include <algorithm>
#include <vector>

#include <vcg/complex/complex.h>

#include <vcg_ext/surfel/surfel.h>
#include <vcg_ext/surfel/surfel_attributes.h>

namespace vcg {
namespace gaussphere {

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
    const bool fitted = std::any_of(surfels.begin(), surfels.end(), [](const Surfel &s) { return s.fitOffset != 0.f; });
    auto blend = OptionalPerVertexFloat(mesh, kBlendScaleAttribute, narrowed);
    auto fit = OptionalPerVertexFloat(mesh, kFitOffsetAttribute, fitted);
    for (const Surfel &s : surfels) {
        vi->P() = Coord::Construct(s.position);
        vi->N() = Coord::Construct(s.normal);
        if (vcg::tri::HasPerVertexRadius(mesh)) vi->R() = float(vcg::Point3d::Construct(s.majorAxis).Norm());
        if (vcg::tri::HasPerVertexQuality(mesh)) vi->Q() = s.memberCount;
        major[vi] = Coord::Construct(s.majorAxis);
        minor[vi] = Coord::Construct(s.minorAxis);
        if (narrowed) blend[vi] = s.blendScale;
        if (fitted) fit[vi] = s.fitOffset;
        ++vi;
    }
    vcg::tri::UpdateBounding<MeshType>::Box(mesh);
}

} // namespace gaussphere
} // namespace vcg

#endif
