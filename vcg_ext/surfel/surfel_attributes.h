// The names of the per-vertex attributes that carry surfels through MeshLab layers and files
// (docs/surfel_format.md), shared by the resampler, the .surfel I/O, the renderer and the metric.
#ifndef VCG_EXT_SURFEL_SURFEL_ATTRIBUTES_H
#define VCG_EXT_SURFEL_SURFEL_ATTRIBUTES_H

#include <vcg/complex/complex.h>

namespace vcg {
namespace gaussphere {

constexpr const char *kMajorAxisAttribute = "EllipseMajorAxis";
constexpr const char *kMinorAxisAttribute = "EllipseMinorAxis";
constexpr const char *kRepresentativeAttribute = "SurfelIndex";
constexpr const char *kBlendScaleAttribute = "SurfelBlendScale";
constexpr const char *kFitOffsetAttribute = "SurfelFitOffset";

/// The per-vertex float attribute `name` of `mesh` when `wanted` (created if needed); when not,
/// none: an old one is deleted (Clear() keeps attributes) and the handle returned is invalid.
template <class MeshType>
typename MeshType::template PerVertexAttributeHandle<float> OptionalPerVertexFloat(MeshType &mesh, const char *name,
                                                                                   bool wanted)
{
    if (wanted) return vcg::tri::Allocator<MeshType>::template GetPerVertexAttribute<float>(mesh, name);
    if (vcg::tri::HasPerVertexAttribute(mesh, name)) vcg::tri::Allocator<MeshType>::DeletePerVertexAttribute(mesh, name);
    return typename MeshType::template PerVertexAttributeHandle<float>();
}

} // namespace gaussphere
} // namespace vcg

#endif
