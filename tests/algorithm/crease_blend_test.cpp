// NarrowBlendsAroundCreases and ResamplingParams::creaseBlendScale: the surfels around a crease blend
// narrower, one-point clusters and smooth surfaces keep their blend, and the blended surface
// the error metric projects on follows sharp edges more closely.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <vcg_ext/gaussphere/surfels/crease_blend.h>

#include "pipeline_support.h"

namespace {

using namespace vcg::gaussphere;

// Ten points in five clusters: point 1 is a crease point, with neighbours 3 (outside its cone
// of normals) and 4 (a one-point cluster); point 2 is one too, and reaches cluster 1 again;
// point 7 is not, and its neighbour 5 keeps its blend; point 9 has no cluster (skipped input).
struct HandMadeCase
{
    NeighborGraph graph = gstest::MakeGraph({{1}, {4, 3}, {3, 9}, {2}, {1}, {6}, {5}, {5}, {7}, {2}});
    Clustering clusters;
    std::vector<Surfel> surfels = std::vector<Surfel>(5);
    HandMadeCase()
    {
        clusters.label = {0, 0, 1, 1, 2, 3, 3, 4, 4, -1};
        clusters.clusterCount = 5;
        for (int l : clusters.label)
            if (l >= 0) ++surfels[l].memberCount;
        graph.count[1] = 1; // neighbour 3 lies outside the cone: still a neighbour for the blend
        graph.crease.assign(10, 0);
        graph.crease[1] = graph.crease[2] = 1;
    }
};

TEST(CreaseBlend, NarrowsClustersHoldingACreasePointOrANeighbourOfOne)
{
    HandMadeCase c;
    EXPECT_EQ(NarrowBlendsAroundCreases(c.graph, c.clusters, 0.7f, c.surfels), 2) << "each surfel counted once";
    EXPECT_EQ(c.surfels[0].blendScale, 0.7f) << "holds the crease point";
    EXPECT_EQ(c.surfels[1].blendScale, 0.7f) << "holds a neighbour of it";
    EXPECT_EQ(c.surfels[2].blendScale, 1.f) << "a one-point cluster stands for the edge itself";
    EXPECT_EQ(c.surfels[3].blendScale, 1.f) << "only a neighbour of a point that is no crease point";
    EXPECT_EQ(c.surfels[4].blendScale, 1.f);
}

TEST(CreaseBlend, NothingNarrowsWithoutCreaseMarksOrAtScaleOne)
{
    HandMadeCase c;
    EXPECT_EQ(NarrowBlendsAroundCreases(c.graph, c.clusters, 1.f, c.surfels), 0);
    c.graph.crease.clear(); // no crease angle: the neighbour search marked nothing
    EXPECT_EQ(NarrowBlendsAroundCreases(c.graph, c.clusters, 0.5f, c.surfels), 0);
    for (const Surfel &s : c.surfels) EXPECT_EQ(s.blendScale, 1.f);
}

TEST(CreaseBlend, ScaleOutsideZeroToOneIsRejected)
{
    for (float bad : {0.f, -0.5f, 1.01f, std::numeric_limits<float>::quiet_NaN()}) {
        ResamplingParams p;
        p.tuning.creaseBlendScale = bad;
        EXPECT_NE(p.Validate().find("CreaseBlendScale"), std::string::npos) << bad;
    }
    ResamplingParams p;
    p.tuning.creaseBlendScale = 1.f;
    EXPECT_EQ(p.Validate(), "");
}

// The cube's edges: surfels on and beside them narrowed, the faces' interiors and the one-point
// clusters not; the blended surface then rounds the edges less.
TEST(CreaseBlend, OnACubeTheEdgesComeOutSharper)
{
    const gstest::PointSet cube = gstest::CubeSurface(24, true);
    const ResamplingResult narrowed = gstest::Resample(cube);
    ResamplingParams wideParam;
    wideParam.tuning.creaseBlendScale = 1.f;
    const ResamplingResult wide = gstest::Resample(cube, wideParam);
    ASSERT_EQ(narrowed.surfels.size(), wide.surfels.size()) << "the blend scale changes no cluster";

    const auto members = gstest::MembersOf(narrowed);
    const float defaultScale = ResamplingParams().tuning.creaseBlendScale, spacing = 2.f / 24;
    int narrowedCount = 0, interior = 0;
    for (size_t c = 0; c < members.size(); ++c) {
        const Surfel &s = narrowed.surfels[c];
        float nearest = 2;
        for (int i : members[c]) nearest = std::min(nearest, gstest::DistanceToCubeEdge(cube, i));
        EXPECT_TRUE(s.blendScale == 1.f || s.blendScale == defaultScale) << s.blendScale;
        if (s.blendScale < 1) {
            ++narrowedCount;
            EXPECT_GT(s.memberCount, 1);
            EXPECT_LT(nearest, 6 * spacing) << "surfel " << c << " is narrowed far from any edge";
        } else {
            EXPECT_TRUE(nearest > 2 * spacing || s.memberCount == 1) << "surfel " << c << " beside an edge is not narrowed";
        }
        if (nearest > 6 * spacing) ++interior;
    }
    EXPECT_GT(interior, 0) << "the test needs surfels inside the faces";
    for (const Surfel &s : wide.surfels) EXPECT_EQ(s.blendScale, 1.f);
    EXPECT_EQ(narrowedCount, narrowed.stats.surfelsNarrowedAtCreases);
    EXPECT_EQ(wide.stats.surfelsNarrowedAtCreases, 0);
    EXPECT_GT(narrowedCount, 0);

    const gstest::Measured sharp = gstest::Measure(cube, narrowed), round = gstest::Measure(cube, wide);
    EXPECT_LT(sharp.stats.normalizedDistance.rms, 0.97 * round.stats.normalizedDistance.rms);
    EXPECT_LT(sharp.stats.normalizedDistance.max, round.stats.normalizedDistance.max);
    std::printf("cube: %d of %zu surfels narrowed; D*RMS %.3e -> %.3e, D*max %.4f -> %.4f\n", narrowedCount,
                narrowed.surfels.size(), round.stats.normalizedDistance.rms, sharp.stats.normalizedDistance.rms,
                round.stats.normalizedDistance.max, sharp.stats.normalizedDistance.max);
}

TEST(CreaseBlend, NothingNarrowsWithoutACreaseAngle)
{
    ResamplingParams p;
    p.creaseAngle = 0;
    const ResamplingResult r = gstest::Resample(gstest::CubeSurface(24, true), p);
    EXPECT_EQ(r.stats.surfelsNarrowedAtCreases, 0);
    for (const Surfel &s : r.surfels) EXPECT_EQ(s.blendScale, 1.f);
}

TEST(CreaseBlend, ASmoothSurfaceKeepsEveryBlend)
{
    const ResamplingResult r = gstest::Resample(gstest::FibonacciSphere(4000));
    EXPECT_EQ(r.stats.surfelsNarrowedAtCreases, 0);
    for (const Surfel &s : r.surfels) EXPECT_EQ(s.blendScale, 1.f);
}

// With an error bound the surfels around creases are narrowed in each of its rounds, so the bound
// is checked on (and holds for) the narrowed blend. (On the CAD parts of bench/ it then needs fewer
// surfels; on this cube, whose edge normals are exact averages, about as many.)
TEST(CreaseBlend, TheErrorBoundHoldsForTheNarrowedBlend)
{
    const gstest::PointSet cube = gstest::CubeSurface(24, true);
    ResamplingParams p;
    p.maxErrorFraction = 0.002;
    const ResamplingResult narrowed = gstest::Resample(cube, p);
    p.tuning.creaseBlendScale = 1.f;
    const ResamplingResult wide = gstest::Resample(cube, p);
    ASSERT_GT(narrowed.stats.surfelsNarrowedAtCreases, 0);
    EXPECT_EQ(wide.stats.surfelsNarrowedAtCreases, 0);
    const float defaultScale = ResamplingParams().tuning.creaseBlendScale;
    int atDefault = 0;
    for (const Surfel &s : narrowed.surfels) {
        if (s.memberCount > 1) EXPECT_TRUE(s.blendScale == 1.f || s.blendScale == defaultScale) << s.blendScale;
        else EXPECT_LE(s.blendScale, 1.f); // one-point surfels: only the bound's own halvings
        atDefault += s.memberCount > 1 && s.blendScale == defaultScale;
    }
    EXPECT_EQ(atDefault, narrowed.stats.surfelsNarrowedAtCreases);
    EXPECT_EQ(narrowed.stats.pointsAboveErrorBound, 0);
    // The bound's own figures are those of the narrowed surfels it returned.
    const gstest::Measured m = gstest::Measure(cube, narrowed);
    EXPECT_LE(m.stats.normalizedDistance.max, p.maxErrorFraction * (1 + 1e-5));
    EXPECT_NEAR(narrowed.stats.surfaceErrorMax, m.stats.normalizedDistance.max, 1e-6);
    std::printf("cube at MaxError 0.002: %zu surfels with narrowed crease blends, %zu without\n",
                narrowed.surfels.size(), wide.surfels.size());
}

} // namespace
