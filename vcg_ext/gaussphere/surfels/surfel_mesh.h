// Writes surfels into a vcg mesh: positions, normals, radius (when the mesh has the
// radius component enabled), quality = member count (when present), the per-vertex
// attributes EllipseMajorAxis / EllipseMinorAxis, SurfelBlendScale when some surfel's blend
// scale is not 1, and SurfelFitOffset when some surfel was fitted to the blend (docs/surfel_format.md).
#ifndef VCG_EXT_GAUSSPHERE_SURFEL_MESH_H
#define VCG_EXT_GAUSSPHERE_SURFEL_MESH_H

#include <algorithm>
#include <cmath>
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

/// Gives each vertex s of `out` (one per surfel, as WriteSurfels makes them) the mean colour of
/// the vertices of `in` that surfel s represents (`representative`, per vertex of `in`: its
/// surfel, or -1). Precondition: both meshes have per-vertex colours.
template <class InMesh, class Indices, class OutMesh>
void ColourSurfelsByMembers(const InMesh &in, const Indices &representative, OutMesh &out)
{
    std::vector<vcg::Point4d> sum(out.vert.size(), vcg::Point4d(0, 0, 0, 0));
    std::vector<int> members(out.vert.size(), 0);
    for (size_t i = 0; i < in.vert.size(); ++i) {
        const int s = representative[i];
        if (s < 0) continue;
        const vcg::Color4b colour = in.vert[i].cC();
        sum[size_t(s)] += vcg::Point4d(colour[0], colour[1], colour[2], colour[3]);
        ++members[size_t(s)];
    }
    for (size_t s = 0; s < sum.size(); ++s) {
        const vcg::Point4d mean = sum[s] / std::max(1, members[s]);
        out.vert[s].C() = vcg::Color4b((unsigned char)std::lround(mean[0]), (unsigned char)std::lround(mean[1]),
                                       (unsigned char)std::lround(mean[2]), (unsigned char)std::lround(mean[3]));
    }
}

} // namespace gaussphere
} // namespace vcg

#endif
