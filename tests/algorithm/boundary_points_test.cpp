// Boundary points (boundary_points.h): the rim of an open surface is found, a closed one has
// none, and SpreadEvenly leaves the surfels along the rim unfitted.
#include <gtest/gtest.h>

#include <cmath>

#include <vcg_ext/gaussphere/neighbors/boundary_points.h>
#include <vcg_ext/gaussphere/neighbors/point_grid.h>

#include "pipeline_support.h"

using namespace vcg::gaussphere;

namespace {

NeighborGraph GraphOf(const gstest::PointSet &s)
{
    const PointGrid grid(s.points);
    return BuildAdaptiveNeighbors(s.points, s.normals, AdaptiveNeighborParams(), grid);
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

TEST(BoundaryPoints, GapTestCountsTheWrapAround)
{
    const double quarter = gstest::kPi / 2;
    std::vector<double> around = {5.7, 0.1, 4.3, 1.5, 2.9}; // gaps below a quarter turn, wrap-around included
    EXPECT_FALSE(GapExceeds(around, quarter));
    std::vector<double> oneSide = {-0.5, 0.0, 0.5, 1.0}; // the wrap-around gap is 4.8 rad
    EXPECT_TRUE(GapExceeds(oneSide, quarter));
    std::vector<double> none;
    EXPECT_TRUE(GapExceeds(none, quarter));
}

TEST(BoundaryPoints, FindsTheRimOfAPlaneAndNoneOnASphere)
{
    const gstest::PointSet plane = gstest::PlaneGrid(12, 9);
    const FlatVector<char> flags = BoundaryPoints(plane.points, plane.normals, GraphOf(plane));
    for (int i = 0; i < plane.Size(); ++i) {
        const int x = i % 12, y = i / 12;
        const bool rim = x == 0 || y == 0 || x == 11 || y == 8;
        EXPECT_EQ(flags[i] != 0, rim) << "point (" << x << ", " << y << ")";
    }
    const gstest::PointSet sphere = gstest::FibonacciSphere(2000);
    const FlatVector<char> none = BoundaryPoints(sphere.points, sphere.normals, GraphOf(sphere));
    EXPECT_EQ(std::count(none.begin(), none.end(), char(1)), 0);
}

TEST(BoundaryPoints, TheBandHoldsTheRimAndItsNeighbours)
{
    const gstest::PointSet plane = gstest::PlaneGrid(12, 9);
    const NeighborGraph graph = GraphOf(plane);
    const FlatVector<char> rim = BoundaryPoints(plane.points, plane.normals, graph);
    const FlatVector<char> band = BoundaryBand(plane.points, plane.normals, graph);
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
