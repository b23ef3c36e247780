// The mesh distance of the downstream benchmark on cases whose answer is known: closest points
// on one triangle, the grid search against brute force, parallel squares and nested cubes.
#include "mesh_distance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace gsbench;
using vcg::Point3d;

namespace {

Triangle MakeTriangle(const Point3d &a, const Point3d &b, const Point3d &c)
{
    Triangle t;
    t.v[0] = a;
    t.v[1] = b;
    t.v[2] = c;
    return t;
}

/// The square [x0, x1] x [y0, y1] at height z, as two triangles.
void AddSquare(std::vector<Triangle> &mesh, double x0, double x1, double y0, double y1, double z)
{
    mesh.push_back(MakeTriangle(Point3d(x0, y0, z), Point3d(x1, y0, z), Point3d(x1, y1, z)));
    mesh.push_back(MakeTriangle(Point3d(x0, y0, z), Point3d(x1, y1, z), Point3d(x0, y1, z)));
}

/// The surface of the cube [lo, hi]^3 as twelve triangles.
std::vector<Triangle> Cube(double lo, double hi)
{
    std::vector<Triangle> mesh;
    const int axes[3][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}}; // (u, v, normal axis) of each face pair
    for (const auto &axis : axes)
        for (double w : {lo, hi}) {
            std::vector<Triangle> square;
            AddSquare(square, lo, hi, lo, hi, w);
            for (Triangle &t : square) {
                for (Point3d &p : t.v) {
                    Point3d q;
                    q[axis[0]] = p[0];
                    q[axis[1]] = p[1];
                    q[axis[2]] = p[2];
                    p = q;
                }
                mesh.push_back(t);
            }
        }
    return mesh;
}

double BruteForceDistance(const std::vector<Triangle> &mesh, const Point3d &p)
{
    double best = std::numeric_limits<double>::max();
    for (const Triangle &t : mesh) best = std::min(best, (ClosestPointOnTriangle(t, p) - p).Norm());
    return best;
}

} // namespace

TEST(MeshDistance, ClosestPointInEveryRegionOfATriangle)
{
    const Triangle t = MakeTriangle(Point3d(0, 0, 0), Point3d(2, 0, 0), Point3d(0, 2, 0));
    // Above the interior: the foot of the perpendicular.
    EXPECT_EQ(ClosestPointOnTriangle(t, Point3d(0.5, 0.5, 3)), Point3d(0.5, 0.5, 0));
    // Beside an edge: the nearest point of that edge.
    EXPECT_EQ(ClosestPointOnTriangle(t, Point3d(1, -1, 1)), Point3d(1, 0, 0));
    EXPECT_EQ(ClosestPointOnTriangle(t, Point3d(2, 2, 0)), Point3d(1, 1, 0));
    // Beyond a vertex: the vertex.
    EXPECT_EQ(ClosestPointOnTriangle(t, Point3d(3, -1, -2)), Point3d(2, 0, 0));
    EXPECT_EQ(ClosestPointOnTriangle(t, Point3d(-1, -1, 0)), Point3d(0, 0, 0));
}

TEST(MeshDistance, DegenerateTrianglesActAsSegmentsAndPoints)
{
    const Triangle segment = MakeTriangle(Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(2, 0, 0));
    EXPECT_EQ(ClosestPointOnTriangle(segment, Point3d(1.5, 1, 0)), Point3d(1.5, 0, 0));
    EXPECT_EQ(ClosestPointOnTriangle(segment, Point3d(3, 0, 4)), Point3d(2, 0, 0));
    const Triangle point = MakeTriangle(Point3d(1, 1, 1), Point3d(1, 1, 1), Point3d(1, 1, 1));
    EXPECT_EQ(ClosestPointOnTriangle(point, Point3d(1, 1, 3)), Point3d(1, 1, 1));
}

TEST(MeshDistance, GridSearchMatchesBruteForce)
{
    // Small triangles scattered in a box, queried inside, near and far outside the box.
    std::mt19937_64 random(3);
    std::uniform_real_distribution<double> inBox(0, 1), offset(-0.02, 0.02), query(-2, 3);
    std::vector<Triangle> mesh;
    for (int i = 0; i < 3000; ++i) {
        const Point3d a(inBox(random), inBox(random), inBox(random));
        mesh.push_back(MakeTriangle(a, a + Point3d(offset(random), offset(random), offset(random)),
                                    a + Point3d(offset(random), offset(random), offset(random))));
    }
    const TriangleIndex index(mesh);
    for (int i = 0; i < 2000; ++i) {
        const Point3d p(query(random), query(random), query(random));
        EXPECT_NEAR(index.Distance(p), BruteForceDistance(mesh, p), 1e-12) << "at " << p[0] << " " << p[1] << " " << p[2];
    }
}

TEST(MeshDistance, SummaryTakesTheNearestRankPercentile)
{
    std::vector<double> distances;
    for (int i = 200; i >= 1; --i) distances.push_back(i);
    const DistanceSummary s = Summarize(distances);
    EXPECT_DOUBLE_EQ(s.max, 200);
    EXPECT_DOUBLE_EQ(s.p99, 198); // rank ceil(0.99 * 200) = 198
    EXPECT_NEAR(s.rms, std::sqrt(200.0 * 201 * 401 / 6 / 200), 1e-12);
}

TEST(MeshDistance, ParallelSquaresAreTheirOffsetApartEverywhere)
{
    std::vector<Triangle> original, shifted;
    AddSquare(original, 0, 1, 0, 1, 0);
    AddSquare(shifted, 0, 1, 0, 1, 0.05);
    const MeshDistance d = MeasureMeshDistance(shifted, original, 100000, 1);
    const double expected = 0.05 / std::sqrt(2.0); // over the original's diagonal
    EXPECT_DOUBLE_EQ(d.diagonal, std::sqrt(2.0));
    for (const DistanceSummary &s : {d.toOriginal, d.toReconstruction, d.symmetric}) {
        EXPECT_NEAR(s.rms, expected, 1e-12);
        EXPECT_NEAR(s.p99, expected, 1e-12);
        EXPECT_NEAR(s.max, expected, 1e-12);
    }
}

TEST(MeshDistance, NestedCubes)
{
    // The unit cube against the cube grown by g on every side. Every point of the unit cube is
    // exactly g from the grown one. A point of the grown cube's face is sqrt(g^2 + e1^2 + e2^2)
    // from the unit cube, e1 and e2 its distances outside [0, 1] along the face: at most g sqrt(3)
    // at a corner, and its mean square over a face of side L = 1 + 2g is g^2 + 4 g^3 / (3 L).
    const double g = 0.1, side = 1 + 2 * g, diagonal = std::sqrt(3.0);
    const std::vector<Triangle> unit = Cube(0, 1), grown = Cube(-g, 1 + g);
    const MeshDistance d = MeasureMeshDistance(grown, unit, 1000000, 7);
    EXPECT_DOUBLE_EQ(d.diagonal, diagonal);

    EXPECT_NEAR(d.toReconstruction.rms, g / diagonal, 1e-12);
    EXPECT_NEAR(d.toReconstruction.p99, g / diagonal, 1e-12);
    EXPECT_NEAR(d.toReconstruction.max, g / diagonal, 1e-12);

    const double meanSquare = g * g + 4 * g * g * g / (3 * side);
    EXPECT_NEAR(d.toOriginal.rms, std::sqrt(meanSquare) / diagonal, 1e-3 * d.toOriginal.rms);
    EXPECT_LE(d.toOriginal.max, g * std::sqrt(3.0) / diagonal + 1e-12);
    EXPECT_GE(d.toOriginal.max, 0.99 * g * std::sqrt(3.0) / diagonal);
    EXPECT_GT(d.toOriginal.p99, g / diagonal);
    EXPECT_LT(d.toOriginal.p99, d.toOriginal.max);

    // Pooled, equal sample counts: each way weighs half.
    EXPECT_NEAR(d.symmetric.rms, std::sqrt((g * g + meanSquare) / 2) / diagonal, 1e-3 * d.symmetric.rms);
    EXPECT_DOUBLE_EQ(d.symmetric.max, d.toOriginal.max);
}
