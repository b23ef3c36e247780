// ResamplingParams::maxErrorFraction: clusters are split until every point lies within the
// bound of its own surfel's plane and of the blended surface of all surfels, the surface the
// error metric (vcg_ext/surfel_error) projects on. These tests measure the result with that
// metric, independently of the resampler's own figures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include <vcg_ext/gaussphere/surfels/surfel_mesh.h>
#include <vcg_ext/surfel_error/surfel_error.h>

#include "pipeline_support.h"

namespace {

using namespace vcg::gaussphere;
using gstest::P3;

/// Largest distance of a point to its own surfel's plane, over the bounding-box diagonal.
double MaxOwnPlaneDistance(const gstest::PointSet &s, const ResamplingResult &r)
{
    double worst = 0;
    for (int i = 0; i < s.Size(); ++i) {
        const Surfel &f = r.surfels[r.representative[i]];
        worst = std::max(worst, std::abs(gstest::Dot(s.points[i] - f.position, f.normal)));
    }
    return worst / r.stats.diagonal;
}

gstest::PointSet BumpySphere(int n, unsigned seed)
{
    // A sphere with a low-frequency bump: smooth, so a bound a few times the metric's floor
    // can be met everywhere.
    gstest::PointSet s = gstest::FibonacciSphere(n);
    std::mt19937 rng(seed);
    std::normal_distribution<float> jitter(0.f, 0.02f);
    for (P3 &normal : s.normals) {
        normal = normal + P3(jitter(rng), jitter(rng), jitter(rng));
        normal /= normal.Norm();
    }
    return s;
}

ResamplingParams Bounded(double fraction)
{
    ResamplingParams p;
    p.maxErrorFraction = fraction;
    return p;
}

// Where the bound can be met, the metric confirms it: every point within it, and the
// resampler's largest distance is the metric's Δ*max (the same operator on the same surfels).
TEST(ErrorBound, MetBoundIsConfirmedByTheMetric)
{
    const gstest::PointSet s = gstest::FibonacciSphere(6000);
    const ResamplingResult plain = gstest::Resample(s);
    const double unbounded = gstest::Measure(s, plain).stats.normalizedDistance.max;
    const double bound = 0.6 * unbounded;
    const ResamplingResult r = gstest::Resample(s, Bounded(bound));
    gstest::ExpectValidResult(r, s);
    const gstest::Measured m = gstest::Measure(s, r);
    EXPECT_EQ(r.stats.pointsAboveErrorBound, 0);
    EXPECT_LE(m.stats.normalizedDistance.max, bound * (1 + 1e-5));
    EXPECT_LE(MaxOwnPlaneDistance(s, r), bound * (1 + 1e-5));
    EXPECT_NEAR(r.stats.surfaceErrorMax, m.stats.normalizedDistance.max, 1e-6 * bound + 1e-9);
    EXPECT_GT(r.surfels.size(), plain.surfels.size()) << "meeting a tighter bound takes more surfels";
    EXPECT_GT(r.stats.splitsForSurfaceBound, 0) << "the own planes alone did not meet it";
}

// On a cube with sharp edges the blend rounds every edge even when each surfel is a single
// point (splitting alone left points beyond this bound). Narrowing the blend of the one-point
// surfels there makes it follow the nearest surfel's plane: the bound holds, and the metric
// confirms it. The ellipses keep their size (coverage).
TEST(ErrorBound, SharpEdgesMeetTheBoundByNarrowingOnePointSurfels)
{
    const gstest::PointSet s = gstest::CubeSurface(24, true);
    const double bound = 1e-4;
    const ResamplingResult r = gstest::Resample(s, Bounded(bound));
    gstest::ExpectValidResult(r, s);
    EXPECT_GT(r.stats.narrowingsForSurfaceBound, 0);
    EXPECT_EQ(r.stats.pointsAboveErrorBound, 0);
    const gstest::Measured m = gstest::Measure(s, r);
    EXPECT_LE(m.stats.normalizedDistance.max, bound * (1 + 1e-5));
    EXPECT_LE(MaxOwnPlaneDistance(s, r), bound * (1 + 1e-5));
    // A one-point surfel's semi-axis stays the coverage margin times its point's spacing; its
    // blend scale is 1 halved 0 to 3 times, never below kMinBlendScale; other surfels keep 1, or
    // the crease blend scale (crease_blend.h).
    const PointGrid grid(s.points);
    const NeighborGraph graph = BuildAdaptiveNeighbors(s.points, s.normals, AdaptiveNeighborParams(), grid);
    const double margin = ResamplingParams().tuning.coverageMargin;
    int narrowed = 0;
    for (int i = 0; i < s.Size(); ++i) {
        const Surfel &f = r.surfels[r.representative[i]];
        if (f.memberCount != 1) {
            EXPECT_TRUE(f.blendScale == 1.f || f.blendScale == ResamplingParams().tuning.creaseBlendScale) << "point " << i;
            continue;
        }
        EXPECT_NEAR(f.majorAxis.Norm(), margin * graph.spacing[i], 1e-5 * graph.spacing[i]) << "point " << i;
        const double halvings = -std::log2(f.blendScale);
        EXPECT_NEAR(halvings, std::round(halvings), 1e-6) << "point " << i;
        EXPECT_GE(f.blendScale, kMinBlendScale) << "point " << i;
        narrowed += f.blendScale < 1;
    }
    EXPECT_GT(narrowed, 0);
}

// When the rounds run out first, the points left beyond the bound are counted exactly as the
// metric finds them (one and three projection rounds on the cube, which needs more; the third
// measures narrowed surfels).
TEST(ErrorBound, PointsLeftAtTheRoundCapAreTheMetricsOwn)
{
    const gstest::PointSet s = gstest::CubeSurface(24, true);
    const ResamplingResult plain = gstest::Resample(s);
    const PointGrid grid(s.points);
    const NeighborGraph graph = BuildAdaptiveNeighbors(s.points, s.normals, AdaptiveNeighborParams(), grid);
    const double diagonal = plain.stats.diagonal;
    SurfelGenerationParams surfelParam;
    surfelParam.weightWidth = 0.01 * diagonal;
    const double bound = 1e-4 * diagonal;
    for (int rounds : {1, 3}) {
        SCOPED_TRACE(rounds);
        Clustering clusters;
        clusters.label = plain.representative;
        clusters.clusterCount = int(plain.surfels.size());
        ClusterRefiner refiner(s.points, s.normals, clusters, 1.0 / (surfelParam.weightWidth * surfelParam.weightWidth));
        const SurfaceErrorBoundResult r = SplitToSurfaceErrorBound(s.points, s.normals, graph.spacing, surfelParam,
                                                                   bound, diagonal, rounds, refiner, clusters);
        EXPECT_EQ(r.rounds, rounds);
        EXPECT_EQ(r.narrowings > 0, rounds > 1);
        ResamplingResult capped;
        capped.surfels = r.surfels;
        capped.representative = clusters.label;
        const gstest::Measured m = gstest::Measure(s, capped);
        const int above =
            int(std::count_if(m.distance.begin(), m.distance.end(), [&](float d) { return d > bound; }));
        EXPECT_GT(above, 0);
        EXPECT_EQ(r.pointsAbove, above);
        EXPECT_NEAR(r.maxDistance, m.stats.distance.max, 1e-6 * diagonal);
    }
}

TEST(ErrorBound, IdenticalOutputForOneAndTwoThreads)
{
    const gstest::PointSet s = BumpySphere(8000, 3);
    ResamplingResult one, two;
    {
        gstest::ScopedThreadCount t(1);
        one = gstest::Resample(s, Bounded(2e-4));
    }
    {
        gstest::ScopedThreadCount t(2);
        two = gstest::Resample(s, Bounded(2e-4));
    }
    EXPECT_GT(one.stats.splitsForSurfaceBound, 0);
    EXPECT_EQ(one.representative, two.representative);
    EXPECT_EQ(one.stats.pointsAboveErrorBound, two.stats.pointsAboveErrorBound);
    EXPECT_EQ(one.stats.surfaceErrorMax, two.stats.surfaceErrorMax);

    // With narrowed surfels (sharp edges): the same axes too.
    const gstest::PointSet cube = gstest::CubeSurface(24, true);
    {
        gstest::ScopedThreadCount t(1);
        one = gstest::Resample(cube, Bounded(1e-4));
    }
    {
        gstest::ScopedThreadCount t(2);
        two = gstest::Resample(cube, Bounded(1e-4));
    }
    EXPECT_GT(one.stats.narrowingsForSurfaceBound, 0);
    EXPECT_EQ(one.stats.narrowingsForSurfaceBound, two.stats.narrowingsForSurfaceBound);
    EXPECT_EQ(one.representative, two.representative);
    ASSERT_EQ(one.surfels.size(), two.surfels.size());
    for (size_t c = 0; c < one.surfels.size(); ++c) {
        EXPECT_EQ(one.surfels[c].majorAxis, two.surfels[c].majorAxis) << "surfel " << c;
        EXPECT_EQ(one.surfels[c].minorAxis, two.surfels[c].minorAxis) << "surfel " << c;
        EXPECT_EQ(one.surfels[c].blendScale, two.surfels[c].blendScale) << "surfel " << c;
    }
}

// One size control a run: with an error bound, a target count changes nothing (the bound sets
// the count), and the bound's figures describe the surfels returned: they equal the metric's.
TEST(ErrorBound, DecidesTheSizeAloneAndItsFiguresDescribeTheSurfels)
{
    const gstest::PointSet s = gstest::FibonacciSphere(6000);
    const double bound = 0.6 * gstest::Measure(s, gstest::Resample(s)).stats.normalizedDistance.max;
    const ResamplingResult alone = gstest::Resample(s, Bounded(bound));
    ResamplingParams p = Bounded(bound);
    p.targetCount = int(alone.surfels.size()) + 300;
    EXPECT_EQ(p.SizeMode(), SizeControl::ErrorBound);
    const ResamplingResult r = gstest::Resample(s, p);
    gstest::ExpectValidResult(r, s);
    ASSERT_EQ(r.surfels.size(), alone.surfels.size());
    EXPECT_EQ(r.representative, alone.representative);
    EXPECT_EQ(r.stats.splitsForTarget, 0);
    EXPECT_EQ(r.stats.TargetMissReason(), "");
    const gstest::Measured m = gstest::Measure(s, r);
    EXPECT_NEAR(r.stats.surfaceErrorMax, m.stats.normalizedDistance.max, 1e-6 * bound + 1e-9);
    EXPECT_EQ(r.stats.pointsAboveErrorBound, 0);
    EXPECT_LE(MaxOwnPlaneDistance(s, r), bound * (1 + 1e-5));
}

bool StopInSurfaceRounds(int, const char *what) { return std::strstr(what, "error bound on the surface") == nullptr; }

// The projection rounds report progress, and a callback can stop them.
TEST(ErrorBound, CallbackCanCancelTheSurfaceRounds)
{
    OrientedPointMesh m;
    gstest::ToMesh(gstest::CubeSurface(16, true), m);
    EXPECT_THROW(ResamplePointSet(m, Bounded(1e-4), StopInSurfaceRounds), ResamplingCancelled);
}

} // namespace
