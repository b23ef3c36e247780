// Distance between two triangle meshes, each way, from uniform area samples of one mesh and the
// exact distance of every sample to the nearest triangle of the other.
//
// The downstream benchmark (scripts/bench_downstream.sh) measures with it how far a surface
// reconstructed from a resampled point set lies from the original mesh. Exact here means the
// closest point is found on the triangles themselves (not on vertices or a sampled copy): a
// regular grid of the target triangles (vcg::GridStaticPtr) is searched in growing shells until
// no unvisited cell can hold a closer triangle. Only the sampling is random: the maximum over
// the samples approaches the true one-sided Hausdorff distance from below.
#ifndef GSBENCH_MESH_DISTANCE_H
#define GSBENCH_MESH_DISTANCE_H

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <vcg/space/box3.h>
#include <vcg/space/point3.h>

namespace gsbench {

/// One triangle in double precision, as vcg::GridStaticPtr stores it (it asks every object for
/// its scalar type, its box and whether it is deleted).
struct Triangle
{
    typedef double ScalarType;
    vcg::Point3d v[3];

    void GetBBox(vcg::Box3d &box) const;
    bool IsD() const { return false; }
    double Area() const;
};

/// The point of `t` closest to `p`. Handles degenerate triangles (segments and points).
vcg::Point3d ClosestPointOnTriangle(const Triangle &t, const vcg::Point3d &p);

/// The faces of a PLY mesh (polygons as vcg's reader triangulates them). Throws
/// std::runtime_error when the file cannot be read or has no face.
std::vector<Triangle> LoadTriangles(const std::string &path);

/// Bounding-box diagonal of the triangles' vertices.
double BoundingBoxDiagonal(const std::vector<Triangle> &triangles);

/// `count` points uniformly distributed over the area of `triangles` (a triangle is chosen with
/// probability proportional to its area, then a point uniformly inside it), reproducible from `seed`.
std::vector<vcg::Point3d> SampleByArea(const std::vector<Triangle> &triangles, std::size_t count, std::uint64_t seed);

/// Nearest-triangle queries on a fixed set of triangles; safe to query from several threads.
class TriangleIndex
{
public:
    explicit TriangleIndex(const std::vector<Triangle> &triangles);
    ~TriangleIndex();
    TriangleIndex(const TriangleIndex &) = delete;
    TriangleIndex &operator=(const TriangleIndex &) = delete;

    /// Exact distance from `p` to the nearest triangle.
    double Distance(const vcg::Point3d &p) const;

private:
    struct CellGrid;
    std::vector<Triangle> triangles_; ///< the grid points into this copy
    std::unique_ptr<CellGrid> grid_;
};

/// Distance of every point of `points` to the nearest triangle of `index` (OpenMP over the points).
std::vector<double> DistancesTo(const TriangleIndex &index, const std::vector<vcg::Point3d> &points);

/// RMS, 99th percentile and maximum of a set of distances.
struct DistanceSummary
{
    double rms = 0, p99 = 0, max = 0;
};

/// The summary of `distances`; the 99th percentile is the value of rank ceil(0.99 n) in
/// ascending order (nearest rank). `distances` is reordered.
DistanceSummary Summarize(std::vector<double> &distances);

/// The distance between a reconstruction and the original mesh, each way and both ways together.
struct MeshDistance
{
    DistanceSummary toOriginal;       ///< samples of the reconstruction to the original mesh
    DistanceSummary toReconstruction; ///< samples of the original mesh to the reconstruction
    DistanceSummary symmetric;        ///< both sample sets pooled (equal counts: each way weighs half)
    double diagonal = 0;              ///< the original mesh's bounding-box diagonal
};

/// Measures `reconstruction` against `original` with `samples` area samples of each, in units of
/// the original's bounding-box diagonal.
MeshDistance MeasureMeshDistance(const std::vector<Triangle> &reconstruction, const std::vector<Triangle> &original,
                                 std::size_t samples, std::uint64_t seed);

} // namespace gsbench

#endif
