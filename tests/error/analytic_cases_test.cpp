// Surfel error on point sets whose answer is known: planes, shifted planes and spheres.

#include "point_sets.h"

#include <vcg_ext/surfel_error/surfel_error.h>

#include <gtest/gtest.h>
#include <omp.h>

#include <random>

using namespace surfel_error_test;
using vcg::gaussphere::metric::ComputeSurfelError;
using vcg::gaussphere::metric::SurfelErrorParams;
using vcg::gaussphere::metric::SurfelErrorStats;

TEST(SurfelErrorAnalytic, IdenticalPlaneIsExact)
{
    PointSet plane;
    AddPlaneGrid(plane, 40, 30, 0.01f);
    const SurfelErrorStats stats = ComputeSurfelError(plane, plane);
    EXPECT_EQ(stats.originalPointCount, 1200u);
    EXPECT_EQ(stats.distance.count, 1200u);
    EXPECT_LT(stats.distance.max, 1e-9);
    EXPECT_LT(stats.normalToOwnSurfel.max, 1e-9);
    EXPECT_LT(stats.normalToBlended.max, 1e-9);
    EXPECT_EQ(stats.unconvergedCount, 0u);
}

TEST(SurfelErrorAnalytic, IrregularPlaneAgainstItselfIsExact)
{
    PointSet plane;
    std::mt19937 random(7);
    std::uniform_real_distribution<float> coordinate(-1, 1);
    for (int i = 0; i < 2000; ++i)
        AddPoint(plane, vcg::Point3f(coordinate(random), coordinate(random), 0.25f), vcg::Point3f(0, 0, 1));
    const SurfelErrorStats stats = ComputeSurfelError(plane, plane);
    EXPECT_LT(stats.distance.max, 1e-9);
    EXPECT_LT(stats.normalToBlended.max, 1e-9);
}

TEST(SurfelErrorAnalytic, ShiftedPlaneGivesTheShift)
{
    const float step = 0.1f, shift = 0.01f;
    PointSet original, shifted;
    AddPlaneGrid(original, 30, 30, step);
    // Offset by half a step in the plane too, so no surfel sits right above a point.
    AddPlaneGrid(shifted, 31, 31, step, shift, -step / 2, -step / 2);
    std::vector<float> perPoint;
    const SurfelErrorStats stats =
        ComputeSurfelError(original, shifted, SurfelErrorParams(), {}, &perPoint, nullptr);
    ASSERT_EQ(perPoint.size(), original.vert.size());
    for (float d : perPoint)
        EXPECT_NEAR(d, shift, 1e-7);
    EXPECT_NEAR(stats.distance.rms, shift, 1e-7);
    EXPECT_NEAR(stats.distance.max, shift, 1e-7);
    EXPECT_NEAR(stats.distance.p999, shift, 1e-7);
    const double diagonal = std::sqrt(2.0) * 29 * step;
    EXPECT_NEAR(stats.diagonal, diagonal, 1e-6);
    EXPECT_NEAR(stats.normalizedDistance.rms, shift / diagonal, 1e-7);
    EXPECT_NEAR(stats.normalizedDistance.max, shift / diagonal, 1e-7);
}

// S' = S on a curved surface: a(x) is a weighted average of samples within about one spacing
// s, so it lies inside the sphere by a sagitta-like c·s²/r (c ≈ 0.45 with the default width:
// weight 1 on the point itself and about 0.64 on each of its six neighbors at distance s).
TEST(SurfelErrorAnalytic, IdenticalSphereFloorHasSagittaOrder)
{
    const int n = 5000;
    const double r = 1.0;
    PointSet sphere;
    AddFibonacciSphere(sphere, n, float(r));
    const SurfelErrorStats stats = ComputeSurfelError(sphere, sphere);
    const double spacing = FibonacciSpacing(n, r);
    EXPECT_GT(stats.distance.rms, 0.2 * spacing * spacing / r);
    EXPECT_LT(stats.distance.rms, 1.0 * spacing * spacing / r);
    EXPECT_LT(stats.distance.max, 2.0 * spacing * spacing / r);
    EXPECT_LT(stats.normalToOwnSurfel.max, 1e-6) << "every point is its own nearest surfel";
}

// A dense sphere against coarse ones: the error of a tangent-plane blend over one spacing s is
// of the order of the sagitta r(1 − cos(θ/2)) ≈ s²/(8r), θ = s/r, and halves the spacing → a
// quarter of the error.
TEST(SurfelErrorAnalytic, CoarseSphereErrorHasSagittaOrderAndQuadraticConvergence)
{
    const double r = 1.0;
    PointSet dense;
    AddFibonacciSphere(dense, 20000, float(r));
    const auto rmsAgainst = [&](int coarseCount) {
        const double theta = FibonacciSpacing(coarseCount, r) / r;
        const double sagitta = r * (1 - std::cos(theta / 2));
        PointSet coarse;
        AddFibonacciSphere(coarse, coarseCount, float(r));
        const SurfelErrorStats stats = ComputeSurfelError(dense, coarse);
        EXPECT_GT(stats.distance.rms, 0.5 * sagitta) << coarseCount << " surfels";
        EXPECT_LT(stats.distance.rms, 10 * sagitta) << coarseCount << " surfels";
        EXPECT_LT(stats.distance.max, 3 * stats.distance.rms) << "the sphere is uniform, so is the error";
        return stats.distance.rms;
    };
    const double coarseRms = rmsAgainst(500), finerRms = rmsAgainst(2000);
    EXPECT_GT(coarseRms / finerRms, 3.0);
    EXPECT_LT(coarseRms / finerRms, 5.0);
}

// On a coarse sphere the nearest surfel's normal is off by up to half the angular spacing;
// the blended normal at q0 interpolates, up to the offset of the weighted centroid of the
// surrounding surfels (a fraction of a spacing), so it must do clearly better.
TEST(SurfelErrorAnalytic, BlendedNormalBeatsNearestSurfelNormalOnSphere)
{
    const int coarseCount = 500;
    PointSet dense, coarse;
    AddFibonacciSphere(dense, 20000, 1.0f);
    AddFibonacciSphere(coarse, coarseCount, 1.0f);
    const SurfelErrorStats stats = ComputeSurfelError(dense, coarse);
    const double angularSpacing = FibonacciSpacing(coarseCount, 1.0);
    EXPECT_GT(stats.normalToOwnSurfel.rms, 0.2 * angularSpacing);
    EXPECT_LT(stats.normalToOwnSurfel.max, angularSpacing);
    EXPECT_LT(stats.normalToBlended.rms, 0.5 * stats.normalToOwnSurfel.rms);
    EXPECT_EQ(stats.ownSurfelFromNearestCount, 20000u);
}

TEST(SurfelErrorAnalytic, ResultsDoNotDependOnThreadCount)
{
    PointSet original, simplified;
    AddFibonacciSphere(original, 30000, 2.0f);
    AddFibonacciSphere(simplified, 3000, 2.0f);
    std::mt19937 random(3);
    std::normal_distribution<float> noise(0, 0.01f);
    for (auto& v : original.vert)
        v.P() += vcg::Point3f(noise(random), noise(random), noise(random));

    const int defaultThreads = omp_get_max_threads();
    std::vector<float> oneThread, twoThreads;
    omp_set_num_threads(1);
    const SurfelErrorStats a = ComputeSurfelError(original, simplified, SurfelErrorParams(), {}, &oneThread);
    omp_set_num_threads(2);
    const SurfelErrorStats b = ComputeSurfelError(original, simplified, SurfelErrorParams(), {}, &twoThreads);
    omp_set_num_threads(defaultThreads);

    EXPECT_EQ(oneThread, twoThreads);
    EXPECT_EQ(a.distance.rms, b.distance.rms);
    EXPECT_EQ(a.distance.p999, b.distance.p999);
    EXPECT_EQ(a.normalToOwnSurfel.rms, b.normalToOwnSurfel.rms);
    EXPECT_EQ(a.normalToBlended.rms, b.normalToBlended.rms);
}

// A thin part: S samples the lower sheet (z = 0, normal +z); S' has the lower sheet's surfels
// half a step aside and the upper sheet's (z = t, normal −z) right above every point, so the
// nearest surfel centers belong to the wrong sheet. The point's own orientation picks the sheet.
TEST(SurfelErrorAnalytic, ThinPartIsProjectedOntoTheSheetFacingThePoint)
{
    const float step = 0.1f, thickness = 0.02f;
    PointSet original, sheets;
    AddPlaneGrid(original, 20, 20, step);
    AddPlaneGrid(sheets, 21, 21, step, 0, -step / 2, -step / 2);
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 20; ++j)
            AddPoint(sheets, vcg::Point3f(i * step, j * step, thickness), vcg::Point3f(0, 0, -1));

    const SurfelErrorStats stats = ComputeSurfelError(original, sheets);
    EXPECT_LT(stats.distance.max, 1e-6);
    EXPECT_LT(stats.normalToBlended.max, 1e-6);
    EXPECT_NEAR(stats.normalToOwnSurfel.max, 2.0, 1e-6) << "the nearest surfel is the opposite one";

    // Without a normal there is no side to choose: the heaviest (nearest) surfel's sheet wins.
    for (auto& v : original.vert)
        v.N() = vcg::Point3f(0, 0, 0);
    EXPECT_NEAR(ComputeSurfelError(original, sheets).distance.rms, thickness, 1e-6);
}
