// Boundary points (boundary_points.h): the rim of an open surface is found, a closed one has
// none, and SpreadEvenly leaves the surfels along the rim unfitted.
#include <gtest/gtest.h>

#include <cmath>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>
#include <vcg_ext/gaussphere/neighbors/boundary_points.h>
#include <vcg_ext/gaussphere/neighbors/point_grid.h>

#include "pipeline_support.h"

using namespace vcg::gaussphere;

namespace {

NeighborGraph GraphOf(const gstest::PointSet &s)
{
    const PointGrid grid(s.points);
    AdaptiveNeighborParams param;
    param.boundaryGapDegrees = kBoundaryGapDegrees;
    return BuildAdaptiveNeighbors(s.points, s.normals, param, grid);
}

/// A hemisphere (z >= 0) of radius 1 on a latitude-longitude lattice: open along the equator.
gstest::PointSet Hemisphere(int rings)
{
    gstest::PointSet s;
    s.Add(gstest::P3(0, 0, 1), gstest::P3(0, 0, 1));
    for (int r = 1; r <= rings; ++r) {
        const double polar = 0.5 * gstest::kPi * r / rings;
        const int around = 6 * r;
        for (int t = 0; t < around; ++t) {
            const double a = 2 * gstest::kPi * t / around;
            const gstest::P3 d(float(std::sin(polar) * std::cos(a)), float(std::sin(polar) * std::sin(a)),
                               float(std::cos(polar)));
            s.Add(d, d, r == rings ? 1 : 0); // tag 1: the rim
        }
    }
    return s;
}

} // namespace

/// Unit directions at the given angles (radians), scaled by 1 to 3 so that lengths play no part.
std::vector<TangentDirection> Directions(const std::vector<double> &angles)
{
    std::vector<TangentDirection> d;
    for (size_t t = 0; t < angles.size(); ++t)
        d.emplace_back((1 + t % 3) * std::cos(angles[t]), (1 + t % 3) * std::sin(angles[t]));
    return d;
}

TEST(BoundaryPoints, GapTestCountsTheWrapAround)
{
    std::vector<TangentDirection> around = Directions({5.7, 0.1, 4.3, 1.5, 2.9}); // gaps below 90 degrees
    EXPECT_FALSE(GapExceeds(around, 90));
    std::vector<TangentDirection> oneSide = Directions({-0.5, 0.0, 0.5, 1.0}); // the wrap-around gap: 274 degrees
    EXPECT_TRUE(GapExceeds(oneSide, 90));
    EXPECT_TRUE(GapExceeds(oneSide, 179));
    std::vector<TangentDirection> wide = Directions({0.0, 1.0, 2.0, 3.0, 4.0}); // the wrap-around gap: 131 degrees
    EXPECT_TRUE(GapExceeds(wide, 90));
    EXPECT_FALSE(GapExceeds(wide, 150));
    std::vector<TangentDirection> none, one = Directions({2.0}), same = Directions({1.0, 1.0, 1.0});
    EXPECT_TRUE(GapExceeds(none, 90));
    EXPECT_TRUE(GapExceeds(one, 90));
    EXPECT_TRUE(GapExceeds(same, 90)) << "one direction thrice leaves a full turn";
}

TEST(BoundaryPoints, GapTestMatchesTheAnglesEitherSideOfTheLimit)
{
    // Directions every 10 degrees over an arc, leaving a gap of 360 - arc: just above and just
    // below the limit, in every quadrant the arc may start from.
    for (int start = 0; start < 360; start += 15) {
        for (const double gap : {145.0, 149.0, 151.0, 155.0, 185.0}) {
            std::vector<double> angles;
            for (double a = 0; a <= 360 - gap + 1e-9; a += (360 - gap) / 20)
                angles.push_back((start + a) * gstest::kPi / 180);
            std::vector<TangentDirection> d = Directions(angles);
            EXPECT_EQ(GapExceeds(d, kBoundaryGapDegrees), gap > kBoundaryGapDegrees)
                << "gap " << gap << " from " << start << " degrees";
        }
    }
}

TEST(BoundaryPoints, FindsTheRimOfAPlaneAndNoneOnASphere)
{
    const gstest::PointSet plane = gstest::PlaneGrid(12, 9);
    const FlatVector<char> flags = GraphOf(plane).boundary;
    for (int i = 0; i < plane.Size(); ++i) {
        const int x = i % 12, y = i / 12;
        const bool rim = x == 0 || y == 0 || x == 11 || y == 8;
        EXPECT_EQ(flags[i] != 0, rim) << "point (" << x << ", " << y << ")";
    }
    const gstest::PointSet sphere = gstest::FibonacciSphere(2000);
    const FlatVector<char> none = GraphOf(sphere).boundary;
    ASSERT_EQ(int(none.size()), sphere.Size());
    EXPECT_EQ(std::count(none.begin(), none.end(), char(1)), 0);
}

TEST(BoundaryPoints, TheBandHoldsTheRimAndItsNeighbours)
{
    const gstest::PointSet plane = gstest::PlaneGrid(12, 9);
    const NeighborGraph graph = GraphOf(plane);
    const FlatVector<char> &rim = graph.boundary;
    const FlatVector<char> band = BoundaryBand(graph, rim);
    for (int i = 0; i < plane.Size(); ++i) {
        const int x = i % 12, y = i / 12;
        const int fromEdge = std::min(std::min(x, 11 - x), std::min(y, 8 - y));
        if (rim[i]) EXPECT_TRUE(band[i]);
        if (fromEdge == 1) EXPECT_TRUE(band[i]) << "next to the rim: (" << x << ", " << y << ")";
        if (fromEdge >= 3) EXPECT_FALSE(band[i]) << "inside: (" << x << ", " << y << ")";
    }
}

TEST(BoundaryPoints, SpreadEvenlyLeavesTheSurfelsAlongTheRimUnfitted)
{
    const gstest::PointSet s = Hemisphere(30);
    ResamplingParams p;
    p.spreadEvenly = true;
    p.targetCount = 400;
    const ResamplingResult r = gstest::Resample(s, p);
    ASSERT_EQ(int(r.surfels.size()), 400);
    EXPECT_GT(r.stats.boundaryPoints, 180); // the 180 rim points and their band
    int rimSurfels = 0, fittedInside = 0;
    std::vector<bool> atRim(r.surfels.size(), false);
    for (int i = 0; i < s.Size(); ++i)
        if (s.tag[i] == 1) atRim[size_t(r.representative[i])] = true;
    for (size_t c = 0; c < r.surfels.size(); ++c) {
        if (atRim[c]) {
            ++rimSurfels;
            EXPECT_EQ(r.surfels[c].fitOffset, 0.f) << "surfel " << c << " holds a rim point";
        } else {
            fittedInside += r.surfels[c].fitOffset != 0;
        }
    }
    EXPECT_GT(rimSurfels, 20);
    EXPECT_GT(fittedInside, 100); // the fit still runs away from the rim
}
