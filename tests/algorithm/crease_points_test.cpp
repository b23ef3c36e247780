// Crease points, as the neighbour search marks them (NeighborGraph::crease): a point is at a
// crease when one of its k nearest has a normal turned by more than the crease angle and less
// than 120 degrees (opposite sheets are not creases).
#include <gtest/gtest.h>

#include <cmath>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>

#include "test_support.h"

namespace {

using namespace vcg::gaussphere;
using gstest::P3;

/// Two 20 x 20 grids with spacing 0.1 meeting along the line x = 0 (z = 0): one in the
/// plane z = 0 (x >= 0, normal +z), one folded up by `foldDegrees` about that line.
gstest::PointSet Fold(double foldDegrees)
{
    const double a = foldDegrees * std::acos(-1.0) / 180.0;
    gstest::PointSet s;
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 20; ++j) {
            s.Add(P3(0.05f + 0.1f * i, 0.1f * j, 0.f), P3(0, 0, 1));
            const float r = 0.05f + 0.1f * i;
            s.Add(P3(float(-r * std::cos(a)), 0.1f * j, float(r * std::sin(a))),
                  P3(float(std::sin(a)), 0.f, float(std::cos(a))));
        }
    return s;
}

FlatVector<char> Mark(const gstest::PointSet &s, double angle)
{
    const PointGrid grid(s.points);
    AdaptiveNeighborParams p;
    p.k = 16;
    p.creaseAngle = angle;
    return BuildAdaptiveNeighbors(s.points, s.normals, p, grid).crease;
}

/// Distance of point i from the fold line (the y axis).
float FromFold(const gstest::PointSet &s, int i) { return std::hypot(s.points[i][0], s.points[i][2]); }

TEST(CreasePoints, SharpFoldMarksTheBandAlongTheEdgeOnly)
{
    const gstest::PointSet s = Fold(90);
    const FlatVector<char> crease = Mark(s, 45);
    int marked = 0;
    for (int i = 0; i < s.Size(); ++i) {
        if (FromFold(s, i) < 0.1f) EXPECT_TRUE(crease[i]) << "point " << i << " next to the edge";
        if (FromFold(s, i) > 0.45f) EXPECT_FALSE(crease[i]) << "point " << i << " far from the edge";
        marked += crease[i];
    }
    EXPECT_GT(marked, 0);
}

TEST(CreasePoints, NoMarksWithoutACreaseAngle)
{
    const gstest::PointSet s = Fold(90);
    const PointGrid grid(s.points);
    EXPECT_TRUE(BuildAdaptiveNeighbors(s.points, s.normals, AdaptiveNeighborParams(), grid).crease.empty());
}

TEST(CreasePoints, GentleFoldIsNoCrease)
{
    const gstest::PointSet s = Fold(30);
    const FlatVector<char> crease = Mark(s, 45);
    for (int i = 0; i < s.Size(); ++i) EXPECT_FALSE(crease[i]) << "point " << i;
    // The same fold is a crease for a smaller angle.
    const FlatVector<char> fine = Mark(s, 20);
    EXPECT_TRUE(fine[0]) << "the points next to the edge turn by 30 degrees";
}

TEST(CreasePoints, OppositeSheetsOfAThinPartAreNoCrease)
{
    gstest::PointSet s;
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 20; ++j) {
            s.Add(P3(0.1f * i, 0.1f * j, 0.f), P3(0, 0, -1));
            s.Add(P3(0.1f * i, 0.1f * j, 0.02f), P3(0, 0, 1));
        }
    const FlatVector<char> crease = Mark(s, 45);
    for (int i = 0; i < s.Size(); ++i) EXPECT_FALSE(crease[i]) << "point " << i;
}

} // namespace
