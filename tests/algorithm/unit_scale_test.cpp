// The resampler's result does not depend on the model's units (usable_points.h): scaled by a
// power of two the surfels are the same up to the scale, scaled by any factor the count is the
// same, and coordinates near the float limits give finite surfels or a clear error.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "pipeline_support.h"

namespace {

using namespace vcg::gaussphere;
using gstest::P3;

gstest::PointSet Scaled(gstest::PointSet s, double factor)
{
    for (P3 &p : s.points) p = P3::Construct(vcg::Point3d::Construct(p) * factor);
    return s;
}

void ExpectAllFinite(const ResamplingResult &r)
{
    for (const Surfel &s : r.surfels) {
        for (int d = 0; d < 3; ++d) {
            ASSERT_TRUE(std::isfinite(s.position[d]) && std::isfinite(s.normal[d]) && std::isfinite(s.majorAxis[d]) &&
                        std::isfinite(s.minorAxis[d]));
        }
        ASSERT_TRUE(std::isfinite(s.fitOffset));
        ASSERT_TRUE(std::isfinite(float(vcg::Point3d::Construct(s.majorAxis).Norm())));
    }
}

/// The settings of the three size controls: the level, a target count, an error bound.
std::vector<ResamplingParams> SizeControls()
{
    ResamplingParams level, target, bound;
    target.targetCount = 300;
    bound.maxErrorFraction = 0.004;
    return {level, target, bound};
}

// Exact but for the components that the scale takes below the smallest normal float, which keep
// fewer bits.
const double kSubnormalStep = std::numeric_limits<float>::denorm_min();

TEST(UnitScale, PowerOfTwoScalesGiveTheSameSurfelsScaled)
{
    const gstest::PointSet cube = gstest::CubeSurface(24, true);
    for (const ResamplingParams &param : SizeControls()) {
        const ResamplingResult unit = gstest::Resample(cube, param);
        for (int exponent : {-100, -20, 7, 100}) {
            const double factor = std::ldexp(1.0, exponent);
            const ResamplingResult scaled = gstest::Resample(Scaled(cube, factor), param);
            ASSERT_EQ(scaled.surfels.size(), unit.surfels.size()) << "2^" << exponent;
            EXPECT_EQ(scaled.representative, unit.representative) << "2^" << exponent;
            for (size_t i = 0; i < unit.surfels.size(); ++i) {
                const Surfel &a = unit.surfels[i], &b = scaled.surfels[i];
                for (int d = 0; d < 3; ++d) {
                    ASSERT_NEAR(b.position[d], double(a.position[d]) * factor, kSubnormalStep) << "surfel " << i << " 2^" << exponent;
                    ASSERT_NEAR(b.majorAxis[d], double(a.majorAxis[d]) * factor, kSubnormalStep);
                    ASSERT_NEAR(b.minorAxis[d], double(a.minorAxis[d]) * factor, kSubnormalStep);
                    ASSERT_EQ(b.normal[d], a.normal[d]);
                }
                ASSERT_NEAR(b.fitOffset, double(a.fitOffset) * factor, kSubnormalStep);
                ASSERT_EQ(b.blendScale, a.blendScale);
            }
            EXPECT_DOUBLE_EQ(scaled.stats.diagonal, unit.stats.diagonal * factor);
            EXPECT_EQ(scaled.stats.normalErrorRms, unit.stats.normalErrorRms);
        }
    }
}

TEST(UnitScale, AnyScaleGivesTheSameCount)
{
    const gstest::PointSet sphere = gstest::FibonacciSphere(5000);
    const ResamplingResult unit = gstest::Resample(sphere);
    for (double factor : {1e-30, 1e-7, 3e5, 1e30, 6e37}) {
        const ResamplingResult scaled = gstest::Resample(Scaled(sphere, factor));
        ExpectAllFinite(scaled);
        // Not the same surfels: the point order follows a curve fixed in space (morton_order.h),
        // and a model scaled by anything but a power of two meets it elsewhere. Another order
        // of the same points gives as many surfels, as good, up to the variation of the
        // clustering (about 1 % of these 1,000 surfels).
        EXPECT_NEAR(double(scaled.surfels.size()), double(unit.surfels.size()), 0.02 * unit.surfels.size())
            << "scale " << factor;
        EXPECT_NEAR(scaled.stats.normalErrorRms, unit.stats.normalErrorRms, 0.02 * unit.stats.normalErrorRms);
    }
}

// A sphere reaching 3e38 (the float limit is 3.4e38) under an error bound: its squared
// distances, bounding box and blended surface would overflow at the model's own scale.
TEST(UnitScale, CoordinatesNearTheFloatLimitGiveFiniteSurfels)
{
    ResamplingParams bound;
    bound.maxErrorFraction = 0.01;
    ResamplingParams target;
    target.targetCount = 200;
    for (const ResamplingParams &param : {ResamplingParams(), bound, target}) {
        const ResamplingResult r = gstest::Resample(gstest::FibonacciSphere(2000, 3e38f), param);
        EXPECT_GT(r.surfels.size(), 100u);
        ExpectAllFinite(r);
        EXPECT_TRUE(std::isfinite(r.stats.diagonal));
        EXPECT_EQ(r.stats.pointsAboveErrorBound, 0);
    }
}

TEST(UnitScale, FarOutliersGiveFiniteSurfels)
{
    gstest::PointSet three;
    three.Add(P3(1e30f, 0, 0), P3(0, 0, 1));
    three.Add(P3(0, 1e30f, 0), P3(0, 0, 1));
    three.Add(P3(0, 0, 1e30f), P3(0, 0, 1));
    ExpectAllFinite(gstest::Resample(three));

    gstest::PointSet withOutlier = gstest::PlaneGrid(10, 10, 0.1f);
    withOutlier.Add(P3(1e30f, 1e30f, 1e30f), P3(0, 0, 1));
    const ResamplingResult r = gstest::Resample(withOutlier);
    ExpectAllFinite(r);
    EXPECT_GE(r.surfels.size(), 1u);
    EXPECT_GT(r.stats.diagonal, 1e30);
}

// Two points at the opposite ends of the float range make one surfel whose axis is longer than
// the largest float: a clear error, not an infinite axis.
TEST(UnitScale, SurfelsBeyondTheFloatRangeAreAnError)
{
    gstest::PointSet ends;
    const float big = std::numeric_limits<float>::max();
    ends.Add(P3(-big, -big, 0), P3(0, 0, 1));
    ends.Add(P3(big, big, 0), P3(0, 0, 1));
    try {
        gstest::Resample(ends);
        ADD_FAILURE() << "no exception for surfels beyond the float range";
    } catch (const std::overflow_error &e) {
        EXPECT_NE(std::string(e.what()).find("scale the model down"), std::string::npos) << e.what();
    }
}

// A small model near the end of the float range: its surfels overflow there, and the message
// names the distance from the origin, not the size, as the cause.
TEST(UnitScale, SurfelsOfAFarSmallModelNameItsDistance)
{
    // A unit sphere's points and normals, flattened onto the plane x = 3e38: the surfels' fitted
    // offsets along the normals carry them past the largest float.
    const gstest::PointSet sphere = gstest::FibonacciSphere(500);
    gstest::PointSet far;
    for (int i = 0; i < sphere.Size(); ++i)
        far.Add(P3(3e38f, sphere.points[i][1], sphere.points[i][2]), sphere.normals[i]);
    try {
        gstest::Resample(far);
        ADD_FAILURE() << "no exception for surfels beyond the float range";
    } catch (const std::overflow_error &e) {
        EXPECT_NE(std::string(e.what()).find("move the model towards the origin"), std::string::npos) << e.what();
    }
}

// Coordinates far from the origin are held in coarse float steps: the run says so, with the
// distance and the step, and stays quiet for the same model near the origin or a few diagonals
// away.
TEST(UnitScale, CoarseFloatCoordinatesAreReported)
{
    const gstest::PointSet sphere = gstest::FibonacciSphere(2000); // diagonal 2 sqrt 3
    const auto shifted = [&sphere](float offset) {
        gstest::PointSet s = sphere;
        for (P3 &p : s.points) p += P3(offset, 0, 0);
        return s;
    };
    EXPECT_EQ(gstest::Resample(sphere).stats.CoarsePositionsReason(), "");
    EXPECT_EQ(gstest::Resample(shifted(100)).stats.CoarsePositionsReason(), "");
    // At 4e6 (a georeferenced scan's northing) floats step by 0.25: 1/14 of this diagonal.
    const ResamplingStats far = gstest::Resample(shifted(4e6f)).stats;
    EXPECT_DOUBLE_EQ(far.farthestCoordinate, double(4e6f + 1.0f));
    const std::string reason = far.CoarsePositionsReason();
    EXPECT_NE(reason.find("up to 4000001 units from the origin"), std::string::npos) << reason;
    EXPECT_NE(reason.find("steps of 0.25"), std::string::npos) << reason;
    EXPECT_DOUBLE_EQ(FloatStepAt(4e6), 0.25);
    EXPECT_DOUBLE_EQ(FloatStepAt(-1.0), std::ldexp(1.0, -23));
}

TEST(UnitScale, PositionsAndNormalsAreCountedApart)
{
    gstest::PointSet s = gstest::FibonacciSphere(1000);
    const float inf = std::numeric_limits<float>::infinity();
    s.points[3] = P3(inf, 0, 0);
    s.points[4] = P3(0, std::numeric_limits<float>::quiet_NaN(), 0);
    s.normals[5] = P3(0, 0, 0);
    s.normals[6] = P3(1e20f, 1e20f, 1e20f); // long, finite: usable
    const ResamplingResult r = gstest::Resample(s);
    EXPECT_EQ(r.stats.skippedPositions, 2);
    EXPECT_EQ(r.stats.skippedNormals, 1);
    EXPECT_EQ(r.stats.skippedCount, 3);
    EXPECT_GE(r.representative[6], 0);
}

} // namespace
