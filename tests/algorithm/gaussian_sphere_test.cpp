// GaussianSphere: lookup of the Gaussian triangle containing a normal, the triangle ids,
// the triangle geometry, and the edge lengths against the paper's d_max.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <vcg_ext/gaussphere/clustering/gaussian_sphere.h>

#include "test_support.h"

namespace {

using vcg::gaussphere::GaussianSphere;
using gstest::P3;
using gstest::PointArray;

double Det(const P3 &a, const P3 &b, const P3 &c) { return gstest::Dot(a, b ^ c); }

/// Coefficients (alpha, beta, gamma) with n = alpha a + beta b + gamma c, in double.
/// n lies in the spherical triangle abc (the cone spanned by a, b, c) iff all are >= 0.
void ConeCoordinates(const P3 &a, const P3 &b, const P3 &c, const P3 &n, double w[3])
{
    // Cramer's rule; cross products in double to keep the error near float rounding.
    auto cross = [](const P3 &x, const P3 &y, double r[3]) {
        r[0] = double(x[1]) * y[2] - double(x[2]) * y[1];
        r[1] = double(x[2]) * y[0] - double(x[0]) * y[2];
        r[2] = double(x[0]) * y[1] - double(x[1]) * y[0];
    };
    auto dot = [](const P3 &x, const double r[3]) { return x[0] * r[0] + x[1] * r[1] + x[2] * r[2]; };
    double bc[3], ca[3], ab[3];
    cross(b, c, bc);
    cross(c, a, ca);
    cross(a, b, ab);
    const double det = dot(a, bc);
    w[0] = dot(n, bc) / det;
    w[1] = dot(n, ca) / det;
    w[2] = dot(n, ab) / det;
}

/// True when the unit direction n lies inside triangle `id` up to `tol` (in cone
/// coordinates of unit vertices, i.e. roughly a distance on the sphere).
bool Contains(const GaussianSphere &s, int id, const P3 &n, double tol)
{
    P3 a, b, c;
    s.TriangleVertices(id, a, b, c);
    double w[3];
    ConeCoordinates(a, b, c, n, w);
    return w[0] >= -tol && w[1] >= -tol && w[2] >= -tol;
}

bool HasCorner(const GaussianSphere &s, int id, const P3 &v, float tol)
{
    P3 a, b, c;
    s.TriangleVertices(id, a, b, c);
    return (a - v).Norm() < tol || (b - v).Norm() < tol || (c - v).Norm() < tol;
}

class GaussianSphereLevels : public ::testing::TestWithParam<int>
{
protected:
    int Level() const { return GetParam(); }
    int ExpectedTriangleCount() const
    {
        // (n-1)^2 triangles per face of the icosahedron.
        const int m = Level() - 1;
        return 20 * m * m;
    }
};

TEST_P(GaussianSphereLevels, TriangleCountIsBaseFacesTimesSquaredSegments)
{
    const GaussianSphere s(Level());
    EXPECT_EQ(s.Level(), Level());
    EXPECT_EQ(s.TriangleIdCount(), ExpectedTriangleCount());
}

// Every id is a real, correctly oriented spherical triangle and together they tile the
// sphere exactly once: positive orientation and spherical areas summing to 4 pi.
TEST_P(GaussianSphereLevels, TrianglesAreOrientedAndTileTheSphere)
{
    const GaussianSphere s(Level());
    double area = 0;
    for (int id = 0; id < s.TriangleIdCount(); ++id) {
        P3 a, b, c;
        s.TriangleVertices(id, a, b, c);
        EXPECT_NEAR(a.Norm(), 1.f, 1e-6f);
        ASSERT_GT(Det(a, b, c), 0) << "triangle " << id << " is not counter-clockwise seen from outside";
        // Van Oosterom-Strackee: tan(E/2) = det / (1 + a.b + b.c + c.a).
        const double e = 2 * std::atan2(Det(a, b, c),
                                         1 + gstest::Dot(a, b) + gstest::Dot(b, c) + gstest::Dot(c, a));
        area += e;
    }
    EXPECT_NEAR(area, 4 * gstest::kPi, 1e-4);
}

// Dense sampling: every returned id is in range, the direction lies inside the returned
// triangle, and every id is returned for some direction (so none is a phantom).
TEST_P(GaussianSphereLevels, LookupReturnsContainingTriangleAndHitsEveryId)
{
    const GaussianSphere s(Level());
    const int count = s.TriangleIdCount();
    std::vector<char> hit(count, 0);
    // 250k directions: about 24 per triangle at n = 24 (icosahedron), enough to land in
    // the smallest ones (their inscribed discs hold several samples).
    const PointArray dirs = gstest::FibonacciDirections(250000);
    int outside = 0;
    for (const P3 &d : dirs) {
        const int id = s.TriangleOf(d);
        ASSERT_GE(id, 0);
        ASSERT_LT(id, count);
        hit[id] = 1;
        if (!Contains(s, id, d, 2e-6)) {
            if (++outside <= 5) ADD_FAILURE() << "direction (" << d[0] << ", " << d[1] << ", " << d[2]
                                              << ") is not inside its triangle " << id;
        }
    }
    EXPECT_EQ(outside, 0);
    int missed = 0;
    for (int id = 0; id < count; ++id) missed += !hit[id];
    EXPECT_EQ(missed, 0) << "ids never returned by TriangleOf";
}

// The lookup only depends on the direction: scaling by a power of two changes nothing.
TEST_P(GaussianSphereLevels, LookupIgnoresLength)
{
    const GaussianSphere s(Level());
    for (const P3 &d : gstest::FibonacciDirections(2000)) {
        EXPECT_EQ(s.TriangleOf(d), s.TriangleOf(d * 4.f));
        EXPECT_EQ(s.TriangleOf(d), s.TriangleOf(d * 0.125f));
    }
}

// Gaussian vertices are shared by up to six triangles: the lookup of a vertex must be
// deterministic, in range, and return one of the triangles having it as a corner.
TEST_P(GaussianSphereLevels, GridVerticesMapToAnAdjacentTriangle)
{
    const GaussianSphere s(Level());
    for (int id = 0; id < s.TriangleIdCount(); ++id) {
        P3 v[3];
        s.TriangleVertices(id, v[0], v[1], v[2]);
        for (const P3 &p : v) {
            const int got = s.TriangleOf(p);
            ASSERT_GE(got, 0);
            ASSERT_LT(got, s.TriangleIdCount());
            ASSERT_EQ(got, s.TriangleOf(p));
            ASSERT_TRUE(HasCorner(s, got, p, 1e-5f))
                << "vertex (" << p[0] << ", " << p[1] << ", " << p[2] << ") of triangle " << id
                << " maps to triangle " << got << " which does not touch it";
        }
    }
}

// Points on Gaussian edges (midpoints of the chords, projected) belong to one of the two
// triangles sharing the edge: the returned triangle must contain them.
TEST_P(GaussianSphereLevels, EdgeMidpointsMapToAnAdjacentTriangle)
{
    const GaussianSphere s(Level());
    for (int id = 0; id < s.TriangleIdCount(); ++id) {
        P3 v[3];
        s.TriangleVertices(id, v[0], v[1], v[2]);
        for (int e = 0; e < 3; ++e) {
            P3 mid = v[e] + v[(e + 1) % 3];
            mid.Normalize();
            const int got = s.TriangleOf(mid);
            ASSERT_GE(got, 0);
            ASSERT_LT(got, s.TriangleIdCount());
            ASSERT_TRUE(Contains(s, got, mid, 1e-5))
                << "edge midpoint of triangle " << id << " maps to triangle " << got << " not touching it";
        }
    }
}

// The directions named in the issue: axis directions (with signed zeros), base-edge
// midpoints and base-face centres; each lands in a triangle touching it.
TEST_P(GaussianSphereLevels, SpecialDirectionsMapToAdjacentTriangles)
{
    const GaussianSphere s(Level());
    const float r2 = float(1 / std::sqrt(2.0)), r3 = float(1 / std::sqrt(3.0));
    const PointArray special = {
        {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},
        {1, -0.f, -0.f}, {-0.f, -0.f, -1}, {-0.f, 1, -0.f},
        {r2, r2, 0}, {-r2, r2, 0}, {r2, 0, -r2}, {0, -r2, -r2},
        {r3, r3, r3}, {-r3, -r3, -r3}, {r3, -r3, r3}};
    for (const P3 &d : special) {
        const int got = s.TriangleOf(d);
        ASSERT_GE(got, 0);
        ASSERT_LT(got, s.TriangleIdCount());
        EXPECT_EQ(got, s.TriangleOf(d));
        EXPECT_TRUE(Contains(s, got, d, 1e-5)) << "(" << d[0] << ", " << d[1] << ", " << d[2] << ") -> " << got;
    }
}

// The batched lookup's AVX2 kernel returns TriangleOf's ids: on dense directions, on every grid
// vertex, chord midpoint and triangle centre (where rounding decides between neighbours), on
// their scaled and opposite copies and on the special directions; with a count that leaves a
// partial group of eight. (A CPU without AVX2 takes TriangleOf itself.)
TEST_P(GaussianSphereLevels, BatchedLookupEqualsTriangleOf)
{
    if (!GaussianSphere::Avx2Kernels())
        GTEST_SKIP() << "no kernel to compare: the batched lookup is TriangleOf here";
    const GaussianSphere s(Level());
    PointArray dirs = gstest::FibonacciDirections(20000);
    for (int id = 0; id < s.TriangleIdCount(); ++id) {
        P3 v[3];
        s.TriangleVertices(id, v[0], v[1], v[2]);
        for (int e = 0; e < 3; ++e) {
            dirs.push_back(v[e]);
            dirs.push_back(v[e] * 3.f);
            dirs.push_back(-v[e]);
            dirs.push_back((v[e] + v[(e + 1) % 3]).Normalize());
        }
        dirs.push_back((v[0] + v[1] + v[2]).Normalize());
    }
    const float r2 = float(1 / std::sqrt(2.0)), r3 = float(1 / std::sqrt(3.0));
    for (const P3 &d : PointArray{{1, 0, 0}, {-0.f, -0.f, -1}, {r2, -r2, 0}, {-r3, r3, r3}}) dirs.push_back(d);
    if (dirs.size() % 8 == 0) dirs.push_back(P3(0.3f, -0.4f, 0.5f).Normalize());
    std::vector<int> batched(dirs.size(), -1);
    s.TrianglesOf(dirs.data(), int(dirs.size()), batched.data());
    int differ = 0;
    for (size_t i = 0; i < dirs.size(); ++i)
        if (batched[i] != s.TriangleOf(dirs[i]) && ++differ <= 5)
            ADD_FAILURE() << "direction " << i << " (" << dirs[i][0] << ", " << dirs[i][1] << ", " << dirs[i][2]
                          << ") -> " << batched[i] << ", TriangleOf " << s.TriangleOf(dirs[i]);
    EXPECT_EQ(differ, 0);
}

INSTANTIATE_TEST_SUITE_P(Levels, GaussianSphereLevels, ::testing::Values(2, 3, 8, 16, 24),
                         [](const ::testing::TestParamInfo<int> &info) { return "n" + std::to_string(info.param); });

// Known answers from CALIBRATION.md: the longest chord of the actual triangulation and
// the paper's formula sqrt(7 pi^2 / (8 (n-1)^2)).
TEST(GaussianSphereEdges, MaxEdgeLengthMatchesCalibration)
{
    struct Case { int level; double longest; };
    const Case cases[] = {{8, 0.188}, {16, 0.088}, {24, 0.058}};
    for (const Case &c : cases) {
        const GaussianSphere s(c.level);
        EXPECT_NEAR(s.MaxEdgeLength(), c.longest, 6e-4) << "n=" << c.level;
        // The formula over-estimates the true longest edge (2.2x).
        EXPECT_GT(s.PaperMaxEdgeLength(), s.MaxEdgeLength());
    }
}

TEST(GaussianSphereEdges, PaperFormulaKnownValues)
{
    EXPECT_NEAR(GaussianSphere::PaperMaxEdgeLength(8), 0.420, 6e-4);
    EXPECT_NEAR(GaussianSphere::PaperMaxEdgeLength(16), 0.196, 6e-4);
    EXPECT_NEAR(GaussianSphere::PaperMaxEdgeLength(24), 0.128, 6e-4);
    // Exact: 7 pi^2 / (8 * 49) at n = 8.
    EXPECT_NEAR(GaussianSphere::PaperMaxEdgeLength(8), std::sqrt(7 * gstest::kPi * gstest::kPi / 392.0), 1e-12);
    // The member uses the sphere's own level.
    EXPECT_DOUBLE_EQ(GaussianSphere(16).PaperMaxEdgeLength(),
                     GaussianSphere::PaperMaxEdgeLength(16));
}

TEST(GaussianSphereEdges, RefinementShrinksEdges)
{
    double previous = 3;
    for (int n : {2, 4, 8, 16, 24, 32}) {
        const double e = GaussianSphere(n).MaxEdgeLength();
        EXPECT_LT(e, previous) << "n=" << n;
        previous = e;
    }
    // n = 2 keeps the icosahedron: edge 1.0515.
    EXPECT_NEAR(GaussianSphere(2).MaxEdgeLength(), 1.0514622, 1e-5);
}

} // namespace
