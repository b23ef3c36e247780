// ResamplePointSet on degenerate input and parameters: too few points, unusable normals,
// duplicates, tiny clouds, invalid parameters (rejected by Validate with a message naming
// the parameter) and cancellation through the callback.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "pipeline_support.h"

namespace {

using namespace vcg::gaussphere;
using gstest::P3;

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const double kNaNd = std::numeric_limits<double>::quiet_NaN();

/// Expects std::invalid_argument whose message contains `needle` (case-insensitive).
template <class F>
void ExpectInvalidArgument(F f, const std::string &needle)
{
    try {
        f();
        ADD_FAILURE() << "no exception; expected invalid_argument mentioning '" << needle << "'";
    } catch (const std::invalid_argument &e) {
        std::string msg = e.what(), low = needle;
        std::transform(msg.begin(), msg.end(), msg.begin(), [](unsigned char c) { return std::tolower(c); });
        std::transform(low.begin(), low.end(), low.begin(), [](unsigned char c) { return std::tolower(c); });
        EXPECT_NE(msg.find(low), std::string::npos) << "message '" << e.what() << "' does not name " << needle;
    } catch (const std::exception &e) {
        ADD_FAILURE() << "unexpected exception: " << e.what();
    }
}

TEST(ResamplingInputs, EmptyAndOnePointMeshesAreRejected)
{
    ExpectInvalidArgument([] { gstest::Resample(gstest::PointSet()); }, "at least 2");
    gstest::PointSet one;
    one.Add(P3(0, 0, 0), P3(0, 0, 1));
    ExpectInvalidArgument([&] { gstest::Resample(one); }, "at least 2");
}

TEST(ResamplingInputs, AllZeroNormalsAreRejected)
{
    gstest::PointSet s = gstest::PlaneGrid(10, 10);
    for (P3 &n : s.normals) n = P3(0, 0, 0);
    ExpectInvalidArgument([&] { gstest::Resample(s); }, "normal");
}

// NaN, infinite and zero normals and NaN positions among valid points are skipped,
// counted, and mapped to -1; the rest is resampled normally.
TEST(ResamplingInputs, UnusableVerticesAreSkippedAndCounted)
{
    gstest::PointSet s = gstest::FibonacciSphere(2000);
    std::vector<char> skipped(s.Size(), 0);
    const float inf = std::numeric_limits<float>::infinity();
    for (int i = 0; i < s.Size(); i += 10) {
        switch ((i / 10) % 4) {
        case 0: s.normals[i] = P3(kNaN, 0, 1); break;
        case 1: s.normals[i] = P3(0, 0, 0); break;
        case 2: s.normals[i] = P3(inf, 0, 0); break;
        case 3: s.points[i] = P3(0, kNaN, 0); break;
        }
        skipped[i] = 1;
    }
    const ResamplingResult r = gstest::Resample(s);
    EXPECT_EQ(r.stats.inputCount, 2000);
    EXPECT_EQ(r.stats.skippedCount, 200);
    // Containment is checked on the kept points only (the skipped ones have NaN data).
    gstest::ExpectValidResult(r, s, skipped);
    for (const Surfel &f : r.surfels) ASSERT_TRUE(std::isfinite(f.position[0]) && std::isfinite(f.normal[0]));
    // The vertices are read in one range per thread and the ranges closed up: the same result
    // for any count, also when the ranges hold different numbers of skipped vertices.
    for (int i = 1; i < 700; i += 3) s.normals[i] = P3(0, 0, 0);
    ResamplingResult one;
    {
        const gstest::ScopedThreadCount t(1);
        one = gstest::Resample(s);
    }
    for (int threads : {2, 3}) {
        const gstest::ScopedThreadCount t(threads);
        const ResamplingResult many = gstest::Resample(s);
        EXPECT_EQ(many.stats.skippedCount, one.stats.skippedCount);
        EXPECT_EQ(many.representative, one.representative) << threads << " threads";
    }
}

// Non-unit normals are normalized before use: scaling every normal changes nothing.
TEST(ResamplingInputs, NormalLengthDoesNotMatter)
{
    const gstest::PointSet s = gstest::FibonacciSphere(3000);
    gstest::PointSet scaled = s;
    for (P3 &n : scaled.normals) n *= 4.f;
    const ResamplingResult a = gstest::Resample(s), b = gstest::Resample(scaled);
    EXPECT_EQ(a.representative, b.representative);
}

// The contract skips only zero or non-finite normals: a finite normal of any length is a
// direction. Lengths near float's range must not be mistaken for unusable ones (|n|^2
// overflows float above ~1.8e19).
TEST(ResamplingInputs, HugeFiniteNormalsAreUsable)
{
    const gstest::PointSet s = gstest::FibonacciSphere(1000);
    gstest::PointSet huge = s;
    for (P3 &n : huge.normals) n *= 1e20f;
    ASSERT_TRUE(std::isfinite(huge.normals[0][0]) && std::isfinite(huge.normals[0][2]));
    const ResamplingResult a = gstest::Resample(s);
    try {
        const ResamplingResult b = gstest::Resample(huge);
        EXPECT_EQ(b.stats.skippedCount, 0);
        EXPECT_EQ(a.representative, b.representative);
    } catch (const std::exception &e) {
        ADD_FAILURE() << "finite normals of length 1e20 rejected: " << e.what();
    }
}

// Every point three times: k-NN lists are full of zero distances; still valid output.
TEST(ResamplingInputs, TriplicatedPointsGiveValidSurfels)
{
    const gstest::PointSet base = gstest::FibonacciSphere(3000);
    gstest::PointSet s;
    for (int i = 0; i < base.Size(); ++i)
        for (int c = 0; c < 3; ++c) s.Add(base.points[i], base.normals[i]);
    const ResamplingResult r = gstest::Resample(s);
    gstest::ExpectValidResult(r, s);
    // Copies share a normal and are mutual nearest neighbours, so they share a cluster.
    for (int i = 0; i < s.Size(); i += 3) {
        EXPECT_EQ(r.representative[i], r.representative[i + 1]);
        EXPECT_EQ(r.representative[i], r.representative[i + 2]);
    }
}

// 40 copies of one point (all at one position with one normal): one cluster. The
// postcondition promises non-zero ellipse axes even though the spread and the local
// spacing are both zero.
TEST(ResamplingInputs, FortyCopiesOfOnePoint)
{
    gstest::PointSet s;
    for (int i = 0; i < 40; ++i) s.Add(P3(1, 2, 3), P3(0, 1, 0));
    const ResamplingResult r = gstest::Resample(s);
    ASSERT_EQ(r.surfels.size(), 1u);
    EXPECT_EQ(r.surfels[0].memberCount, 40);
    EXPECT_EQ(r.surfels[0].position, P3(1, 2, 3));
    EXPECT_NEAR(r.surfels[0].normal[1], 1, 1e-6);
    gstest::ExpectValidResult(r, s);
}

// Copies of every point (a scan merged with itself) change nothing but the member counts: the
// same surfels, each also representing its points' copies, at the level, at a target and spread
// evenly.
TEST(ResamplingInputs, CopiesOfEveryPointCountOnce)
{
    const gstest::PointSet once = gstest::FibonacciSphere(3000);
    const int n = once.Size();
    gstest::PointSet thrice;
    for (int copy = 0; copy < 3; ++copy)
        for (int i = 0; i < n; ++i) thrice.Add(once.points[i], once.normals[i]);
    ResamplingParams level, target, even;
    target.targetCount = 300;
    even.spreadEvenly = true;
    for (const ResamplingParams &p : {level, target, even}) {
        const ResamplingResult r1 = gstest::Resample(once, p), r3 = gstest::Resample(thrice, p);
        gstest::ExpectValidResult(r3, thrice);
        EXPECT_EQ(r1.stats.coincidentPoints, 0);
        EXPECT_EQ(r3.stats.coincidentPoints, 2 * n);
        ASSERT_EQ(r3.surfels.size(), r1.surfels.size());
        for (size_t c = 0; c < r1.surfels.size(); ++c) {
            const Surfel &a = r1.surfels[c], &b = r3.surfels[c];
            EXPECT_TRUE(a.position == b.position && a.normal == b.normal && a.majorAxis == b.majorAxis &&
                        a.minorAxis == b.minorAxis) << "surfel " << c;
            EXPECT_EQ(b.memberCount, 3 * a.memberCount) << "surfel " << c;
        }
        for (int i = 0; i < 3 * n; ++i) EXPECT_EQ(r3.representative[i], r1.representative[i % n]) << "vertex " << i;
    }
}

// Points at one position facing opposite sides (the two sides of a thin part) stay apart; copies
// facing one side with different normals become one point with their mean normal.
TEST(ResamplingInputs, CoincidentPointsMergeOnlyFacingOneSide)
{
    const gstest::PointSet plane = gstest::PlaneGrid(30, 30, 0.1f);
    gstest::PointSet sheet = plane; // the same points seen from below
    for (int i = 0; i < plane.Size(); ++i) sheet.Add(plane.points[i], P3(0, 0, -1));
    const ResamplingResult twoSided = gstest::Resample(sheet);
    gstest::ExpectValidResult(twoSided, sheet);
    EXPECT_EQ(twoSided.stats.coincidentPoints, 0);
    for (int i = 0; i < plane.Size(); ++i)
        EXPECT_NE(twoSided.representative[i], twoSided.representative[i + plane.Size()]) << "point " << i;

    gstest::PointSet tilted = plane; // copies whose normals lean 10 degrees to either side
    const float lean = std::sin(10 * float(M_PI) / 180), up = std::cos(10 * float(M_PI) / 180);
    for (int i = 0; i < plane.Size(); ++i) tilted.Add(plane.points[i], P3(lean, 0, up));
    for (int i = 0; i < plane.Size(); ++i) tilted.Add(plane.points[i], P3(-lean, 0, up));
    const ResamplingResult merged = gstest::Resample(tilted);
    gstest::ExpectValidResult(merged, tilted);
    EXPECT_EQ(merged.stats.coincidentPoints, 2 * plane.Size());
    for (const Surfel &s : merged.surfels) EXPECT_NEAR(s.normal[2], 1.f, 1e-6f); // the mean of up, +lean and -lean
}

// Fewer points than k: every point sees all others. (On a single row every point is a rim point,
// whose cluster is kept small as at creases: the crease angle is off here, and with it that limit.)
TEST(ResamplingInputs, FewerPointsThanK)
{
    gstest::PointSet s = gstest::PlaneGrid(5, 1, 0.1f);
    ResamplingParams p;
    p.neighborCount = 16;
    p.creaseAngle = 0;
    const ResamplingResult r = gstest::Resample(s, p);
    gstest::ExpectValidResult(r, s);
    EXPECT_EQ(r.surfels.size(), 1u); // one plane, depth 6 reaches all 5 points
    EXPECT_DOUBLE_EQ(r.stats.meanAdaptiveNeighbors, 4.0);
    // Two points are the minimum.
    gstest::PointSet two;
    two.Add(P3(0, 0, 0), P3(0, 0, 1));
    two.Add(P3(1, 0, 0), P3(0, 0, 1));
    gstest::ExpectValidResult(gstest::Resample(two, p), two);
}

// Two points whose normals differ too much to be neighbours: two singletons, two surfels.
TEST(ResamplingInputs, TwoIncompatiblePointsStaySeparate)
{
    gstest::PointSet s;
    s.Add(P3(0, 0, 0), P3(0, 0, 1));
    s.Add(P3(1, 0, 0), P3(1, 0, 0));
    const ResamplingResult r = gstest::Resample(s);
    EXPECT_EQ(r.surfels.size(), 2u);
    gstest::ExpectValidResult(r, s);
}

struct BadParam
{
    const char *what;
    void (*set)(ResamplingParams &);
    const char *needle; // the parameter's name as the message spells it
};

// Absurd parameters are rejected before any work, with a message naming the parameter.
TEST(ResamplingInputs, InvalidParametersAreRejectedByName)
{
    const BadParam cases[] = {
        {"level 0", [](ResamplingParams &p) { p.subdivisionLevel = 0; }, "SubdivisionLevel"},
        {"level 1", [](ResamplingParams &p) { p.subdivisionLevel = 1; }, "SubdivisionLevel"},
        {"level -3", [](ResamplingParams &p) { p.subdivisionLevel = -3; }, "SubdivisionLevel"},
        {"level 100000", [](ResamplingParams &p) { p.subdivisionLevel = 100000; }, "SubdivisionLevel"},
        {"k 0", [](ResamplingParams &p) { p.neighborCount = 0; }, "NeighborCount"},
        {"k 1000", [](ResamplingParams &p) { p.neighborCount = 1000; }, "NeighborCount"},
        {"k -1", [](ResamplingParams &p) { p.neighborCount = -1; }, "NeighborCount"},
        {"threshold 0.5", [](ResamplingParams &p) { p.normalizationThreshold = 0.5; }, "NormalizationThreshold"},
        {"threshold 1", [](ResamplingParams &p) { p.normalizationThreshold = 1.0; }, "NormalizationThreshold"},
        {"threshold NaN", [](ResamplingParams &p) { p.normalizationThreshold = kNaNd; }, "NormalizationThreshold"},
        {"depth -1", [](ResamplingParams &p) { p.propagationDepth = -1; }, "PropagationDepth"},
        {"iterations -1", [](ResamplingParams &p) { p.tuning.maxIterations = -1; }, "MaxIterations"},
        {"weight width -1", [](ResamplingParams &p) { p.weightWidth = -1; }, "WeightWidth"},
        {"weight width NaN", [](ResamplingParams &p) { p.weightWidth = kNaNd; }, "WeightWidth"},
        {"margin -1", [](ResamplingParams &p) { p.tuning.coverageMargin = -1; }, "margin"},
        {"margin NaN", [](ResamplingParams &p) { p.tuning.coverageMargin = kNaNd; }, "margin"},
    };
    const gstest::PointSet s = gstest::PlaneGrid(10, 10);
    for (const BadParam &c : cases) {
        SCOPED_TRACE(c.what);
        ResamplingParams p;
        c.set(p);
        EXPECT_FALSE(p.Validate().empty());
        ExpectInvalidArgument([&] { gstest::Resample(s, p); }, c.needle);
    }
    // The limits themselves are valid.
    for (auto set : {+[](ResamplingParams &p) { p.subdivisionLevel = 2; },
                     +[](ResamplingParams &p) { p.subdivisionLevel = 256; },
                     +[](ResamplingParams &p) { p.neighborCount = 1; },
                     +[](ResamplingParams &p) { p.neighborCount = 255; },
                     +[](ResamplingParams &p) { p.propagationDepth = 0; },
                     +[](ResamplingParams &p) { p.tuning.maxIterations = 0; },
                     +[](ResamplingParams &p) { p.normalizationThreshold = 1.0001; }}) {
        ResamplingParams p;
        set(p);
        EXPECT_EQ(p.Validate(), "");
        gstest::ExpectValidResult(gstest::Resample(s, p), s);
    }
    EXPECT_EQ(ResamplingParams().Validate(), "") << "the defaults are valid";
}

// Cancellation: a callback returning false stops the run with ResamplingCancelled, at
// whichever stage it happens. A callback returning true sees progress up to 100.
int gCallsUntilCancel = 0;
int gLastPercent = -1;
bool CancelAfterSomeCalls(int percent, const char *)
{
    gLastPercent = percent;
    return --gCallsUntilCancel > 0;
}

TEST(ResamplingInputs, CallbackReturningFalseCancels)
{
    const gstest::PointSet s = gstest::FibonacciSphere(2000);
    OrientedPointMesh m;
    gstest::ToMesh(s, m);
    for (int calls : {1, 2, 3, 4}) {
        gCallsUntilCancel = calls;
        EXPECT_THROW(ResamplePointSet(m, ResamplingParams(), CancelAfterSomeCalls), ResamplingCancelled)
            << "cancel at call " << calls;
    }
    gCallsUntilCancel = 1000000;
    const ResamplingResult r = ResamplePointSet(m, ResamplingParams(), CancelAfterSomeCalls);
    EXPECT_EQ(gLastPercent, 100);
    gstest::ExpectValidResult(r, s);
}

// Long stages report between their steps, and a cancel there stops the run. The callback is
// a plain function pointer: the stage and the report to cancel at are globals.
const char *gCancelStage = "";
int gCancelAtReport = 0, gStageReports = 0;
bool CancelAtNthStageReport(int, const char *what)
{
    return std::string(what).find(gCancelStage) == std::string::npos || ++gStageReports < gCancelAtReport;
}

/// Resamples a sphere, cancelling at report `n` of the stage named `stage`; expects the run to be
/// cancelled and returns how many of that stage's reports came.
int StageReportsUntilCancelled(const char *stage, int n, const ResamplingParams &param = ResamplingParams())
{
    const gstest::PointSet s = gstest::FibonacciSphere(2000);
    OrientedPointMesh m;
    gstest::ToMesh(s, m);
    gCancelStage = stage;
    gCancelAtReport = n;
    gStageReports = 0;
    EXPECT_THROW(ResamplePointSet(m, param, CancelAtNthStageReport), ResamplingCancelled);
    return gStageReports;
}

// Cluster normalization runs for seconds on tens of millions of points: it reports after each
// pass, not only when it starts.
TEST(ResamplingInputs, CancelDuringClusterNormalization)
{
    EXPECT_EQ(StageReportsUntilCancelled("cluster normalization", 2), 2);
}

// The spatial sort before the neighbour search reports between its stages too.
TEST(ResamplingInputs, CancelDuringTheSpatialSort)
{
    EXPECT_EQ(StageReportsUntilCancelled("sorting the points", 3), 3);
}

// Below level 2's count, the merges to the target report between their steps and cancel.
TEST(ResamplingInputs, CancelWhileMergingToATargetSize)
{
    ResamplingParams param;
    param.targetCount = 20;
    EXPECT_EQ(StageReportsUntilCancelled("merging clusters", 2, param), 2);
}

// Between two levels' counts, the splits to the target report (when they start, then every few
// thousand splits) and cancel too.
TEST(ResamplingInputs, CancelWhileSplittingToATargetSize)
{
    ResamplingParams param;
    param.targetCount = 150; // level 3, then 62 splits
    EXPECT_EQ(StageReportsUntilCancelled("splitting clusters", 1, param), 1);
}

} // namespace
