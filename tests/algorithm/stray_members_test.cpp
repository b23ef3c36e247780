// Clusters with a stray member beside a crease (stray_members.h): a wide cluster whose edge
// points lie nearer to many small clusters' centres than to its own is flagged and split; nothing
// is flagged away from creases.
#include <gtest/gtest.h>

#include <vcg_ext/gaussphere/clustering/stray_members.h>
#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>
#include <vcg_ext/gaussphere/neighbors/point_grid.h>

#include "pipeline_support.h"

using namespace vcg::gaussphere;

namespace {

constexpr int kWidth = 20, kHeight = 12, kWideColumns = 12;

/// A flat grid clustered as one wide cluster over columns [0, 12) and vertical pairs of points
/// beyond (as beside a crease, where clusters are small).
struct WideBesideSmall
{
    gstest::PointSet set = gstest::PlaneGrid(kWidth, kHeight);
    NeighborGraph graph;
    Clustering clusters;

    WideBesideSmall()
    {
        const PointGrid grid(set.points);
        graph = BuildAdaptiveNeighbors(set.points, set.normals, AdaptiveNeighborParams(), grid);
        clusters.label.assign(size_t(set.Size()), 0);
        clusters.clusterCount = 1;
        for (int x = kWideColumns; x < kWidth; ++x)
            for (int y = 0; y < kHeight; y += 2) {
                clusters.label[size_t(y * kWidth + x)] = clusters.label[size_t((y + 1) * kWidth + x)] =
                    clusters.clusterCount++;
            }
    }
    /// Marks the two columns either side of the border between the wide cluster and the pairs.
    void MarkCreaseAtTheBorder()
    {
        graph.crease.assign(size_t(set.Size()), 0);
        for (int y = 0; y < kHeight; ++y)
            for (int x = kWideColumns - 1; x <= kWideColumns; ++x) graph.crease[size_t(y * kWidth + x)] = 1;
    }
};

} // namespace

TEST(StrayMembers, TheWideClusterBesideACreaseIsFlaggedAndSplit)
{
    WideBesideSmall s;
    s.MarkCreaseAtTheBorder();
    const FlatVector<char> flagged = ClustersWithStrayMembers(s.set.points, s.set.normals, s.graph, s.clusters);
    ASSERT_EQ(int(flagged.size()), s.clusters.clusterCount);
    EXPECT_EQ(flagged[0], 1) << "its border column lies nearer to many pairs than to its own centre";
    EXPECT_EQ(std::count(flagged.begin() + 1, flagged.end(), char(1)), 0) << "a pair's members are at its centre";

    const int before = s.clusters.clusterCount;
    const int split = SplitClustersWithStrayMembers(s.set.points, s.set.normals, s.graph, ClusterNormalizationParams(),
                                                    0.1, s.clusters);
    EXPECT_EQ(split, 1);
    EXPECT_EQ(s.clusters.clusterCount, before + 1);
    // Split across its major axis (x): the halves are the columns below and above its centre.
    const int left = s.clusters.label[0], right = s.clusters.label[size_t(kWideColumns - 1)];
    EXPECT_NE(left, right);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWideColumns; ++x)
            EXPECT_EQ(s.clusters.label[size_t(y * kWidth + x)], x < kWideColumns / 2 ? left : right);
}

TEST(StrayMembers, NothingIsFlaggedAwayFromCreases)
{
    WideBesideSmall s;
    FlatVector<char> flagged = ClustersWithStrayMembers(s.set.points, s.set.normals, s.graph, s.clusters);
    EXPECT_EQ(std::count(flagged.begin(), flagged.end(), char(1)), 0) << "no crease marks at all";
    s.graph.crease.assign(size_t(s.set.Size()), 0);
    s.graph.crease[0] = 1; // a corner of the wide cluster, far from the pairs
    flagged = ClustersWithStrayMembers(s.set.points, s.set.normals, s.graph, s.clusters);
    EXPECT_EQ(std::count(flagged.begin(), flagged.end(), char(1)), 0);
    const int before = s.clusters.clusterCount;
    EXPECT_EQ(SplitClustersWithStrayMembers(s.set.points, s.set.normals, s.graph, ClusterNormalizationParams(), 0.1,
                                            s.clusters),
              0);
    EXPECT_EQ(s.clusters.clusterCount, before);
}

TEST(StrayMembers, NeighboursFacingTheOtherWayDoNotCount)
{
    WideBesideSmall s;
    s.MarkCreaseAtTheBorder();
    for (int y = 0; y < kHeight; ++y)
        for (int x = kWideColumns; x < kWidth; ++x) s.set.normals[size_t(y * kWidth + x)] = gstest::P3(0, 0, -1);
    const FlatVector<char> flagged = ClustersWithStrayMembers(s.set.points, s.set.normals, s.graph, s.clusters);
    EXPECT_EQ(std::count(flagged.begin(), flagged.end(), char(1)), 0) << "the pairs are another sheet";
}
