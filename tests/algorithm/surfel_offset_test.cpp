// FitSurfelOffsets: surfels move along their normals to fit the blended surface; planes stay
// put, the fit converges, crease clusters stay, and the result does not depend on the threads.
#include <gtest/gtest.h>

#include <algorithm>

#include <vcg_ext/gaussphere/neighbors/point_grid.h>
#include <vcg_ext/gaussphere/surfels/surfel_offset.h>
#include <vcg_ext/surfel_error/surfel_error.h>

#include "pipeline_support.h"

namespace {

using namespace vcg::gaussphere;
using gstest::P3;

/// A point set with its neighbour graph, and the clusters and surfels (before any offset
/// fitting) of a resampling of it.
struct Fixture
{
    gstest::PointSet s;
    NeighborGraph graph;
    Clustering clusters;
    std::vector<Surfel> surfels;

    explicit Fixture(const gstest::PointSet &points, ResamplingParams p = {}) : s(points)
    {
        p.fitOffsets = false;
        const ResamplingResult r = gstest::Resample(s, p);
        clusters.label.assign(r.representative.begin(), r.representative.end());
        clusters.clusterCount = int(r.surfels.size());
        surfels = r.surfels;
        const PointGrid grid(s.points);
        graph = BuildAdaptiveNeighbors(s.points, s.normals, AdaptiveNeighborParams(), grid);
    }
    SurfelOffsetResult Fit(std::vector<Surfel> &fitted, const FlatVector<char> *crease = nullptr,
                           double maxPlaneDistance = 0) const
    {
        return FitSurfelOffsets(s.points, s.normals, graph, clusters, crease, fitted, maxPlaneDistance);
    }
    /// The largest distance of a point to its surfel's plane.
    double LargestPlaneDistance(const std::vector<Surfel> &fitted) const
    {
        double largest = 0;
        for (int i = 0; i < s.Size(); ++i) {
            const Surfel &f = fitted[clusters.label[i]];
            largest = std::max(largest, std::abs(double((s.points[i] - f.position).dot(f.normal))));
        }
        return largest;
    }
};

/// Largest distance between the positions of two lists of surfels.
double LargestMove(const std::vector<Surfel> &a, const std::vector<Surfel> &b)
{
    double largest = 0;
    for (size_t c = 0; c < a.size(); ++c) largest = std::max(largest, double((a[c].position - b[c].position).Norm()));
    return largest;
}

TEST(SurfelOffset, PlaneSurfelsStayOnThePlane)
{
    const Fixture f(gstest::PlaneGrid(40, 40, 0.1f));
    std::vector<Surfel> fitted = f.surfels;
    f.Fit(fitted);
    for (const Surfel &s : fitted) EXPECT_NEAR(s.position[2], 0.f, 1e-6f);
    EXPECT_LT(LargestMove(fitted, f.surfels), 1e-6);
}

TEST(SurfelOffset, OnACurvedSurfaceTheFitMovesAlongNormalsAndConverges)
{
    ResamplingParams p;
    p.targetCount = 400; // clusters of about ten points: a visible blend bias on the sphere
    const Fixture f(gstest::FibonacciSphere(4000), p);
    std::vector<Surfel> once = f.surfels;
    const SurfelOffsetResult fit = f.Fit(once);
    EXPECT_GT(fit.moved, 0);
    const double first = LargestMove(once, f.surfels);
    EXPECT_NEAR(fit.largest, first, 1e-6);
    EXPECT_GT(first, 1e-4) << "the blend of surfels on a sphere is off the samples";
    for (size_t c = 0; c < once.size(); ++c) { // along the normal only, by the recorded offset
        const vcg::Point3f move = once[c].position - f.surfels[c].position;
        EXPECT_LT((move - f.surfels[c].normal * move.dot(f.surfels[c].normal)).Norm(), 1e-6f) << "surfel " << c;
        EXPECT_NEAR(once[c].fitOffset, move.dot(f.surfels[c].normal), 1e-6f) << "surfel " << c;
    }
    // A second fit from the fitted surfels has less left to correct: the first went the right way.
    std::vector<Surfel> twice = once;
    f.Fit(twice);
    EXPECT_LT(LargestMove(twice, once), 0.5 * first);
    for (size_t c = 0; c < twice.size(); ++c) // the offsets add up: back to the unfitted position
        EXPECT_LT((twice[c].position - twice[c].normal * twice[c].fitOffset - f.surfels[c].position).Norm(), 1e-6f) << c;
}

TEST(SurfelOffset, MovesKeepEveryMemberWithinAPlaneDistance)
{
    ResamplingParams p;
    p.targetCount = 400;
    const Fixture f(gstest::FibonacciSphere(4000), p);
    const double before = f.LargestPlaneDistance(f.surfels);
    std::vector<Surfel> free = f.surfels, bounded = f.surfels;
    f.Fit(free);
    ASSERT_GT(f.LargestPlaneDistance(free), before) << "unbounded, some member ends farther: the test can fail";
    EXPECT_GT(f.Fit(bounded, nullptr, before).moved, 0);
    EXPECT_LE(f.LargestPlaneDistance(bounded), before);
}

TEST(SurfelOffset, CreaseClustersAndNarrowedSurfelsStay)
{
    ResamplingParams p;
    p.targetCount = 400;
    const Fixture f(gstest::FibonacciSphere(4000), p);
    // One crease point (the last member) in every other cluster; every third surfel narrowed.
    FlatVector<char> crease(f.s.Size(), 0);
    std::vector<int> lastMember(f.surfels.size(), -1);
    for (int i = 0; i < f.s.Size(); ++i) lastMember[f.clusters.label[i]] = i;
    std::vector<Surfel> fitted = f.surfels;
    for (size_t c = 0; c < fitted.size(); ++c) {
        if (c % 2 == 0) crease[lastMember[c]] = 1;
        if (c % 3 == 0) fitted[c].blendScale = 0.5f;
    }
    const std::vector<Surfel> before = fitted;
    const SurfelOffsetResult fit = f.Fit(fitted, &crease);
    int free = 0;
    for (size_t c = 0; c < fitted.size(); ++c) {
        const bool stays = c % 2 == 0 || c % 3 == 0;
        const bool moved = !(fitted[c].position == before[c].position);
        free += !stays;
        if (stays) EXPECT_FALSE(moved) << "surfel " << c;
        else EXPECT_TRUE(moved) << "surfel " << c;
    }
    EXPECT_EQ(fit.moved, free);
}

// The blend weights are the metric's (vcg_ext/surfel_error): the same exponent at any offset.
TEST(SurfelOffset, WeightsAreTheMetrics)
{
    Surfel s;
    s.position = P3(0.1f, -0.2f, 0.3f);
    s.normal = P3(0, 0, 1);
    s.majorAxis = P3(0.06f, 0.08f, 0);   // length 0.1
    s.minorAxis = P3(-0.024f, 0.018f, 0); // length 0.03
    const vcg::gaussphere::SurfelSurface surface = vcg::gaussphere::MakeEllipseSurfelSurface(
        {s.position, s.position + P3(1, 0, 0)}, {s.normal, s.normal}, {s.majorAxis, s.majorAxis}, {s.minorAxis, s.minorAxis});
    const BlendWeight weight(s);
    for (const P3 &x : {P3(0.1f, -0.2f, 0.3f), P3(0.15f, -0.1f, 0.32f), P3(0.05f, -0.22f, 0.25f), P3(0.3f, 0, 0.3f)}) {
        const double expected = surface[0].WeightExponent(vcg::Point3d::Construct(x));
        EXPECT_NEAR(weight.Exponent(s.position, x), expected, 1e-4 * (1 + expected)) << x[0] << " " << x[1] << " " << x[2];
    }
}

TEST(SurfelOffset, SameResultForAnyThreadCount)
{
    ResamplingParams p;
    p.targetCount = 400;
    const Fixture f(gstest::FibonacciSphere(4000), p);
    std::vector<Surfel> one = f.surfels, two = f.surfels;
    {
        const gstest::ScopedThreadCount threads(1);
        f.Fit(one);
    }
    {
        const gstest::ScopedThreadCount threads(2);
        f.Fit(two);
    }
    EXPECT_EQ(LargestMove(one, two), 0.0);
}

} // namespace
