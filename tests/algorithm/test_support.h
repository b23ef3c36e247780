// Shared generators and helpers for the algorithm tests: analytic point sets (grids,
// strips, cube surfaces, Fibonacci spheres), a hand-built neighbour graph, and a guard
// that restores the OpenMP thread count.
#ifndef GAUSSPHERE_TESTS_ALGORITHM_TEST_SUPPORT_H
#define GAUSSPHERE_TESTS_ALGORITHM_TEST_SUPPORT_H

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>
#include <vcg_ext/gaussphere/oriented_point_mesh.h>
#include <omp.h>

namespace gstest {

typedef vcg::Point3f P3;
using vcg::gaussphere::PointArray;
using vcg::gaussphere::IndexArray;
const double kPi = 3.14159265358979323846;

/// An oriented point set as two parallel arrays, plus an optional per-point tag
/// (e.g. the cube face a point was sampled on).
struct PointSet
{
    vcg::gaussphere::PointArray points, normals;
    std::vector<int> tag;

    void Add(const P3 &p, const P3 &n, int t = 0)
    {
        points.push_back(p);
        normals.push_back(n);
        tag.push_back(t);
    }
    int Size() const { return int(points.size()); }
};

/// nx x ny grid in the plane z = 0 with spacing h, first point at the origin, normal +z.
inline PointSet PlaneGrid(int nx, int ny, float h = 1.f)
{
    PointSet s;
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) s.Add(P3(x * h, y * h, 0), P3(0, 0, 1));
    return s;
}

/// n points spread evenly over the unit sphere (golden-angle spiral); normal = position.
inline PointSet FibonacciSphere(int n, float radius = 1.f)
{
    PointSet s;
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const double z = 1.0 - (2.0 * i + 1.0) / n;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        const P3 d(float(r * std::cos(golden * i)), float(r * std::sin(golden * i)), float(z));
        s.Add(d * radius, d);
    }
    return s;
}

/// Unit directions spread evenly over the sphere (for probing the Gaussian sphere).
inline PointArray FibonacciDirections(int n)
{
    return FibonacciSphere(n).normals;
}

/// The surface of the cube [-1,1]^3 sampled on a grid of `cells` cells per edge.
/// Face-interior points carry their face normal and tag 0..5 (the face: +x,-x,+y,-y,+z,-z).
/// With `withEdges`, points on the 12 edges (corners excluded) carry the normalized sum
/// of the two face normals and tag 6; the 8 corners carry the sum of three, tag 7.
inline PointSet CubeSurface(int cells, bool withEdges)
{
    PointSet s;
    const float h = 2.f / cells;
    for (int a = 0; a <= cells; ++a)
        for (int b = 0; b <= cells; ++b)
            for (int c = 0; c <= cells; ++c) {
                const int ia[3] = {a, b, c};
                P3 p, n(0, 0, 0);
                int onBoundary = 0, face = -1;
                for (int d = 0; d < 3; ++d) {
                    p[d] = -1.f + ia[d] * h;
                    if (ia[d] == 0 || ia[d] == cells) {
                        ++onBoundary;
                        n[d] = ia[d] == 0 ? -1.f : 1.f;
                        face = 2 * d + (ia[d] == 0 ? 1 : 0);
                    }
                }
                if (onBoundary == 0) continue;
                if (onBoundary == 1) s.Add(p, n, face);
                else if (withEdges) s.Add(p, n / n.Norm(), onBoundary == 2 ? 6 : 7);
            }
    return s;
}

/// Distance from point i of CubeSurface() to the nearest edge of the cube: from a face point to
/// its face's boundary, 0 for the edge and corner points (tag 6 and 7).
inline float DistanceToCubeEdge(const PointSet &cube, int i)
{
    if (cube.tag[i] >= 6) return 0.f;
    float d = 2;
    for (int a = 0; a < 3; ++a)
        if (cube.normals[i][a] == 0) d = std::min(d, 1.f - std::abs(cube.points[i][a]));
    return d;
}

/// Fills `m` (vcg meshes cannot be copied or returned) with one vertex per point.
inline void ToMesh(const PointSet &s, vcg::gaussphere::OrientedPointMesh &m)
{
    m.Clear();
    auto vi = vcg::tri::Allocator<vcg::gaussphere::OrientedPointMesh>::AddVertices(m, s.points.size());
    for (int i = 0; i < s.Size(); ++i, ++vi) {
        vi->P() = s.points[i];
        vi->N() = s.normals[i];
    }
}

/// A neighbour graph written by hand: adjacency lists, stride = longest list.
inline vcg::gaussphere::NeighborGraph MakeGraph(const std::vector<std::vector<int>> &adj, float spacing = 1.f)
{
    vcg::gaussphere::NeighborGraph g;
    g.stride = 1;
    for (const auto &a : adj) g.stride = std::max<int>(g.stride, int(a.size()));
    g.adjacency.assign(adj.size() * g.stride, -1);
    g.count.assign(adj.size(), 0);
    g.found.assign(adj.size(), 0);
    g.spacing.assign(adj.size(), spacing);
    for (size_t i = 0; i < adj.size(); ++i) {
        for (size_t t = 0; t < adj[i].size(); ++t) g.adjacency[i * g.stride + t] = adj[i][t];
        g.count[i] = g.found[i] = std::uint8_t(adj[i].size());
    }
    return g;
}

/// Sizes of the clusters of a labelling (label -> member count), ignoring -1.
inline std::map<int, int> ClusterSizes(const IndexArray &label)
{
    std::map<int, int> size;
    for (int l : label)
        if (l >= 0) ++size[l];
    return size;
}

inline double Dot(const P3 &a, const P3 &b) { return double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2]; }

/// Sets OpenMP's thread count for a scope and restores the caller's at its end.
class ScopedThreadCount
{
public:
    explicit ScopedThreadCount(int threads) : saved_(omp_get_max_threads()) { omp_set_num_threads(std::max(1, threads)); }
    ~ScopedThreadCount() { omp_set_num_threads(saved_); }
    ScopedThreadCount(const ScopedThreadCount &) = delete;
    ScopedThreadCount &operator=(const ScopedThreadCount &) = delete;

private:
    int saved_;
};

} // namespace gstest

#endif
