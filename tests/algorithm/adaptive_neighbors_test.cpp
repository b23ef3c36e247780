// BuildAdaptiveNeighbors: the k nearest neighbours filtered by the cone of normals
// <n_p, n_q> >= 1 - d_max^2 / 2 (paper, section 3.2.1), and the local spacing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>
#include <vcg_ext/gaussphere/clustering/gaussian_sphere.h>

#include "test_support.h"

namespace {

using namespace vcg::gaussphere;
using gstest::P3;

NeighborGraph Build(const gstest::PointSet &s, int k, double chord)
{
    const PointGrid tree(s.points);
    AdaptiveNeighborParams p;
    p.k = k;
    p.coneChord = chord;
    return BuildAdaptiveNeighbors(s.points, s.normals, p, tree);
}

/// Random points in a unit cube with random unit normals all within ~60 degrees of +z,
/// so that the cone test keeps some neighbours and drops others.
gstest::PointSet RandomOrientedPoints(int n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    gstest::PointSet s;
    for (int i = 0; i < n; ++i) {
        P3 nrm(u(rng), u(rng), 1.f);
        s.Add(P3(u(rng), u(rng), u(rng)), nrm / nrm.Norm());
    }
    return s;
}

// The graph is exactly: the k nearest (brute force, no ties with random floats) in
// ascending distance order, keeping those with dot >= 1 - chord^2/2.
TEST(AdaptiveNeighbors, KeepsExactlyTheKNearestInsideTheCone)
{
    const gstest::PointSet s = RandomOrientedPoints(1500, 11);
    const int k = 16;
    const double chord = GaussianSphere::PaperMaxEdgeLength(8);
    const NeighborGraph g = Build(s, k, chord);
    ASSERT_EQ(g.Size(), s.Size());
    ASSERT_EQ(g.stride, k);
    const float minDot = float(1.0 - 0.5 * chord * chord);
    long long kept = 0, dropped = 0;
    for (int i = 0; i < s.Size(); ++i) {
        std::vector<std::pair<float, int>> all;
        for (int j = 0; j < s.Size(); ++j)
            if (j != i) all.push_back({(s.points[j] - s.points[i]).SquaredNorm(), j});
        std::partial_sort(all.begin(), all.begin() + k, all.end());
        std::vector<int> expected;
        for (int t = 0; t < k; ++t) {
            if (s.normals[i].dot(s.normals[all[t].second]) >= minDot) expected.push_back(all[t].second);
            else ++dropped;
        }
        const std::vector<int> got(g.begin(i), g.end(i));
        ASSERT_EQ(got, expected) << "point " << i;
        kept += got.size();
    }
    // The data must exercise both outcomes of the cone test, or the test proves nothing.
    EXPECT_GT(kept, 1000);
    EXPECT_GT(dropped, 1000);
}

// On a plane all normals agree, so every one of the k nearest is kept.
TEST(AdaptiveNeighbors, PlaneKeepsAllKNeighbours)
{
    const gstest::PointSet s = gstest::PlaneGrid(20, 20, 0.1f);
    const NeighborGraph g = Build(s, 16, 0.42);
    for (int i = 0; i < s.Size(); ++i) EXPECT_EQ(int(g.count[i]), 16) << "point " << i;
}

// An L-shaped fold: the floor z = 0 (normal +z) meets the wall x = 0 (normal -x) at a
// sharp 90-degree edge. The normals differ by a chord of sqrt(2) >> d_max, so no point
// keeps a neighbour from the other side, although many are among its k nearest.
TEST(AdaptiveNeighbors, SharpEdgeSeparatesTheTwoSides)
{
    gstest::PointSet s;
    const float h = 0.1f;
    for (int y = 0; y < 15; ++y)
        for (int t = 1; t <= 10; ++t) {
            s.Add(P3(t * h, y * h, 0), P3(0, 0, 1), 0);   // floor
            s.Add(P3(0, y * h, t * h), P3(-1, 0, 0), 1);  // wall
        }
    const NeighborGraph g = Build(s, 16, GaussianSphere::PaperMaxEdgeLength(8));
    int crossingInKnn = 0;
    for (int i = 0; i < s.Size(); ++i) {
        for (const int *q = g.begin(i); q != g.end(i); ++q) EXPECT_EQ(s.tag[*q], s.tag[i]) << i << " -> " << *q;
        std::vector<std::pair<float, int>> nearest; // the 16 nearest by (distance, index)
        for (int j = 0; j < s.Size(); ++j)
            if (j != i) nearest.push_back({(s.points[j] - s.points[i]).SquaredNorm(), j});
        std::partial_sort(nearest.begin(), nearest.begin() + 16, nearest.end());
        int sameSide = 0;
        for (int t = 0; t < 16; ++t) {
            crossingInKnn += s.tag[nearest[t].second] != s.tag[i];
            sameSide += s.tag[nearest[t].second] == s.tag[i];
        }
        EXPECT_EQ(int(g.count[i]), sameSide) << "every same-side k-NN neighbour is kept";
    }
    EXPECT_GT(crossingInKnn, 100) << "the fixture must put other-side points among the k nearest";
}

// Spacing: the mean distance to the 6 nearest. On a square grid of spacing h an interior
// point has 4 neighbours at h and 4 at h sqrt 2, so spacing = (4 + 2 sqrt 2) / 6 h ~ 1.14 h.
TEST(AdaptiveNeighbors, SpacingOnARegularGrid)
{
    const float h = 0.05f;
    const gstest::PointSet s = gstest::PlaneGrid(30, 30, h);
    const NeighborGraph g = Build(s, 16, 0.42);
    const double expected = (4 + 2 * std::sqrt(2.0)) / 6 * h;
    for (int y = 2; y < 28; ++y)
        for (int x = 2; x < 28; ++x) EXPECT_NEAR(g.spacing[y * 30 + x], expected, 1e-5) << x << "," << y;
    for (int i = 0; i < s.Size(); ++i) {
        EXPECT_GE(g.spacing[i], h * 0.999f);   // nothing is closer than h
        EXPECT_LE(g.spacing[i], 1.62f * h);    // worst, a corner: (h + h + h sqrt2 + 2h + 2h + h sqrt5) / 6
    }
}

// Coincident neighbours do not count towards the spacing: with every grid point three
// times, the six nearest at a non-zero distance of an interior point are all at h.
TEST(AdaptiveNeighbors, SpacingIgnoresCoincidentNeighbours)
{
    const float h = 0.25f;
    const gstest::PointSet grid = gstest::PlaneGrid(12, 12, h);
    gstest::PointSet s;
    for (int i = 0; i < grid.Size(); ++i)
        for (int c = 0; c < 3; ++c) s.Add(grid.points[i], grid.normals[i]);
    const NeighborGraph g = Build(s, 16, 0.42);
    for (int y = 2; y < 10; ++y)
        for (int x = 2; x < 10; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(g.spacing[3 * (y * 12 + x) + c], h) << x << "," << y;
    for (float sp : g.spacing) EXPECT_GT(sp, 0.f);
}

// A point whose k nearest all coincide with it has no spacing of its own: it gets the
// median of the others'; when all points coincide there is no scale and 1e-3 is used.
TEST(AdaptiveNeighbors, SpacingOfFullyCoincidentPointsFallsBack)
{
    gstest::PointSet s = gstest::PlaneGrid(10, 10, 0.5f);
    for (int c = 0; c < 40; ++c) s.Add(P3(20, 20, 20), P3(0, 0, 1));
    const NeighborGraph g = Build(s, 16, 0.42);
    std::vector<float> grid(g.spacing.begin(), g.spacing.begin() + 100);
    std::nth_element(grid.begin(), grid.begin() + 50, grid.end());
    for (int i = 100; i < s.Size(); ++i) EXPECT_EQ(g.spacing[i], grid[50]) << i;

    gstest::PointSet same;
    for (int c = 0; c < 40; ++c) same.Add(P3(1, 2, 3), P3(0, 0, 1));
    for (float sp : Build(same, 16, 0.42).spacing) EXPECT_FLOAT_EQ(sp, 1e-3f);
}

// Fewer points than k: every other point is examined (stride clamps to N - 1).
TEST(AdaptiveNeighbors, FewerPointsThanK)
{
    const gstest::PointSet s = gstest::PlaneGrid(5, 1, 1.f);
    const NeighborGraph g = Build(s, 16, 0.42);
    EXPECT_EQ(g.stride, 4);
    for (int i = 0; i < 5; ++i) {
        EXPECT_EQ(int(g.count[i]), 4);
        for (const int *q = g.begin(i); q != g.end(i); ++q) EXPECT_NE(*q, i) << "a point is not its own neighbour";
    }
    // Spacing of the end point 0: distances 1, 2, 3, 4 (only 4 neighbours exist).
    EXPECT_FLOAT_EQ(g.spacing[0], 2.5f);
}

TEST(AdaptiveNeighbors, IndependentOfThreadCount)
{
    const gstest::PointSet s = RandomOrientedPoints(6000, 12);
    NeighborGraph one, two;
    {
        gstest::ScopedThreadCount t(1);
        one = Build(s, 16, 0.42);
    }
    {
        gstest::ScopedThreadCount t(2);
        two = Build(s, 16, 0.42);
    }
    EXPECT_EQ(one.count, two.count);
    EXPECT_EQ(one.adjacency, two.adjacency);
    EXPECT_EQ(one.spacing, two.spacing);
}

// KeepFirstSlots leaves the first slots of every row, and found and count capped to them, in a
// buffer of exactly that size (the full one is freed), for strides cut by a factor 16, 2, 9/8
// and 3/2, on 1 and 3 threads.
TEST(AdaptiveNeighbors, KeepFirstSlotsKeepsEachRowsFirstSlots)
{
    const gstest::PointSet s = RandomOrientedPoints(70000, 5);
    for (int threads : {1, 3})
        for (const auto &cut : {std::make_pair(16, 1), std::make_pair(16, 8), std::make_pair(9, 8), std::make_pair(3, 2)}) {
            gstest::ScopedThreadCount t(threads);
            NeighborGraph g = Build(s, cut.first, 0.42);
            ASSERT_EQ(g.stride, cut.first);
            std::vector<int> expected;
            std::vector<std::uint8_t> found, count;
            for (int i = 0; i < g.Size(); ++i) {
                expected.insert(expected.end(), g.begin(i), g.begin(i) + cut.second);
                found.push_back(std::uint8_t(std::min<int>(g.found[i], cut.second)));
                count.push_back(std::uint8_t(std::min<int>(g.count[i], cut.second)));
            }
            KeepFirstSlots(g, cut.second);
            EXPECT_EQ(g.stride, cut.second);
            EXPECT_EQ(g.adjacency.capacity(), expected.size());
            EXPECT_TRUE(std::equal(expected.begin(), expected.end(), g.adjacency.begin(), g.adjacency.end()))
                << cut.first << " -> " << cut.second << " slots, " << threads << " threads";
            EXPECT_TRUE(std::equal(found.begin(), found.end(), g.found.begin(), g.found.end()));
            EXPECT_TRUE(std::equal(count.begin(), count.end(), g.count.begin(), g.count.end()));
        }
}

} // namespace
