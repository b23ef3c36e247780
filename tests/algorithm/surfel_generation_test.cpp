// GenerateSurfels (paper, section 3.5): one elliptical surfel per cluster, with the
// centroid as position, the L2,1-optimal (Gaussian-weighted mean) normal, tangent
// orthogonal semi-axes, and an ellipse that holds every member's projection.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <vcg_ext/gaussphere/surfels/surfel_generation.h>

#include "test_support.h"

namespace {

using namespace vcg::gaussphere;
using gstest::P3;

SurfelGenerationParams GenerationParams(double h = 0.1, double margin = 0.75)
{
    SurfelGenerationParams p;
    p.weightWidth = h;
    p.coverageMargin = margin;
    return p;
}

std::vector<Surfel> Generate(const gstest::PointSet &s, const IndexArray &label, const SurfelGenerationParams &p,
                             float spacing = 0.05f)
{
    Clustering c;
    c.label = label;
    c.clusterCount = 0;
    for (int l : label) c.clusterCount = std::max(c.clusterCount, l + 1);
    return GenerateSurfels(s.points, s.normals, FlatVector<float>(s.Size(), spacing), c, p);
}

/// The frame invariants of every surfel, and containment of each member's projection:
/// x^2/a^2 + y^2/b^2 <= 1 with x, y the offsets from the centre along the unit axes and
/// a, b the semi-axis lengths (which include the coverage margin).
void ExpectValidSurfels(const std::vector<Surfel> &surfels, const gstest::PointSet &s, const IndexArray &label)
{
    for (size_t c = 0; c < surfels.size(); ++c) {
        const Surfel &f = surfels[c];
        SCOPED_TRACE(testing::Message() << "surfel " << c);
        const double a = f.majorAxis.Norm(), b = f.minorAxis.Norm();
        EXPECT_NEAR(f.normal.Norm(), 1.0, 1e-5);
        EXPECT_GT(b, 0);
        EXPECT_GE(a, b * (1 - 1e-6));
        EXPECT_LT(std::abs(gstest::Dot(f.majorAxis, f.normal)), 1e-5 * a) << "major axis not tangent";
        EXPECT_LT(std::abs(gstest::Dot(f.minorAxis, f.normal)), 1e-5 * b) << "minor axis not tangent";
        EXPECT_LT(std::abs(gstest::Dot(f.majorAxis, f.minorAxis)), 1e-5 * a * b) << "axes not orthogonal";
        ASSERT_TRUE(std::isfinite(a) && std::isfinite(b) && std::isfinite(f.position[0]));
    }
    IndexArray members(surfels.size(), 0);
    for (int i = 0; i < s.Size(); ++i) {
        if (label[i] < 0) continue;
        const Surfel &f = surfels[label[i]];
        ++members[label[i]];
        const double a = f.majorAxis.Norm(), b = f.minorAxis.Norm();
        const P3 d = s.points[i] - f.position;
        const double x = gstest::Dot(d, f.majorAxis) / a, y = gstest::Dot(d, f.minorAxis) / b;
        EXPECT_LE(x * x / (a * a) + y * y / (b * b), 1 + 1e-4) << "point " << i << " outside surfel " << label[i];
    }
    for (size_t c = 0; c < surfels.size(); ++c) EXPECT_EQ(surfels[c].memberCount, members[c]);
}

/// Points on the cylinder x^2 + y^2 = 1 with outward normals, theta in [0, arc], z in
/// [0, length], on an nt x nz grid.
gstest::PointSet CylinderPatch(double arc, double length, int nt, int nz)
{
    gstest::PointSet s;
    for (int i = 0; i < nt; ++i)
        for (int j = 0; j < nz; ++j) {
            const double t = arc * i / (nt - 1);
            const P3 n(float(std::cos(t)), float(std::sin(t)), 0);
            s.Add(P3(n[0], n[1], float(length * j / (nz - 1))), n);
        }
    return s;
}

// Many clusters on curved surfaces (cylinder and sphere, cut into blocks): every surfel
// has a valid frame and contains its members.
TEST(SurfelGeneration, CurvedClustersGiveValidFramesThatContainTheirMembers)
{
    const gstest::PointSet cyl = CylinderPatch(2.0, 2.0, 40, 40);
    IndexArray label;
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j) label.push_back((i / 8) * 4 + j / 10); // 5 x 4 blocks of 8 x 10
    const std::vector<Surfel> a = Generate(cyl, label, GenerationParams());
    ASSERT_EQ(a.size(), 20u);
    ExpectValidSurfels(a, cyl, label);

    const gstest::PointSet sph = gstest::FibonacciSphere(4000);
    IndexArray sphLabel;
    for (const P3 &n : sph.normals) // octants x 4 latitude bands
        sphLabel.push_back((n[0] < 0) + 2 * (n[1] < 0) + 4 * std::min(3, int((n[2] + 1) * 2)));
    const std::vector<Surfel> b = Generate(sph, sphLabel, GenerationParams(0.5));
    ASSERT_EQ(b.size(), 16u);
    ExpectValidSurfels(b, sph, sphLabel);
}

// Axis choice on a cylinder patch: the normal covariance points along theta, but the
// major axis is the direction of the larger spread: along z for a patch long in z,
// along theta for a patch wide in theta.
TEST(SurfelGeneration, MajorAxisFollowsTheLongerSpread)
{
    const gstest::PointSet longZ = CylinderPatch(0.3, 2.0, 7, 41);
    const std::vector<Surfel> a = Generate(longZ, IndexArray(longZ.Size(), 0), GenerationParams(10));
    ExpectValidSurfels(a, longZ, IndexArray(longZ.Size(), 0));
    EXPECT_GT(std::abs(a[0].majorAxis[2]) / a[0].majorAxis.Norm(), 0.999);

    const gstest::PointSet wideT = CylinderPatch(1.0, 0.2, 41, 5);
    const std::vector<Surfel> b = Generate(wideT, IndexArray(wideT.Size(), 0), GenerationParams(10));
    ExpectValidSurfels(b, wideT, IndexArray(wideT.Size(), 0));
    EXPECT_LT(std::abs(b[0].majorAxis[2]) / b[0].majorAxis.Norm(), 1e-3);
    // The mean normal of the symmetric arc points to theta = 0.5.
    EXPECT_NEAR(b[0].normal[0], std::cos(0.5), 1e-5);
    EXPECT_NEAR(b[0].normal[1], std::sin(0.5), 1e-5);
}

// A flat cluster: identical normals leave the normal covariance at zero, so the axes come
// from the positions (the documented fallback). On an 11 x 3 grid (unit spacing, normal
// +z) the spreads give aspect^2 = var(y) / var(x) = (9-1)/(121-1) = 1/15; the ellipse
// through the corners (5, 1) from the centroid has x^2 + (y/aspect)^2 = 25 + 15 = 40,
// so a = sqrt(40) + m, b = sqrt(40/15) + m with the margin m = 0.75 * spacing.
TEST(SurfelGeneration, FlatClusterUsesPositionAxesWithKnownLengths)
{
    gstest::PointSet s = gstest::PlaneGrid(11, 3);
    for (P3 &p : s.points) p += P3(3, -2, 7);
    const float spacing = 1.f;
    const IndexArray label(s.Size(), 0);
    const std::vector<Surfel> f = Generate(s, label, GenerationParams(100), spacing);
    ASSERT_EQ(f.size(), 1u);
    ExpectValidSurfels(f, s, label);
    EXPECT_NEAR(f[0].position[0], 8, 1e-5);
    EXPECT_NEAR(f[0].position[1], -1, 1e-5);
    EXPECT_NEAR(f[0].position[2], 7, 1e-5);
    EXPECT_EQ(f[0].normal, P3(0, 0, 1));
    EXPECT_NEAR(std::abs(f[0].majorAxis[0]), std::sqrt(40.0) + 0.75, 1e-4);
    EXPECT_NEAR(std::abs(f[0].minorAxis[1]), std::sqrt(40.0 / 15) + 0.75, 1e-4);
    EXPECT_EQ(f[0].memberCount, 33);
}

// A curved cluster (a spherical cap of the unit sphere, sagitta 0.134): its centroid lies
// about half the sagitta inside the sphere; the surfel sits on the sampled surface above it.
TEST(SurfelGeneration, CurvedClusterSurfelSitsOnTheSurface)
{
    const gstest::PointSet sphere = gstest::FibonacciSphere(20000);
    gstest::PointSet cap;
    for (int i = 0; i < sphere.Size(); ++i)
        if (sphere.points[i][2] > std::cos(30 * M_PI / 180)) cap.Add(sphere.points[i], sphere.normals[i]);
    ASSERT_GT(cap.Size(), 500);
    const IndexArray label(cap.Size(), 0);
    const std::vector<Surfel> f = Generate(cap, label, GenerationParams(10), 0.01f);
    ExpectValidSurfels(f, cap, label);
    P3 centroid(0, 0, 0);
    for (const P3 &p : cap.points) centroid += p;
    centroid /= float(cap.Size());
    const double sagitta = 1 - std::cos(30 * M_PI / 180);
    EXPECT_GT(1 - centroid.Norm(), 0.4 * sagitta); // the bias the position corrects
    // The weights average over ~0.3 of the radius: about 0.09 of the sagitta remains.
    EXPECT_LT(std::abs(f[0].position.Norm() - 1), 0.12 * sagitta);
    EXPECT_NEAR(f[0].position[0], 0, 1e-3);
    EXPECT_NEAR(f[0].position[1], 0, 1e-3);
}

// One point: an arbitrary tangent frame and a circle of radius margin x spacing.
TEST(SurfelGeneration, SinglePointGetsACircleOfMarginTimesSpacing)
{
    for (const P3 &n : {P3(0, 0, 1), P3(1, 0, 0), P3(0, -1, 0), P3(0.6f, 0, -0.8f)}) {
        gstest::PointSet s;
        s.Add(P3(1, 2, 3), n);
        const std::vector<Surfel> f = Generate(s, {0}, GenerationParams(0.1, 0.75), 0.2f);
        ASSERT_EQ(f.size(), 1u);
        ExpectValidSurfels(f, s, {0});
        EXPECT_EQ(f[0].position, P3(1, 2, 3));
        EXPECT_NEAR(f[0].majorAxis.Norm(), 0.15, 1e-6);
        EXPECT_NEAR(f[0].minorAxis.Norm(), 0.15, 1e-6);
        EXPECT_NEAR(gstest::Dot(f[0].normal, n), 1.0, 1e-6);
    }
}

// Two points 2 apart: major semi-axis 1 + m along the pair, minor at the aspect floor
// (0.1 of the major before the margin) + m.
TEST(SurfelGeneration, TwoPointsGiveANeedleClampedByMinAspect)
{
    gstest::PointSet s;
    s.Add(P3(0, 0, 0), P3(0, 0, 1));
    s.Add(P3(0, 2, 0), P3(0, 0, 1));
    const std::vector<Surfel> f = Generate(s, {0, 0}, GenerationParams(1, 0.5), 0.4f);
    ExpectValidSurfels(f, s, {0, 0});
    EXPECT_NEAR(std::abs(f[0].majorAxis[1]), 1 + 0.2, 1e-5);
    EXPECT_NEAR(f[0].minorAxis.Norm(), 0.1 + 0.2, 1e-5);
}

// The normal minimizes the weighted L2,1 error: n' = sum w_i n_i / |...| with
// w_i = exp(-r_i^2 / h^2). Points at x = 0, 0, 3 have their centroid at x = 1, so with
// h = 1 the weights are e^-1, e^-1, e^-4.
TEST(SurfelGeneration, NormalIsTheGaussianWeightedMean)
{
    gstest::PointSet s;
    P3 n1(0, 0, 1), n2(0.6f, 0, 0.8f), n3(0, 0.8f, 0.6f);
    s.Add(P3(0, 0, 0), n1);
    s.Add(P3(0, 0, 0), n2);
    s.Add(P3(3, 0, 0), n3);
    const double w1 = std::exp(-1.0), w3 = std::exp(-4.0);
    double e[3];
    for (int k = 0; k < 3; ++k) e[k] = w1 * n1[k] + w1 * n2[k] + w3 * n3[k];
    const double len = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    const std::vector<Surfel> f = Generate(s, {0, 0, 0}, GenerationParams(1.0));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[0].normal[k], e[k] / len, 1e-6) << k;
    // A width much smaller than the cluster: every weight underflows, the plain mean is used.
    const std::vector<Surfel> g = Generate(s, {0, 0, 0}, GenerationParams(1e-3));
    P3 plain = n1 + n2 + n3;
    plain.Normalize();
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(g[0].normal[k], plain[k], 1e-6) << k;
    ExpectValidSurfels(g, s, {0, 0, 0});
}

// Clusters of coincident points (duplicates) still get a valid frame from the margin.
TEST(SurfelGeneration, CoincidentPointsGetAValidFrame)
{
    gstest::PointSet s;
    for (int i = 0; i < 5; ++i) s.Add(P3(1, 1, 1), P3(0, 0, 1));
    const std::vector<Surfel> f = Generate(s, IndexArray(5, 0), GenerationParams(), 0.1f);
    ExpectValidSurfels(f, s, IndexArray(5, 0));
    EXPECT_NEAR(f[0].majorAxis.Norm(), 0.075, 1e-6);
}

// Labels -1 are ignored; each cluster's surfel sits at its own centroid.
TEST(SurfelGeneration, ExcludedPointsAreIgnored)
{
    gstest::PointSet s = gstest::PlaneGrid(4, 4);
    IndexArray label(16, -1);
    for (int i = 0; i < 4; ++i) label[i] = 0;      // row y = 0
    for (int i = 12; i < 16; ++i) label[i] = 1;    // row y = 3
    const std::vector<Surfel> f = Generate(s, label, GenerationParams());
    ASSERT_EQ(f.size(), 2u);
    ExpectValidSurfels(f, s, label);
    EXPECT_NEAR(f[0].position[1], 0, 1e-6);
    EXPECT_NEAR(f[1].position[1], 3, 1e-6);
    EXPECT_NEAR(f[1].position[0], 1.5, 1e-6);
}

} // namespace
