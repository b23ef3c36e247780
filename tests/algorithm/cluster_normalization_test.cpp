// SplitElongatedClusters (paper, section 3.4): a cluster with lambda1 / lambda2 above the
// threshold is cut by the plane through its centroid perpendicular to its major axis.
//
// Known answers: for an a x b grid of unit spacing the coordinate variances are
// (a^2 - 1) / 12 and (b^2 - 1) / 12, so lambda1 / lambda2 = (a^2 - 1) / (b^2 - 1).
#include <gtest/gtest.h>

#include <random>

#include <vcg_ext/gaussphere/clustering/cluster_normalization.h>

#include "test_support.h"

namespace {

using namespace vcg::gaussphere;
using gstest::P3;
using gstest::PointArray;
using gstest::IndexArray;

Clustering OneCluster(int n)
{
    Clustering c;
    c.label.assign(n, 0);
    c.clusterCount = 1;
    return c;
}

ClusterNormalizationParams NormalizationParams(double threshold = 6.0, int minSplitSize = 6)
{
    ClusterNormalizationParams p;
    p.threshold = threshold;
    p.minSplitSize = minSplitSize;
    return p;
}

/// Splits one grid-shaped cluster and checks the cut: either no split, or two halves
/// separated at the centroid along x (the long axis).
void ExpectGridSplit(int a, int b, double threshold, bool expectSplit)
{
    const gstest::PointSet s = gstest::PlaneGrid(a, b);
    Clustering c = OneCluster(s.Size());
    const int split = SplitElongatedClusters(s.points, NormalizationParams(threshold), c);
    SCOPED_TRACE(testing::Message() << a << " x " << b << ", ratio " << (a * a - 1.0) / (b * b - 1.0)
                                    << ", threshold " << threshold);
    if (!expectSplit) {
        EXPECT_EQ(split, 0);
        EXPECT_EQ(c.clusterCount, 1);
        for (int l : c.label) EXPECT_EQ(l, 0);
        return;
    }
    EXPECT_EQ(split, 1);
    ASSERT_EQ(c.clusterCount, 2);
    const float cx = (a - 1) / 2.f;
    int low = -1, high = -1;
    for (int i = 0; i < s.Size(); ++i) {
        const float x = s.points[i][0];
        if (x == cx) continue; // on the plane: either side is acceptable
        int &side = x < cx ? low : high;
        if (side < 0) side = c.label[i];
        EXPECT_EQ(c.label[i], side) << "point at x = " << x << " is on the wrong side of the cut";
    }
    EXPECT_NE(low, high);
}

TEST(ClusterNormalization, LongStripIsSplitAcrossItsLongAxis)
{
    ExpectGridSplit(40, 4, 6.0, true);  // ratio 1599 / 15 = 107
    ExpectGridSplit(8, 3, 6.0, true);   // ratio 63 / 8 = 7.9
    ExpectGridSplit(41, 2, 6.0, true);  // odd length: the middle column lies on the plane
}

TEST(ClusterNormalization, CompactPatchesAreNotSplit)
{
    ExpectGridSplit(10, 10, 6.0, false); // ratio 1
    ExpectGridSplit(7, 4, 6.0, false);   // ratio 48 / 15 = 3.2
    ExpectGridSplit(8, 3, 8.0, false);   // 7.9 is below a threshold of 8
}

TEST(ClusterNormalization, DiscIsNotSplit)
{
    gstest::PointSet s;
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    while (s.Size() < 500) {
        const P3 p(u(rng), u(rng), 0);
        if (p.Norm() <= 1) s.Add(p, P3(0, 0, 1));
    }
    Clustering c = OneCluster(s.Size());
    EXPECT_EQ(SplitElongatedClusters(s.points, NormalizationParams(), c), 0);
    EXPECT_EQ(c.clusterCount, 1);
}

// A strip along a skew 3D direction on a tilted plane: the cut is still perpendicular to
// the strip's long axis through its centroid (PCA, not coordinate axes).
TEST(ClusterNormalization, SkewStripIsCutPerpendicularToItsAxis)
{
    P3 along(1, 2, 2), across(2, 1, -2);
    along /= along.Norm();
    across /= across.Norm(); // orthogonal to `along`
    PointArray pts;
    for (int i = 0; i < 30; ++i)
        for (int j = 0; j < 3; ++j) pts.push_back(along * float(i) + across * float(j) + P3(5, -3, 1));
    Clustering c = OneCluster(int(pts.size()));
    ASSERT_EQ(SplitElongatedClusters(pts, NormalizationParams(), c), 1);
    for (size_t k = 0; k < pts.size(); ++k) {
        const int i = int(k) / 3; // position along the strip; centroid at i = 14.5
        EXPECT_EQ(c.label[k], c.label[i < 15 ? 0 : pts.size() - 1]) << "point " << k;
    }
    EXPECT_NE(c.label[0], c.label[pts.size() - 1]);
}

// Clusters under minSplitSize are never split, however elongated; a perfect line
// (lambda2 = 0) is split once it is big enough.
TEST(ClusterNormalization, SmallClustersAreNotSplit)
{
    const PointArray line = gstest::PlaneGrid(5, 1).points;
    Clustering c = OneCluster(5);
    EXPECT_EQ(SplitElongatedClusters(line, NormalizationParams(6.0, 6), c), 0);
    EXPECT_EQ(c.clusterCount, 1);
    Clustering d = OneCluster(5);
    EXPECT_EQ(SplitElongatedClusters(line, NormalizationParams(6.0, 5), d), 1);
    // Centroid at x = 2: points 0, 1 on one side, 3, 4 on the other, 2 on the plane stays.
    EXPECT_EQ(d.label[0], d.label[1]);
    EXPECT_EQ(d.label[3], d.label[4]);
    EXPECT_NE(d.label[0], d.label[4]);
    EXPECT_EQ(d.label[2], 0);
}

// All members at one position: no axis, nothing to split.
TEST(ClusterNormalization, CoincidentPointsAreNotSplit)
{
    const PointArray pts(20, P3(1, 1, 1));
    Clustering c = OneCluster(20);
    EXPECT_EQ(SplitElongatedClusters(pts, NormalizationParams(6.0, 2), c), 0);
    EXPECT_EQ(c.clusterCount, 1);
}

// Several clusters in one pass: compact ones and excluded points are untouched, new
// labels are appended in the order of the clusters they come from.
TEST(ClusterNormalization, OnlyElongatedClustersChangeAndNewLabelsAreAppended)
{
    PointArray pts;
    IndexArray label;
    auto add = [&](const gstest::PointSet &s, P3 offset, int l) {
        for (const P3 &p : s.points) { pts.push_back(p + offset); label.push_back(l); }
    };
    add(gstest::PlaneGrid(6, 6), P3(0, 0, 0), 0);    // compact
    add(gstest::PlaneGrid(30, 2), P3(0, 20, 0), 1);  // elongated
    add(gstest::PlaneGrid(3, 3), P3(0, 40, 0), -1);  // excluded
    add(gstest::PlaneGrid(2, 30), P3(40, 0, 0), 2);  // elongated along y
    Clustering c;
    c.label = label;
    c.clusterCount = 3;
    EXPECT_EQ(SplitElongatedClusters(pts, NormalizationParams(), c), 2);
    EXPECT_EQ(c.clusterCount, 5);
    for (size_t i = 0; i < pts.size(); ++i) {
        if (label[i] == 0 || label[i] == -1) EXPECT_EQ(c.label[i], label[i]);
        if (label[i] == 1) EXPECT_TRUE(c.label[i] == 1 || c.label[i] == 3);
        if (label[i] == 2) EXPECT_TRUE(c.label[i] == 2 || c.label[i] == 4);
    }
    const auto sizes = gstest::ClusterSizes(c.label);
    EXPECT_EQ(sizes.at(1), 30);
    EXPECT_EQ(sizes.at(3), 30);
    EXPECT_EQ(sizes.at(2), 30);
    EXPECT_EQ(sizes.at(4), 30);
}

} // namespace

// A compact but large cluster (a 12 x 12 patch: lambda1/lambda2 = 1) is split only by the
// size cap, and halves keep being split while they exceed it.
TEST(ClusterNormalization, SizeCapSplitsLargeCompactClusters)
{
    PointArray points;
    for (int x = 0; x < 12; ++x)
        for (int y = 0; y < 12; ++y) points.push_back(vcg::Point3f(x * 0.1f, y * 0.1f, 0));
    vcg::gaussphere::Clustering c;
    c.label.assign(points.size(), 0);
    c.clusterCount = 1;
    vcg::gaussphere::ClusterNormalizationParams p;
    p.minSplitSize = 6;
    EXPECT_EQ(vcg::gaussphere::SplitElongatedClusters(points, p, c), 0) << "no cap: a square is never split";
    p.maxClusterSize = 40;
    EXPECT_EQ(vcg::gaussphere::SplitElongatedClusters(points, p, c), 1);
    EXPECT_EQ(c.clusterCount, 2);
    vcg::gaussphere::SplitElongatedClusters(points, p, c); // 72-point halves split again
    const vcg::gaussphere::ClusterMembers members(c);
    for (int k = 0; k < c.clusterCount; ++k) EXPECT_LE(members.Size(k), 40);
}

namespace {

/// A square 6 x 6 grid (ratio 1: never split for its shape), one cluster, with or without
/// a crease point among its members.
int SplitsOfSquare(const ClusterNormalizationParams &base, bool atCrease)
{
    const gstest::PointSet s = gstest::PlaneGrid(6, 6);
    Clustering c = OneCluster(s.Size());
    vcg::gaussphere::FlatVector<char> crease(s.Size(), 0);
    crease[0] = atCrease;
    ClusterNormalizationParams p = base;
    p.creasePoints = &crease;
    return SplitElongatedClusters(s.points, p, c);
}

} // namespace

// Clusters with a crease point are split above creaseClusterSize; the others keep the
// general limit.
TEST(ClusterNormalization, CreaseClustersGetTheTighterCap)
{
    ClusterNormalizationParams p = NormalizationParams();
    p.maxClusterSize = 64;
    p.creaseClusterSize = 5;
    EXPECT_EQ(SplitsOfSquare(p, false), 0) << "36 points, below the general cap of 64";
    EXPECT_EQ(SplitsOfSquare(p, true), 1) << "36 points, above the crease cap of 5";
}

// The crease limits only ever tighten the general ones: no crease cap (0) or a larger one
// leaves the general cap in force.
TEST(ClusterNormalization, CreaseLimitsNeverLoosenTheGeneralOnes)
{
    ClusterNormalizationParams p = NormalizationParams();
    p.maxClusterSize = 16;
    p.creaseClusterSize = 0;
    EXPECT_EQ(SplitsOfSquare(p, true), 1) << "36 points, above the general cap of 16";
    p.creaseClusterSize = 100;
    EXPECT_EQ(SplitsOfSquare(p, true), 1);
    // A never-split size larger than the general one does not protect crease clusters.
    p.creaseClusterSize = 0;
    p.minSplitSize = 6;
    p.creaseMinSplitSize = 50;
    EXPECT_EQ(SplitsOfSquare(p, true), 1);
}
