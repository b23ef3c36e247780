// Converts between `.surfel` records (surfel_file.h) and a vcg mesh whose vertices carry
// the surfel attributes of docs/surfel_format.md, the ellipse axes being the per-vertex
// attributes (of type MeshType::CoordType, Point3m in MeshLab) named in
// vcg_ext/surfel/surfel_attributes.h. Header-only, templated on the mesh type, so MeshLab's
// CMeshO (io_surfel plugin) and the test and tool meshes share it.
#ifndef GAUSSPHERE_IO_SURFEL_SURFEL_RECORDS_MESH_H
#define GAUSSPHERE_IO_SURFEL_SURFEL_RECORDS_MESH_H

#include "surfel_file.h"

#include <vcg/complex/complex.h>
#include <vcg_ext/surfel/surfel_attributes.h>

#include <vector>

namespace surfel_io {

namespace detail {

template <class Point3>
Vec3f toVec3f(const Point3& p) {
  return {{float(p[0]), float(p[1]), float(p[2])}};
}

template <class Point3>
Point3 toPoint3(const Vec3f& v) {
  return Point3(v[0], v[1], v[2]);
}

}  // namespace detail

// One record per live (not deleted) vertex, in vertex order. What the mesh lacks is written
// as zero: the radius without the radius component, an axis without its attribute (the
// two attributes are looked up independently); a missing blend scale as 1, a missing fit
// offset as 0; faces and edges are not part of the format.
// Non-const: vcg looks attributes up through a mutable mesh.
template <class MeshType>
std::vector<SurfelRecord> recordsFromMesh(MeshType& mesh) {
  using Point3 = typename MeshType::CoordType;
  using Allocator = vcg::tri::Allocator<MeshType>;
  using vcg::gaussphere::kMajorAxisAttribute;
  using vcg::gaussphere::kMinorAxisAttribute;
  auto major = Allocator::template FindPerVertexAttribute<Point3>(mesh, kMajorAxisAttribute);
  auto minor = Allocator::template FindPerVertexAttribute<Point3>(mesh, kMinorAxisAttribute);
  auto blend = Allocator::template FindPerVertexAttribute<float>(mesh, vcg::gaussphere::kBlendScaleAttribute);
  auto fit = Allocator::template FindPerVertexAttribute<float>(mesh, vcg::gaussphere::kFitOffsetAttribute);
  const bool hasBlend = Allocator::IsValidHandle(mesh, blend);
  const bool hasFit = Allocator::IsValidHandle(mesh, fit);
  const bool hasMajor = Allocator::IsValidHandle(mesh, major);
  const bool hasMinor = Allocator::IsValidHandle(mesh, minor);
  const bool hasNormal = vcg::tri::HasPerVertexNormal(mesh);
  const bool hasRadius = vcg::tri::HasPerVertexRadius(mesh);
  const bool hasQuality = vcg::tri::HasPerVertexQuality(mesh);
  const bool hasColor = vcg::tri::HasPerVertexColor(mesh);

  std::vector<SurfelRecord> surfels;
  surfels.reserve(mesh.vn);
  for (auto v = mesh.vert.begin(); v != mesh.vert.end(); ++v) {
    if (v->IsD()) continue;
    SurfelRecord s;
    s.position = detail::toVec3f(v->cP());
    if (hasNormal) s.normal = detail::toVec3f(v->cN());
    if (hasRadius) s.radius = float(v->cR());
    if (hasMajor) s.majorAxis = detail::toVec3f(major[v]);
    if (hasMinor) s.minorAxis = detail::toVec3f(minor[v]);
    if (hasQuality) s.quality = float(v->cQ());
    if (hasBlend) s.blendScale = blend[v];
    if (hasFit) s.fitOffset = fit[v];
    if (hasColor)
      for (int c = 0; c < 4; ++c) s.color[c] = v->cC()[c];
    surfels.push_back(s);
  }
  return surfels;
}

// Adds one vertex per surfel to an empty mesh (as MeshLab hands it to an IO plugin). Only
// the components the mesh has are filled: in CMeshO the radius is optional and must be
// enabled first. Both ellipse attributes are added when some surfel has a non-zero axis
// (hasEllipseFrames) and neither otherwise: a file written from a layer without ellipse
// frames reads back without them, and none are synthesized from the radius. The blend scale
// attribute likewise exists only when some surfel's differs from 1 (hasBlendScales), the fit
// offset attribute only when some surfel's is not 0 (hasFitOffsets).
template <class MeshType>
void addRecordsToMesh(const std::vector<SurfelRecord>& surfels, MeshType& mesh) {
  using Point3 = typename MeshType::CoordType;
  using Allocator = vcg::tri::Allocator<MeshType>;
  const bool hasNormal = vcg::tri::HasPerVertexNormal(mesh);
  const bool hasRadius = vcg::tri::HasPerVertexRadius(mesh);
  const bool hasQuality = vcg::tri::HasPerVertexQuality(mesh);
  const bool hasColor = vcg::tri::HasPerVertexColor(mesh);

  if (surfels.empty()) return;
  auto v = Allocator::AddVertices(mesh, surfels.size());
  typename MeshType::template PerVertexAttributeHandle<Point3> major, minor;
  const bool withFrames = hasEllipseFrames(surfels);
  if (withFrames) {
    using vcg::gaussphere::kMajorAxisAttribute;
    using vcg::gaussphere::kMinorAxisAttribute;
    major = Allocator::template GetPerVertexAttribute<Point3>(mesh, kMajorAxisAttribute);
    minor = Allocator::template GetPerVertexAttribute<Point3>(mesh, kMinorAxisAttribute);
  }
  const bool withBlend = hasBlendScales(surfels), withFit = hasFitOffsets(surfels);
  auto blend = vcg::gaussphere::OptionalPerVertexFloat(mesh, vcg::gaussphere::kBlendScaleAttribute, withBlend);
  auto fit = vcg::gaussphere::OptionalPerVertexFloat(mesh, vcg::gaussphere::kFitOffsetAttribute, withFit);
  for (const SurfelRecord& s : surfels) {
    v->P() = detail::toPoint3<Point3>(s.position);
    if (hasNormal) v->N() = detail::toPoint3<typename MeshType::VertexType::NormalType>(s.normal);
    if (hasRadius) v->R() = s.radius;
    if (hasQuality) v->Q() = s.quality;
    if (hasColor) v->C() = vcg::Color4b(s.color[0], s.color[1], s.color[2], s.color[3]);
    if (withFrames) {
      major[v] = detail::toPoint3<Point3>(s.majorAxis);
      minor[v] = detail::toPoint3<Point3>(s.minorAxis);
    }
    if (withBlend) blend[v] = s.blendScale;
    if (withFit) fit[v] = s.fitOffset;
    ++v;
  }
}

}  // namespace surfel_io

#endif
