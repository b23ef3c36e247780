#ifndef TESTS_ERROR_POINT_SETS_H
#define TESTS_ERROR_POINT_SETS_H

// Minimal vcg point-set types and analytic samplings for the surfel error tests.

#include <vcg/complex/complex.h>

#include <cmath>

namespace surfel_error_test {

class PlainVertex;
struct PlainTypes : vcg::UsedTypes<vcg::Use<PlainVertex>::AsVertexType>
{};
class PlainVertex
    : public vcg::Vertex<PlainTypes, vcg::vertex::Coord3f, vcg::vertex::Normal3f, vcg::vertex::BitFlags>
{};
/// Oriented points without radius: circular surfels sized by their spacing.
class PointSet : public vcg::tri::TriMesh<std::vector<PlainVertex>>
{};

class RadiusVertex;
struct RadiusTypes : vcg::UsedTypes<vcg::Use<RadiusVertex>::AsVertexType>
{};
class RadiusVertex : public vcg::Vertex<RadiusTypes, vcg::vertex::Coord3f, vcg::vertex::Normal3f,
                                        vcg::vertex::Radiusf, vcg::vertex::BitFlags>
{};
/// Oriented points with a per-vertex radius.
class RadiusPointSet : public vcg::tri::TriMesh<std::vector<RadiusVertex>>
{};

template <class Mesh>
void AddPoint(Mesh& m, const vcg::Point3f& p, const vcg::Point3f& n)
{
    vcg::tri::Allocator<Mesh>::AddVertex(m, p, n);
}

// vcg meshes cannot be copied or moved, so the samplings append to a mesh of the caller.

/// Square grid of (nx × ny) points in the plane z = height, step `step`, normals +z,
/// starting at (x0, y0).
inline void AddPlaneGrid(PointSet& m, int nx, int ny, float step, float height = 0, float x0 = 0,
                         float y0 = 0)
{
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j)
            AddPoint(m, vcg::Point3f(x0 + i * step, y0 + j * step, height), vcg::Point3f(0, 0, 1));
}

/// Nearly uniform sampling of the sphere of radius r centerd at the origin (Fibonacci
/// spiral), outward normals. Its spacing is about sqrt(4π/n)·r.
inline void AddFibonacciSphere(PointSet& m, int n, float r)
{
    const double goldenAngle = M_PI * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const double z = 1.0 - (2.0 * i + 1.0) / n;
        const double ring = std::sqrt(1.0 - z * z);
        const vcg::Point3f normal(float(ring * std::cos(goldenAngle * i)),
                                  float(ring * std::sin(goldenAngle * i)), float(z));
        AddPoint(m, normal * r, normal);
    }
}

inline double FibonacciSpacing(int n, double r)
{
    return std::sqrt(4 * M_PI / n) * r;
}

} // namespace surfel_error_test

#endif // TESTS_ERROR_POINT_SETS_H
