// Conversion between .surfel records and vcg meshes (surfel_records_mesh.h): what a layer
// without ellipse attributes or radius writes, and what such a file loads as.
#include "surfel_fixture.h"

#include <surfel_records_mesh.h>

#include <gtest/gtest.h>

namespace {

using surfel_io::SurfelRecord;
using vcg::gaussphere::kFitOffsetAttribute;
using vcg::gaussphere::kMajorAxisAttribute;
using vcg::gaussphere::kMinorAxisAttribute;

class Vertex;
class Face;
struct UsedTypes : vcg::UsedTypes<vcg::Use<Vertex>::AsVertexType, vcg::Use<Face>::AsFaceType> {};
class Vertex : public vcg::Vertex<UsedTypes, vcg::vertex::Coord3f, vcg::vertex::Normal3f,
                                  vcg::vertex::Radiusf, vcg::vertex::Qualityf,
                                  vcg::vertex::Color4b, vcg::vertex::BitFlags> {};
class Face : public vcg::Face<UsedTypes, vcg::face::VertexRef> {};
class Mesh : public vcg::tri::TriMesh<std::vector<Vertex>, std::vector<Face>> {};

// Like MeshLab's CMeshO: the radius is an optional component, off until enabled.
class OcfVertex;
struct OcfUsedTypes : vcg::UsedTypes<vcg::Use<OcfVertex>::AsVertexType> {};
class OcfVertex : public vcg::Vertex<OcfUsedTypes, vcg::vertex::InfoOcf, vcg::vertex::Coord3f,
                                     vcg::vertex::Normal3f, vcg::vertex::BitFlags,
                                     vcg::vertex::RadiusfOcf> {};
class OcfMesh : public vcg::tri::TriMesh<vcg::vertex::vector_ocf<OcfVertex>> {};

template <class MeshType>
bool hasAttribute(MeshType& mesh, const char* name) {
  return vcg::tri::HasPerVertexAttribute(mesh, name);
}

TEST(SurfelRecordsMesh, MeshKeepsEveryAttribute) {
  const std::vector<SurfelRecord> surfels = syntheticSurfels(50);
  Mesh mesh;
  surfel_io::addRecordsToMesh(surfels, mesh);
  ASSERT_EQ(mesh.vn, 50);
  EXPECT_TRUE(hasAttribute(mesh, kMajorAxisAttribute));
  EXPECT_TRUE(hasAttribute(mesh, kMinorAxisAttribute));
  auto major = vcg::tri::Allocator<Mesh>::FindPerVertexAttribute<vcg::Point3f>(mesh, kMajorAxisAttribute);
  EXPECT_EQ(major[7], vcg::Point3f(surfels[7].majorAxis.data()));
  EXPECT_EQ(mesh.vert[7].R(), surfels[7].radius);
  EXPECT_EQ(surfel_io::recordsFromMesh(mesh), surfels);
}

TEST(SurfelRecordsMesh, DeletedVerticesAreNotWritten) {
  const std::vector<SurfelRecord> surfels = syntheticSurfels(5);
  Mesh mesh;
  surfel_io::addRecordsToMesh(surfels, mesh);
  vcg::tri::Allocator<Mesh>::DeleteVertex(mesh, mesh.vert[1]);
  EXPECT_EQ(surfel_io::recordsFromMesh(mesh),
            std::vector<SurfelRecord>({surfels[0], surfels[2], surfels[3], surfels[4]}));
}

TEST(SurfelRecordsMesh, LayerWithoutEllipseAttributesWritesZeroAxesAndLoadsWithoutThem) {
  std::vector<SurfelRecord> surfels = syntheticSurfels(4);
  for (SurfelRecord& s : surfels) s.majorAxis = s.minorAxis = surfel_io::Vec3f{};
  Mesh mesh;
  surfel_io::addRecordsToMesh(surfels, mesh);
  EXPECT_FALSE(hasAttribute(mesh, kMajorAxisAttribute));
  EXPECT_FALSE(hasAttribute(mesh, kMinorAxisAttribute));
  EXPECT_EQ(surfel_io::recordsFromMesh(mesh), surfels);
}

TEST(SurfelRecordsMesh, OneMissingAttributeWritesThatAxisAsZero) {
  std::vector<SurfelRecord> surfels = syntheticSurfels(4);
  Mesh mesh;
  surfel_io::addRecordsToMesh(surfels, mesh);
  vcg::tri::Allocator<Mesh>::DeletePerVertexAttribute(mesh, kMinorAxisAttribute);
  for (SurfelRecord& s : surfels) s.minorAxis = surfel_io::Vec3f{};
  EXPECT_EQ(surfel_io::recordsFromMesh(mesh), surfels);
}

TEST(SurfelRecordsMesh, RadiusFollowsTheOptionalComponent) {
  const std::vector<SurfelRecord> surfels = syntheticSurfels(3);
  OcfMesh withoutRadius;
  surfel_io::addRecordsToMesh(surfels, withoutRadius);
  for (const SurfelRecord& s : surfel_io::recordsFromMesh(withoutRadius)) EXPECT_EQ(s.radius, 0);

  OcfMesh withRadius;
  withRadius.vert.EnableRadius();
  surfel_io::addRecordsToMesh(surfels, withRadius);
  const std::vector<SurfelRecord> written = surfel_io::recordsFromMesh(withRadius);
  ASSERT_EQ(written.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(written[i].radius, surfels[i].radius);
    EXPECT_EQ(written[i].majorAxis, surfels[i].majorAxis);
    EXPECT_EQ(written[i].quality, 0) << "the mesh has no quality component";
  }
}

TEST(SurfelRecordsMesh, FitOffsetAttributeOnlyWhenSomeOffsetIsNotZero) {
  std::vector<SurfelRecord> surfels = syntheticSurfels(6);
  ASSERT_TRUE(surfel_io::hasFitOffsets(surfels));
  Mesh fitted;
  surfel_io::addRecordsToMesh(surfels, fitted);
  ASSERT_TRUE(hasAttribute(fitted, kFitOffsetAttribute));
  auto fit = vcg::tri::Allocator<Mesh>::FindPerVertexAttribute<float>(fitted, kFitOffsetAttribute);
  for (std::size_t i = 0; i < surfels.size(); ++i) EXPECT_EQ(fit[i], surfels[i].fitOffset) << i;
  EXPECT_EQ(surfel_io::recordsFromMesh(fitted), surfels);

  for (SurfelRecord& s : surfels) s.fitOffset = 0;
  Mesh unfitted;
  surfel_io::addRecordsToMesh(surfels, unfitted);
  EXPECT_FALSE(hasAttribute(unfitted, kFitOffsetAttribute));
  EXPECT_EQ(surfel_io::recordsFromMesh(unfitted), surfels);
}

TEST(SurfelRecordsMesh, NoSurfelsAddNothing) {
  Mesh mesh;
  surfel_io::addRecordsToMesh({}, mesh);
  EXPECT_EQ(mesh.vn, 0);
  EXPECT_FALSE(hasAttribute(mesh, kMajorAxisAttribute));
  EXPECT_TRUE(surfel_io::recordsFromMesh(mesh).empty());
}

}  // namespace
