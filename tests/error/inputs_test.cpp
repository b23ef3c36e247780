// Surfel error: which surfel represents a point, how radius and ellipse axes shape the blend,
// percentiles, and what bad input does.

#include "point_sets.h"

#include <vcg_ext/surfel_error/surfel_error.h>

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

using namespace surfel_error_test;
using vcg::Point3f;
using vcg::gaussphere::metric::ComputeSurfelError;
using vcg::gaussphere::metric::SurfelErrorAttributes;
using vcg::gaussphere::metric::SurfelErrorParams;
using vcg::gaussphere::metric::SurfelErrorStats;

namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();

::testing::AssertionResult Contains(const std::string& text, const std::string& part)
{
    if (text.find(part) != std::string::npos)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

// vcg meshes cannot be copied or moved: each fixture fills a mesh of the caller.

/// Three points around the origin with normal +z.
void AddPointsAroundOrigin(PointSet& m)
{
    AddPoint(m, Point3f(0.1f, 0, 0), Point3f(0, 0, 1));
    AddPoint(m, Point3f(-0.1f, 0, 0), Point3f(0, 0, 1));
    AddPoint(m, Point3f(0, 0.1f, 0), Point3f(0, 0, 1));
}

/// Surfel 0 at the origin with normal +z, surfel 1 at (1, 0, 0) tilted by 45° about y.
void AddUprightAndTiltedSurfels(PointSet& m)
{
    AddPoint(m, Point3f(0, 0, 0), Point3f(0, 0, 1));
    AddPoint(m, Point3f(1, 0, 0), Point3f(1, 0, 1).Normalize());
}

/// Two parallel surfels (normal +z): A at the origin, B at (1, 0, 0.2). A query point above
/// their midpoint is projected to the height of the weighted average of their centers, so
/// d = 1 − that height: 0.9 when they weigh the same, towards 1 when A dominates.
template <class Mesh>
void AddTwoParallelSurfels(Mesh& m)
{
    AddPoint(m, Point3f(0, 0, 0), Point3f(0, 0, 1));
    AddPoint(m, Point3f(1, 0, 0.2f), Point3f(0, 0, 1));
}

/// d(q, S') of the point q = (0.5, 0, 1) above the midpoint of AddTwoParallelSurfels().
template <class Mesh>
double DistanceAboveMidpoint(const Mesh& surfels, const SurfelErrorAttributes& attributes = {})
{
    PointSet q;
    AddPoint(q, Point3f(0.5f, 0, 1), Point3f(0, 0, 1));
    return ComputeSurfelError(q, surfels, SurfelErrorParams(), attributes).distance.max;
}

} // namespace

/// S = three points around the origin, S' = an upright and a tilted surfel.
class OwnSurfelTest : public ::testing::Test
{
protected:
    void SetUp() override
    {
        AddPointsAroundOrigin(original);
        AddUprightAndTiltedSurfels(surfels);
    }
    SurfelErrorStats Compute(const std::vector<int>* representative = nullptr)
    {
        SurfelErrorAttributes attributes;
        attributes.representative = representative;
        return ComputeSurfelError(original, surfels, SurfelErrorParams(), attributes);
    }
    const double chordOf45Degrees = 2 * std::sin(M_PI / 8);
    PointSet original, surfels;
};

TEST_F(OwnSurfelTest, NearestSurfelRepresentsPointsWithoutRepresentative)
{
    const SurfelErrorStats stats = Compute();
    EXPECT_NEAR(stats.normalToOwnSurfel.max, 0, 1e-12);
    EXPECT_EQ(stats.ownSurfelFromNearestCount, 3u);
}

TEST_F(OwnSurfelTest, RepresentativeChoosesTheOwnClusterSurfel)
{
    const std::vector<int> representedByTilted = {1, 1, 1};
    const SurfelErrorStats stats = Compute(&representedByTilted);
    EXPECT_NEAR(stats.normalToOwnSurfel.rms, chordOf45Degrees, 1e-6);
    EXPECT_NEAR(stats.normalToOwnSurfel.max, chordOf45Degrees, 1e-6);
    EXPECT_EQ(stats.ownSurfelFromNearestCount, 0u);
    EXPECT_EQ(stats.normalToBlended.rms, Compute().normalToBlended.rms)
        << "the blended form does not depend on the representatives";
}

TEST_F(OwnSurfelTest, UnnamedOrUnusableRepresentativeFallsBackToNearest)
{
    AddPoint(surfels, Point3f(5, 5, 5), Point3f(0, 0, 0)); // no normal: not a usable surfel
    const std::vector<int> representatives = {-1, 2, 1};
    const SurfelErrorStats stats = Compute(&representatives);
    EXPECT_EQ(stats.ownSurfelFromNearestCount, 2u);
    EXPECT_NEAR(stats.normalToOwnSurfel.max, chordOf45Degrees, 1e-6);
    EXPECT_NEAR(stats.normalToOwnSurfel.rms, chordOf45Degrees / std::sqrt(3.0), 1e-6);
}

TEST_F(OwnSurfelTest, MismatchedAttributesAndBadParametersAreRejected)
{
    const std::vector<int> outOfRange = {0, 2, 0}, tooShort = {0, 0};
    EXPECT_THROW(Compute(&outOfRange), std::invalid_argument);
    EXPECT_THROW(Compute(&tooShort), std::invalid_argument);

    const std::vector<Point3f> axes(2, Point3f(0.1f, 0, 0));
    SurfelErrorAttributes majorOnly;
    majorOnly.ellipseMajorAxes = &axes;
    EXPECT_THROW(ComputeSurfelError(original, surfels, SurfelErrorParams(), majorOnly),
                 std::invalid_argument);

    SurfelErrorParams noNeighbors;
    noNeighbors.neighborCount = 0;
    EXPECT_THROW(ComputeSurfelError(original, surfels, noNeighbors), std::invalid_argument);
    SurfelErrorParams zeroWidth;
    zeroWidth.widthFactor = 0;
    EXPECT_THROW(ComputeSurfelError(original, surfels, zeroWidth), std::invalid_argument);
}

TEST(SurfelErrorInputs, RadiusWeightsTheBlend)
{
    const auto distanceWithRadii = [](float radiusA, float radiusB) {
        RadiusPointSet surfels;
        AddTwoParallelSurfels(surfels);
        surfels.vert[0].R() = radiusA;
        surfels.vert[1].R() = radiusB;
        return DistanceAboveMidpoint(surfels);
    };
    EXPECT_NEAR(distanceWithRadii(0.5f, 0.5f), 0.9, 1e-6);
    EXPECT_GT(distanceWithRadii(1.0f, 0.25f), 0.96); // A dominates: height ≈ 0.025
    EXPECT_LT(distanceWithRadii(0.25f, 1.0f), 0.84); // B dominates: height ≈ 0.17
    // No radius: both take their spacing, which is the same.
    EXPECT_NEAR(distanceWithRadii(0, 0), 0.9, 1e-6);
}

// A: semi-axes 1 and 0.25; B: circular, 0.25. With A's major axis towards B, A weighs far more
// at the midpoint (exponents 0.11 vs 2.06 over σ² → height ≈ 0.025). With A's major axis across,
// both are 0.5/0.25 minor radii away and only the normal term differs (A's uses its major
// length), so the height stays near the symmetric 0.1 (≈ 0.097).
TEST(SurfelErrorInputs, EllipseMajorAxisExtendsInfluence)
{
    PointSet surfels;
    AddTwoParallelSurfels(surfels);
    const auto distanceWithMajorOfA = [&](const Point3f& direction) {
        const Point3f across = Point3f(0, 0, 1) ^ direction;
        const std::vector<Point3f> major = {direction * 1.0f, Point3f(0.25f, 0, 0)};
        const std::vector<Point3f> minor = {across * 0.25f, Point3f(0, 0.25f, 0)};
        SurfelErrorAttributes attributes;
        attributes.ellipseMajorAxes = &major;
        attributes.ellipseMinorAxes = &minor;
        return DistanceAboveMidpoint(surfels, attributes);
    };
    EXPECT_GT(distanceWithMajorOfA(Point3f(1, 0, 0)), 0.97);
    EXPECT_NEAR(distanceWithMajorOfA(Point3f(0, 1, 0)), 0.903, 0.005);
}

// The blend scale narrows a surfel's weight only: equal ellipses, B's blend scaled by 1/4, and
// A dominates as if B were four times smaller. Values outside (0, 1] count as 1; a scale array
// of the wrong size is refused.
TEST(SurfelErrorInputs, BlendScaleNarrowsTheWeight)
{
    PointSet surfels;
    AddTwoParallelSurfels(surfels);
    const std::vector<Point3f> major = {Point3f(1, 0, 0), Point3f(1, 0, 0)};
    const std::vector<Point3f> minor = {Point3f(0, 1, 0), Point3f(0, 1, 0)};
    const auto distanceWithScales = [&](std::vector<float> scales) {
        SurfelErrorAttributes attributes;
        attributes.ellipseMajorAxes = &major;
        attributes.ellipseMinorAxes = &minor;
        attributes.blendScale = &scales;
        return DistanceAboveMidpoint(surfels, attributes);
    };
    const double symmetric = distanceWithScales({1, 1});
    EXPECT_NEAR(symmetric, 0.9, 1e-6);
    EXPECT_GT(distanceWithScales({1, 0.25f}), 0.96);
    EXPECT_LT(distanceWithScales({0.25f, 1}), 0.84);
    for (float invalid : {0.f, -1.f, 2.f, std::numeric_limits<float>::quiet_NaN()})
        EXPECT_NEAR(distanceWithScales({1, invalid}), symmetric, 1e-9) << invalid;
    EXPECT_THROW(distanceWithScales({1}), std::invalid_argument);
}

TEST(SurfelErrorInputs, PercentileIsNearestRank)
{
    std::vector<double> oneToThousand;
    for (int i = 1; i <= 1000; ++i)
        oneToThousand.push_back(i);
    EXPECT_EQ(vcg::gaussphere::NearestRankPercentile(oneToThousand, 99.9), 999);
    EXPECT_EQ(vcg::gaussphere::NearestRankPercentile(oneToThousand, 50), 500);
    EXPECT_EQ(vcg::gaussphere::NearestRankPercentile(oneToThousand, 100), 1000);
    std::vector<double> bunnySized;
    for (int i = 34834; i >= 1; --i)
        bunnySized.push_back(i);
    EXPECT_EQ(vcg::gaussphere::NearestRankPercentile(bunnySized, 99.9), 34800); // ceil(34799.166)
    EXPECT_EQ(vcg::gaussphere::NearestRankPercentile({4.5}, 99.9), 4.5);
    // 99.9 · 41000 / 100 rounds to just above 40959 in double precision.
    std::vector<double> roundingTrap;
    for (int i = 1; i <= 41000; ++i)
        roundingTrap.push_back(i);
    EXPECT_EQ(vcg::gaussphere::NearestRankPercentile(roundingTrap, 99.9), 40959);
}

TEST(SurfelErrorInputs, SummaryKeepsOutlierInMaxButNotInP999AndSkipsNaN)
{
    std::vector<double> errors(999, 1.0);
    errors.push_back(50.0);
    errors.push_back(std::numeric_limits<double>::quiet_NaN());
    const vcg::gaussphere::metric::ErrorSummary summary = vcg::gaussphere::metric::SummarizeDefined(errors);
    EXPECT_EQ(summary.count, 1000u);
    EXPECT_EQ(summary.max, 50.0);
    EXPECT_EQ(summary.p999, 1.0);
    EXPECT_NEAR(summary.rms, std::sqrt((999 + 2500) / 1000.0), 1e-12);
}

TEST(SurfelErrorInputs, SimplifiedSetWithoutNormalsIsRejected)
{
    PointSet original, noNormals;
    AddPlaneGrid(original, 5, 5, 0.1f);
    AddPlaneGrid(noNormals, 5, 5, 0.1f);
    for (auto& v : noNormals.vert)
        v.N() = Point3f(0, 0, 0);
    EXPECT_THROW(ComputeSurfelError(original, noNormals), std::invalid_argument);
}

TEST(SurfelErrorInputs, EmptySetsAreRejected)
{
    PointSet empty, plane, allDeleted;
    AddPlaneGrid(plane, 5, 5, 0.1f);
    EXPECT_THROW(ComputeSurfelError(empty, plane), std::invalid_argument);
    EXPECT_THROW(ComputeSurfelError(plane, empty), std::invalid_argument);
    AddPlaneGrid(allDeleted, 2, 2, 0.1f);
    for (auto& v : allDeleted.vert)
        v.SetD();
    EXPECT_THROW(ComputeSurfelError(allDeleted, plane), std::invalid_argument);
}

TEST(SurfelErrorInputs, UnusableSurfelsAreIgnored)
{
    PointSet original, surfels;
    AddPlaneGrid(original, 10, 10, 0.1f);
    AddPlaneGrid(surfels, 10, 10, 0.1f, 0.05f);
    const SurfelErrorStats clean = ComputeSurfelError(original, surfels);
    AddPoint(surfels, Point3f(0.3f, 0.3f, 1), Point3f(0, 0, 0));
    AddPoint(surfels, Point3f(0.3f, 0.3f, 1), Point3f(kNaN, 0, 1));
    AddPoint(surfels, Point3f(kNaN, 0.3f, 1), Point3f(0, 0, 1));
    const SurfelErrorStats dirty = ComputeSurfelError(original, surfels);
    EXPECT_EQ(dirty.surfelCount, 103u);
    EXPECT_EQ(dirty.usableSurfelCount, 100u);
    EXPECT_EQ(dirty.distance.max, clean.distance.max);
    EXPECT_EQ(dirty.normalToBlended.max, clean.normalToBlended.max);
}

TEST(SurfelErrorInputs, OriginalWithoutNormalsGivesDistancesOnly)
{
    PointSet original, surfels;
    AddPlaneGrid(original, 10, 10, 0.1f);
    AddPlaneGrid(surfels, 10, 10, 0.1f, 0.02f);
    for (auto& v : original.vert)
        v.N() = Point3f(0, 0, 0);
    const SurfelErrorStats stats = ComputeSurfelError(original, surfels);
    EXPECT_EQ(stats.distance.count, 100u);
    EXPECT_NEAR(stats.distance.max, 0.02, 1e-7);
    EXPECT_EQ(stats.normalToOwnSurfel.count, 0u);
    EXPECT_TRUE(std::isnan(stats.normalToOwnSurfel.rms));
    EXPECT_TRUE(std::isnan(stats.normalToBlended.max));
}

TEST(SurfelErrorInputs, NonFiniteOrDeletedOriginalPointsAreSkipped)
{
    PointSet original, surfels;
    AddPlaneGrid(original, 4, 4, 0.1f);
    AddPlaneGrid(surfels, 4, 4, 0.1f, 0.01f);
    original.vert[3].P() = Point3f(kNaN, 0, 0);
    original.vert[5].N() = Point3f(kNaN, kNaN, kNaN);
    original.vert[7].SetD();
    std::vector<float> perPoint;
    const SurfelErrorStats stats = ComputeSurfelError(original, surfels, SurfelErrorParams(), {}, &perPoint);
    EXPECT_EQ(stats.originalPointCount, 15u);
    EXPECT_EQ(stats.distance.count, 14u);
    EXPECT_EQ(stats.normalToBlended.count, 13u);
    EXPECT_TRUE(std::isnan(perPoint[3]));
    EXPECT_TRUE(std::isnan(perPoint[7]));
    EXPECT_NEAR(perPoint[5], 0.01, 1e-7);
    EXPECT_NEAR(stats.diagonal, std::sqrt(2.0) * 0.3, 1e-6);
}

namespace {

/// The message of the std::invalid_argument ComputeSurfelError throws, or "" when it measures.
std::string RefusalOf(const PointSet& original, const PointSet& surfels)
{
    try {
        ComputeSurfelError(original, surfels);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return std::string();
}

} // namespace

// vcg's single-precision KdTree overflows on such coordinates (squared distances, split values
// near FLT_MAX that read past its buffer): the metric refuses them before building it.
TEST(SurfelErrorInputs, CoordinatesBeyond1e18AreRefusedNamingTheVertex)
{
    PointSet original, surfels;
    AddPlaneGrid(original, 4, 4, 0.1f);
    AddPlaneGrid(surfels, 4, 4, 0.1f, 0.01f);
    AddPoint(original, Point3f(3e38f, 0, 0), Point3f(0, 0, 1));
    EXPECT_TRUE(Contains(RefusalOf(original, surfels),
                        "vertex 16 of the original set has the coordinate 3e+38, beyond the supported +-1e18"));

    PointSet plane, farSurfel;
    AddPlaneGrid(plane, 4, 4, 0.1f);
    AddPlaneGrid(farSurfel, 4, 4, 0.1f, 0.01f);
    AddPoint(farSurfel, Point3f(0, -2e19f, 0), Point3f(0, 0, 1));
    EXPECT_TRUE(Contains(RefusalOf(plane, farSurfel), "vertex 16 of the simplified set has the coordinate -2e+19"));

    // A small box far out: finite extent, but sums of coordinates overflow single precision.
    PointSet farOriginal, farSurfels;
    AddPlaneGrid(farOriginal, 4, 4, 1e32f, 0, 3e38f);
    AddPlaneGrid(farSurfels, 4, 4, 1e32f, 0, 3e38f);
    EXPECT_TRUE(Contains(RefusalOf(farOriginal, farSurfels), "vertex 0 of the original set"));
}

TEST(SurfelErrorInputs, UnusableSurfelsFarOutAreIgnoredNotRefused)
{
    PointSet original, surfels;
    AddPlaneGrid(original, 4, 4, 0.1f);
    AddPlaneGrid(surfels, 4, 4, 0.1f, 0.01f);
    AddPoint(surfels, Point3f(3e38f, 0, 0), Point3f(0, 0, 0)); // no normal
    const SurfelErrorStats stats = ComputeSurfelError(original, surfels);
    EXPECT_EQ(stats.usableSurfelCount, 16u);
    EXPECT_NEAR(stats.distance.max, 0.01, 1e-7);
}

TEST(SurfelErrorInputs, CoordinatesUpTo1e18AreMeasured)
{
    PointSet original, surfels;
    AddPlaneGrid(original, 10, 10, 1e17f, 0, -4.5e17f, -4.5e17f);
    AddPlaneGrid(surfels, 10, 10, 1e17f, 1e15f, -4.5e17f, -4.5e17f);
    AddPoint(original, Point3f(-1e18f, 1e18f, 0), Point3f(0, 0, 1));
    AddPoint(surfels, Point3f(1e18f, -1e18f, 1e15f), Point3f(0, 0, 1));
    const SurfelErrorStats stats = ComputeSurfelError(original, surfels);
    EXPECT_EQ(stats.distance.count, 101u);
    EXPECT_NEAR(stats.distance.max, 1e15, 1e9);
    EXPECT_NEAR(stats.distance.rms, 1e15, 1e9);
}
