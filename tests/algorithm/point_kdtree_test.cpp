// PointKdTree::KNearest against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include <vcg_ext/gaussphere/neighbors/point_kdtree.h>

#include "test_support.h"

namespace {

using vcg::gaussphere::PointKdTree;
using gstest::P3;
using gstest::PointArray;

struct Neighbor { float d2; int index; };

/// The k nearest by brute force, sorted by (distance, index).
std::vector<Neighbor> BruteForce(const PointArray &pts, const P3 &q, int k, int exclude)
{
    std::vector<Neighbor> all;
    for (int i = 0; i < int(pts.size()); ++i)
        if (i != exclude) all.push_back({(pts[i] - q).SquaredNorm(), i});
    std::sort(all.begin(), all.end(), [](const Neighbor &a, const Neighbor &b) {
        return a.d2 < b.d2 || (a.d2 == b.d2 && a.index < b.index);
    });
    all.resize(std::min<size_t>(all.size(), size_t(std::max(k, 0))));
    return all;
}

/// Checks one query: same count as brute force, ascending distances equal to brute force's
/// (ties may pick different indices), each reported distance is the true distance of the
/// reported index, no index twice, `exclude` never reported.
void ExpectMatchesBruteForce(const PointKdTree &tree, const PointArray &pts, const P3 &q, int k, int exclude)
{
    const std::vector<Neighbor> expected = BruteForce(pts, q, k, exclude);
    std::vector<int> idx(std::max(k, 1), -7);
    std::vector<float> d2(std::max(k, 1), -7.f);
    const int found = tree.KNearest(q, k, exclude, idx.data(), d2.data());
    ASSERT_EQ(found, int(expected.size())) << "k=" << k << " exclude=" << exclude;
    std::vector<int> seen;
    for (int t = 0; t < found; ++t) {
        ASSERT_GE(idx[t], 0);
        ASSERT_LT(idx[t], int(pts.size()));
        EXPECT_NE(idx[t], exclude);
        EXPECT_EQ(d2[t], (pts[idx[t]] - q).SquaredNorm()) << "distance does not belong to index " << idx[t];
        EXPECT_EQ(d2[t], expected[t].d2) << "rank " << t << " of k=" << k;
        if (t > 0) EXPECT_LE(d2[t - 1], d2[t]) << "not sorted ascending";
        seen.push_back(idx[t]);
    }
    std::sort(seen.begin(), seen.end());
    EXPECT_TRUE(std::adjacent_find(seen.begin(), seen.end()) == seen.end()) << "an index was reported twice";
}

PointArray RandomPoints(int n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    PointArray pts(n);
    for (P3 &p : pts) p = P3(u(rng), u(rng), u(rng));
    return pts;
}

TEST(PointKdTree, RandomPointsMatchBruteForce)
{
    const PointArray pts = RandomPoints(3000, 1);
    const PointKdTree tree(pts);
    EXPECT_EQ(tree.Size(), 3000);
    std::mt19937 rng(2);
    std::uniform_int_distribution<int> pick(0, 2999);
    for (int q = 0; q < 200; ++q) {
        const int i = pick(rng);
        ExpectMatchesBruteForce(tree, pts, pts[i], 16, i);       // the resampler's query
        ExpectMatchesBruteForce(tree, pts, pts[i], 7, -1);       // keeps the point itself
        ExpectMatchesBruteForce(tree, pts, pts[i] + P3(0.01f, -0.02f, 0.005f), 1, -1);
    }
    // Queries far outside the cloud.
    ExpectMatchesBruteForce(tree, pts, P3(10, 10, 10), 20, -1);
    ExpectMatchesBruteForce(tree, pts, P3(-5, 0, 0), 3, 17);
}

TEST(PointKdTree, QueryPointItselfComesFirstWhenNotExcluded)
{
    const PointArray pts = RandomPoints(500, 3);
    const PointKdTree tree(pts);
    int idx[4];
    float d2[4];
    for (int i = 0; i < 500; i += 37) {
        ASSERT_EQ(tree.KNearest(pts[i], 4, -1, idx, d2), 4);
        EXPECT_EQ(idx[0], i);
        EXPECT_EQ(d2[0], 0.f);
    }
}

// Duplicates: every point three times, plus 40 copies of one point (a leaf that cannot
// be split). Distances must still match brute force, and exclusion only drops the index.
TEST(PointKdTree, DuplicatePointsMatchBruteForce)
{
    PointArray pts;
    for (const P3 &p : RandomPoints(400, 4))
        for (int c = 0; c < 3; ++c) pts.push_back(p);
    for (int c = 0; c < 40; ++c) pts.push_back(P3(0.25f, 0.25f, 0.25f));
    const PointKdTree tree(pts, 8);
    for (int i = 0; i < int(pts.size()); i += 7) {
        ExpectMatchesBruteForce(tree, pts, pts[i], 16, i);
        ExpectMatchesBruteForce(tree, pts, pts[i], 2, i); // both other copies at distance 0
    }
    // A query at the 40-fold point: the 16 nearest are all copies at distance 0.
    int idx[16];
    float d2[16];
    ASSERT_EQ(tree.KNearest(P3(0.25f, 0.25f, 0.25f), 16, int(pts.size()) - 1, idx, d2), 16);
    for (int t = 0; t < 16; ++t) {
        EXPECT_EQ(d2[t], 0.f);
        EXPECT_GE(idx[t], 1200);
        EXPECT_NE(idx[t], int(pts.size()) - 1);
    }
}

TEST(PointKdTree, AllPointsIdentical)
{
    const PointArray pts(50, P3(1, 2, 3));
    const PointKdTree tree(pts);
    for (int i = 0; i < 50; i += 5) ExpectMatchesBruteForce(tree, pts, pts[i], 16, i);
}

// k larger than the cloud: all points come back (one fewer when one is excluded).
TEST(PointKdTree, KLargerThanPointCount)
{
    const PointArray pts = RandomPoints(5, 5);
    const PointKdTree tree(pts);
    ExpectMatchesBruteForce(tree, pts, pts[0], 16, -1);
    ExpectMatchesBruteForce(tree, pts, pts[0], 16, 0);
    ExpectMatchesBruteForce(tree, pts, P3(3, 3, 3), 100, 2);
    int idx[16];
    float d2[16];
    EXPECT_EQ(tree.KNearest(pts[0], 16, 0, idx, d2), 4);
    EXPECT_EQ(tree.KNearest(pts[0], 16, -1, idx, d2), 5);
}

TEST(PointKdTree, DegenerateSizes)
{
    int idx[4] = {-7, -7, -7, -7};
    float d2[4];
    const PointKdTree empty(PointArray{});
    EXPECT_EQ(empty.Size(), 0);
    EXPECT_EQ(empty.KNearest(P3(0, 0, 0), 4, -1, idx, d2), 0);
    const PointKdTree one(PointArray{P3(1, 1, 1)});
    EXPECT_EQ(one.KNearest(P3(0, 0, 0), 4, -1, idx, d2), 1);
    EXPECT_EQ(idx[0], 0);
    EXPECT_FLOAT_EQ(d2[0], 3.f);
    EXPECT_EQ(one.KNearest(P3(0, 0, 0), 4, 0, idx, d2), 0);
    EXPECT_EQ(one.KNearest(P3(0, 0, 0), 0, -1, idx, d2), 0); // k = 0 asks for nothing
}

// Structured input with many equal coordinates (a planar grid: equal split values on
// two axes and a zero extent on the third).
TEST(PointKdTree, PlanarGridMatchesBruteForce)
{
    const PointArray pts = gstest::PlaneGrid(40, 25, 0.5f).points;
    for (int leaf : {1, 3, 12, 64}) {
        const PointKdTree tree(pts, leaf);
        for (int i = 0; i < int(pts.size()); i += 23) ExpectMatchesBruteForce(tree, pts, pts[i], 16, i);
    }
}

TEST(PointKdTree, LeafOrderIsAPermutation)
{
    const PointKdTree tree(RandomPoints(1000, 6));
    std::vector<int> order = tree.LeafOrder();
    ASSERT_EQ(order.size(), 1000u);
    std::sort(order.begin(), order.end());
    for (int i = 0; i < 1000; ++i) ASSERT_EQ(order[i], i);
}

} // namespace
