// The point sets the benchmark moves around: the input S, and each method's output S' with
// whatever the error metric can use of it (ellipse axes and the point-to-surfel map exist
// only for our resampler; the peers output plain oriented points, i.e. circular surfels).
#ifndef GSBENCH_POINT_SETS_H
#define GSBENCH_POINT_SETS_H

#include <string>
#include <vector>

#include <vcg_ext/gaussphere/oriented_point_mesh.h>
#include <vcg_ext/surfel_error/surfel_error.h>

namespace gsbench {

using PointMesh = vcg::gaussphere::OrientedPointMesh;

/// Loads a PLY point set with normals. Per-vertex radius is zeroed unless the file has one:
/// vcg leaves the component uninitialised, and the error metric would read it as a surfel size.
/// Throws std::runtime_error when the file cannot be read or has no normals.
void LoadPointSet(const std::string &path, PointMesh &mesh);

/// Saves positions and normals (and radius when `withRadius`) as binary PLY.
void SavePointSet(PointMesh &mesh, const std::string &path, bool withRadius);

/// Vertex count from a PLY header, without loading the file; -1 if unreadable.
int PlyVertexCount(const std::string &path);

/// The vertices `indices` of `from` (positions, normals), radius zeroed.
void CopySubset(const PointMesh &from, const std::vector<int> &indices, PointMesh &to);

/// One method's output S'.
struct SimplifiedSet
{
    PointMesh mesh;                         ///< centres and normals
    std::vector<vcg::Point3f> major, minor; ///< ellipse semi-axes per vertex; empty: circular
    std::vector<float> blendScale;          ///< per vertex (SurfelBlendScale); empty: all 1
    std::vector<int> representative;        ///< per input point: its surfel; empty: nearest centre

    int Count() const { return mesh.vn; }
    vcg::gaussphere::metric::SurfelErrorAttributes Attributes() const;
};

/// S' = S: every input point is its own circular surfel. Its error is the metric's floor.
void MakeIdentitySet(const PointMesh &input, SimplifiedSet &set);

/// Error of `set` against `input` with the metric's default parameters. `perPointDistance`, if
/// given, receives d(q, S') per input vertex (NaN where undefined), in model units.
vcg::gaussphere::metric::SurfelErrorStats Evaluate(const PointMesh &input, const SimplifiedSet &set,
                                    std::vector<float> *perPointDistance = nullptr);

} // namespace gsbench

#endif
