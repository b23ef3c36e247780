#include "mesh_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include <vcg/complex/complex.h>
#include <vcg/space/index/grid_static_ptr.h>
#include <wrap/io_trimesh/import_ply.h>

namespace gsbench {

namespace {

// The mesh type PLY files are read into; only positions and faces are used.
class PlyVertex;
class PlyFace;
struct PlyTypes : vcg::UsedTypes<vcg::Use<PlyVertex>::AsVertexType, vcg::Use<PlyFace>::AsFaceType>
{
};
class PlyVertex : public vcg::Vertex<PlyTypes, vcg::vertex::Coord3f, vcg::vertex::BitFlags>
{
};
class PlyFace : public vcg::Face<PlyTypes, vcg::face::VertexRef, vcg::face::BitFlags>
{
};
class PlyMesh : public vcg::tri::TriMesh<std::vector<PlyVertex>, std::vector<PlyFace>>
{
};

vcg::Point3d ClosestPointOnSegment(const vcg::Point3d &a, const vcg::Point3d &b, const vcg::Point3d &p)
{
    const vcg::Point3d ab = b - a;
    const double length2 = ab.SquaredNorm();
    if (length2 == 0) return a;
    const double t = std::min(1.0, std::max(0.0, (p - a).dot(ab) / length2));
    return a + ab * t;
}

/// Whether `q`, a point in the plane of `t` with normal `n` (unnormalized, not zero), lies inside
/// `t` or on its border: q is on the inner side of each edge.
bool InsideTriangle(const Triangle &t, const vcg::Point3d &n, const vcg::Point3d &q)
{
    for (int e = 0; e < 3; ++e) {
        const vcg::Point3d &a = t.v[e], &b = t.v[(e + 1) % 3];
        if (((b - a) ^ (q - a)).dot(n) < 0) return false;
    }
    return true;
}

/// The distance functor and marker vcg::GridClosest asks for. Triangles spanning several grid
/// cells may be measured more than once: no marks, so that queries share nothing and can run
/// in parallel.
struct TriangleDistanceFunctor
{
    typedef vcg::Point3d QueryType;
    static vcg::Point3d Pos(const QueryType &p) { return p; }
    bool operator()(const Triangle &t, const vcg::Point3d &p, double &minDistance, vcg::Point3d &closest) const
    {
        const vcg::Point3d q = ClosestPointOnTriangle(t, p);
        const double d = (q - p).Norm();
        if (!(d < minDistance)) return false;
        minDistance = d;
        closest = q;
        return true;
    }
};

struct NoMarks
{
    void UnMarkAll() const {}
    bool IsMarked(const Triangle *) const { return false; }
    void Mark(const Triangle *) const {}
};

} // namespace

void Triangle::GetBBox(vcg::Box3d &box) const
{
    box.Set(v[0]);
    box.Add(v[1]);
    box.Add(v[2]);
}

double Triangle::Area() const { return 0.5 * ((v[1] - v[0]) ^ (v[2] - v[0])).Norm(); }

vcg::Point3d ClosestPointOnTriangle(const Triangle &t, const vcg::Point3d &p)
{
    // The projection on the plane when it falls inside, else the nearest point of the border.
    const vcg::Point3d n = (t.v[1] - t.v[0]) ^ (t.v[2] - t.v[0]);
    const double n2 = n.SquaredNorm();
    if (n2 > 0) {
        const vcg::Point3d projection = p - n * ((p - t.v[0]).dot(n) / n2);
        if (InsideTriangle(t, n, projection)) return projection;
    }
    vcg::Point3d best = ClosestPointOnSegment(t.v[0], t.v[1], p);
    for (int e = 1; e < 3; ++e) {
        const vcg::Point3d q = ClosestPointOnSegment(t.v[e], t.v[(e + 1) % 3], p);
        if ((q - p).SquaredNorm() < (best - p).SquaredNorm()) best = q;
    }
    return best;
}

std::vector<Triangle> LoadTriangles(const std::string &path)
{
    PlyMesh mesh;
    int mask = 0;
    const int status = vcg::tri::io::ImporterPLY<PlyMesh>::Open(mesh, path.c_str(), mask);
    // A non-critical status (a property the mesh type has no room for) still loads the faces.
    if (status != 0 && vcg::tri::io::ImporterPLY<PlyMesh>::ErrorCritical(status))
        throw std::runtime_error("cannot read " + path + ": " + vcg::tri::io::ImporterPLY<PlyMesh>::ErrorMsg(status));
    std::vector<Triangle> triangles;
    triangles.reserve(mesh.face.size());
    for (const PlyFace &f : mesh.face) {
        if (f.IsD()) continue;
        Triangle t;
        for (int i = 0; i < 3; ++i) t.v[i] = vcg::Point3d::Construct(f.cV(i)->cP());
        triangles.push_back(t);
    }
    if (triangles.empty()) throw std::runtime_error(path + " has no face");
    return triangles;
}

double BoundingBoxDiagonal(const std::vector<Triangle> &triangles)
{
    vcg::Box3d box;
    for (const Triangle &t : triangles)
        for (const vcg::Point3d &v : t.v) box.Add(v);
    return box.Diag();
}

std::vector<vcg::Point3d> SampleByArea(const std::vector<Triangle> &triangles, std::size_t count, std::uint64_t seed)
{
    std::vector<double> cumulativeArea(triangles.size());
    double total = 0;
    for (std::size_t i = 0; i < triangles.size(); ++i) cumulativeArea[i] = total += triangles[i].Area();
    if (!(total > 0)) throw std::runtime_error("the mesh has no area to sample");
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<vcg::Point3d> samples;
    samples.reserve(count);
    for (std::size_t s = 0; s < count; ++s) {
        const double at = unit(random) * total;
        const std::size_t i = std::min<std::size_t>(
            std::upper_bound(cumulativeArea.begin(), cumulativeArea.end(), at) - cumulativeArea.begin(),
            triangles.size() - 1);
        // Uniform in the triangle: sqrt(r1) spreads the points evenly from the first vertex.
        const double r1 = std::sqrt(unit(random)), r2 = unit(random);
        const Triangle &t = triangles[i];
        samples.push_back(t.v[0] * (1 - r1) + t.v[1] * (r1 * (1 - r2)) + t.v[2] * (r1 * r2));
    }
    return samples;
}

struct TriangleIndex::CellGrid : vcg::GridStaticPtr<Triangle, double>
{
};

TriangleIndex::TriangleIndex(const std::vector<Triangle> &triangles) : triangles_(triangles), grid_(new CellGrid)
{
    if (triangles_.empty()) throw std::invalid_argument("TriangleIndex needs at least one triangle");
    grid_->Set(triangles_.begin(), triangles_.end());
}

TriangleIndex::~TriangleIndex() = default;

double TriangleIndex::Distance(const vcg::Point3d &p) const
{
    TriangleDistanceFunctor distance;
    NoMarks marks;
    double minDistance = 0;
    vcg::Point3d closest;
    // No distance limit: the search grows until it meets a triangle.
    vcg::GridClosest(*grid_, distance, marks, p, std::numeric_limits<double>::max(), minDistance, closest);
    return minDistance;
}

std::vector<double> DistancesTo(const TriangleIndex &index, const std::vector<vcg::Point3d> &points)
{
    std::vector<double> distances(points.size());
#pragma omp parallel for schedule(dynamic, 4096)
    for (long i = 0; i < long(points.size()); ++i) distances[i] = index.Distance(points[i]);
    return distances;
}

DistanceSummary Summarize(std::vector<double> &distances)
{
    DistanceSummary s;
    if (distances.empty()) return s;
    double squares = 0;
    for (double d : distances) {
        squares += d * d;
        s.max = std::max(s.max, d);
    }
    s.rms = std::sqrt(squares / distances.size());
    const std::size_t rank = std::size_t(std::ceil(0.99 * distances.size())); // 1-based
    std::nth_element(distances.begin(), distances.begin() + (rank - 1), distances.end());
    s.p99 = distances[rank - 1];
    return s;
}

namespace {

DistanceSummary Scaled(DistanceSummary s, double factor)
{
    s.rms *= factor;
    s.p99 *= factor;
    s.max *= factor;
    return s;
}

} // namespace

MeshDistance MeasureMeshDistance(const std::vector<Triangle> &reconstruction, const std::vector<Triangle> &original,
                                 std::size_t samples, std::uint64_t seed)
{
    MeshDistance result;
    result.diagonal = BoundingBoxDiagonal(original);
    std::vector<double> toOriginal, toReconstruction;
    {
        const TriangleIndex index(original);
        toOriginal = DistancesTo(index, SampleByArea(reconstruction, samples, seed));
    }
    {
        const TriangleIndex index(reconstruction);
        toReconstruction = DistancesTo(index, SampleByArea(original, samples, seed + 1));
    }
    std::vector<double> pooled(toOriginal);
    pooled.insert(pooled.end(), toReconstruction.begin(), toReconstruction.end());
    const double unit = 1.0 / result.diagonal;
    result.toOriginal = Scaled(Summarize(toOriginal), unit);
    result.toReconstruction = Scaled(Summarize(toReconstruction), unit);
    result.symmetric = Scaled(Summarize(pooled), unit);
    return result;
}

} // namespace gsbench
