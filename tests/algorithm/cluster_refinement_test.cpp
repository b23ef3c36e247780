// Exact output size (cluster_refinement.h): splitting the worst clusters, merging the
// cheapest neighbours.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <set>

#include <vcg_ext/gaussphere/size_control/cluster_refinement.h>

#include "test_support.h"

using namespace vcg::gaussphere;
using namespace gstest;

namespace {

/// Two flat terraces, both facing +z: x = 0..5 at z = 0 and x = 5.3..10.3 at z = step, ten
/// rows each, linked by 4-neighbour edges within a terrace and across the gap. Tag: terrace.
struct Terraces
{
    PointSet set;
    NeighborGraph graph;
};

Terraces MakeTerraces(float step)
{
    Terraces t;
    const int columns = 6, rows = 10;
    auto id = [&](int terrace, int x, int y) { return (terrace * columns + x) * rows + y; };
    for (int terrace = 0; terrace < 2; ++terrace)
        for (int x = 0; x < columns; ++x)
            for (int y = 0; y < rows; ++y)
                t.set.Add(P3(terrace * (columns - 0.7f) + x, float(y), terrace * step), P3(0, 0, 1), terrace);
    std::vector<std::vector<int>> adj(t.set.Size());
    auto link = [&](int a, int b) { adj[a].push_back(b); adj[b].push_back(a); };
    for (int terrace = 0; terrace < 2; ++terrace)
        for (int x = 0; x < columns; ++x)
            for (int y = 0; y < rows; ++y) {
                if (x + 1 < columns) link(id(terrace, x, y), id(terrace, x + 1, y));
                if (y + 1 < rows) link(id(terrace, x, y), id(terrace, x, y + 1));
            }
    for (int y = 0; y < rows; ++y) link(id(0, columns - 1, y), id(1, 0, y)); // across the gap
    t.graph = MakeGraph(adj);
    return t;
}

/// Every point of `s` in one cluster.
Clustering OneCluster(const PointSet &s)
{
    Clustering c;
    c.label.assign(s.Size(), 0);
    c.clusterCount = 1;
    return c;
}

Clustering Singletons(int n)
{
    Clustering c;
    for (int i = 0; i < n; ++i) c.label.push_back(i);
    c.clusterCount = n;
    return c;
}

} // namespace

// The points across the gap are nearer to each other (0.3 apart in x) than to their own
// terrace's neighbours (1 apart): by position alone they would merge first. The height a
// merge adds to the surfel's plane keeps every cluster on one terrace.
TEST(MergeToCount, KeepsClustersOnOneTerraceOfAStep)
{
    const Terraces t = MakeTerraces(0.5f);
    Clustering c = Singletons(t.set.Size());
    const int target = t.set.Size() / 4;
    const int merges = MergeToCount(t.set.points, t.set.normals, t.graph, 1.0, target, c);
    EXPECT_EQ(merges, t.set.Size() - target);
    ASSERT_EQ(c.clusterCount, target);
    std::vector<std::set<int>> terraces(c.clusterCount);
    for (int i = 0; i < t.set.Size(); ++i) terraces[c.label[i]].insert(t.set.tag[i]);
    for (int k = 0; k < c.clusterCount; ++k) EXPECT_EQ(terraces[k].size(), 1u) << "cluster " << k;
}

// Without a step the gap is just the nearest pair: the merge across it is the cheapest.
TEST(MergeToCount, MergesAcrossAGapWithoutAStep)
{
    const Terraces t = MakeTerraces(0.f);
    Clustering c = Singletons(t.set.Size());
    MergeToCount(t.set.points, t.set.normals, t.graph, 1.0, t.set.Size() - 1, c);
    int across = 0;
    std::vector<std::set<int>> terraces(c.clusterCount);
    for (int i = 0; i < t.set.Size(); ++i) terraces[c.label[i]].insert(t.set.tag[i]);
    for (const auto &s : terraces) across += int(s.size() == 2);
    EXPECT_EQ(across, 1);
}

// Merging stops when no two clusters are linked, short of the target.
TEST(MergeToCount, StopsWhenNoClustersAreLinked)
{
    PointSet s;
    for (int i = 0; i < 4; ++i) s.Add(P3(float(i), 0, 0), P3(0, 0, 1));
    const NeighborGraph g = MakeGraph({{1}, {0}, {3}, {2}});
    Clustering c = Singletons(4);
    EXPECT_EQ(MergeToCount(s.points, s.normals, g, 1.0, 1, c), 2);
    EXPECT_EQ(c.clusterCount, 2);
    EXPECT_EQ(c.label[0], c.label[1]);
    EXPECT_EQ(c.label[2], c.label[3]);
}

// Splitting reaches the requested count exactly, worst normal error first: on a cube's
// surface held as one cluster, the first split separates faces.
TEST(SplitToCount, ReachesTheCountExactly)
{
    const PointSet cube = CubeSurface(8, false);
    Clustering c = OneCluster(cube);
    ClusterRefiner refiner(cube.points, cube.normals, c, 1.0);
    EXPECT_EQ(refiner.SplitToCount(37), 36);
    EXPECT_EQ(c.clusterCount, 37);
    EXPECT_EQ(refiner.Count(), 37);
    std::set<int> labels(c.label.begin(), c.label.end());
    EXPECT_EQ(int(labels.size()), 37);
}

// The record of the splits: one entry a split, in order, naming the cluster split and the one it
// added, with priorities that never rise; the clusters end as the record says.
TEST(SplitToCount, RecordsEachSplitWithFallingPriorities)
{
    const PointSet cube = CubeSurface(8, false);
    Clustering plain = OneCluster(cube), recorded = plain;
    ClusterRefiner(cube.points, cube.normals, plain, 1.0).SplitToCount(37);
    std::vector<CountSplit> record;
    ClusterRefiner(cube.points, cube.normals, recorded, 1.0).SplitToCount(37, nullptr, &record);
    EXPECT_EQ(recorded.label, plain.label) << "recording changes nothing";
    ASSERT_EQ(record.size(), 36u);
    for (std::size_t k = 0; k < record.size(); ++k) {
        EXPECT_EQ(record[k].added, int(k) + 1) << "each split adds the next cluster";
        EXPECT_LT(record[k].cluster, record[k].added);
        if (k > 0) {
            const bool falls = record[k].error < record[k - 1].error ||
                               (record[k].error == record[k - 1].error && record[k].size <= record[k - 1].size);
            EXPECT_TRUE(falls) << "split " << k;
        }
    }
    EXPECT_EQ(record[0].size, cube.Size()) << "the one cluster first";
    EXPECT_GT(record[0].error, 0.0);
}

// Merging reports its progress and stops when told to: at 20 million points it runs for
// seconds. Reporting does not change what is merged.
TEST(MergeToCount, ReportsProgressAndCancels)
{
    const Terraces t = MakeTerraces(0.5f);
    const int target = t.set.Size() / 4;
    Clustering quiet = Singletons(t.set.Size()), watched = quiet, stopped = quiet;
    MergeToCount(t.set.points, t.set.normals, t.graph, 1.0, target, quiet);
    std::vector<double> fractions;
    MergeToCount(t.set.points, t.set.normals, t.graph, 1.0, target, watched, [&](double f) {
        fractions.push_back(f);
        return true;
    });
    EXPECT_EQ(watched.label, quiet.label);
    ASSERT_GE(fractions.size(), 3u) << "set-up steps and the merge loop";
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
    EXPECT_LE(fractions.back(), 1.0);
    int calls = 0;
    EXPECT_EQ(MergeToCount(t.set.points, t.set.normals, t.graph, 1.0, target, stopped, [&](double) { return ++calls < 2; }),
              kRefinementCancelled);
    EXPECT_EQ(calls, 2);
}

TEST(SplitToCount, ReportsProgressAndCancels)
{
    const PointSet cube = CubeSurface(8, false);
    Clustering c = OneCluster(cube);
    ClusterRefiner refiner(cube.points, cube.normals, c, 1.0);
    int calls = 0;
    EXPECT_EQ(refiner.SplitToCount(37, [&](double fraction) {
        EXPECT_GE(fraction, 0.0);
        ++calls;
        return false;
    }), kRefinementCancelled);
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(refiner.SplitToCount(37, [](double) { return true; }), 36);
}

// The pairs of linked clusters: every linked pair once (a < b), with MergeCostModel's cost, in
// order of a then b, as a serial listing gives them.
// Merging leaves in its basis the merged clusters' links, as ClusterAdjacency reads them from
// the graph (k-nearest: not symmetric), and needs no graph for it: the graph is cut first.
TEST(MergeToCount, LeavesTheMergedClustersLinks)
{
    const PointSet cube = CubeSurface(12, true);
    const PointGrid grid(cube.points);
    AdaptiveNeighborParams neighbours;
    neighbours.k = 16;
    NeighborGraph graph = BuildAdaptiveNeighbors(cube.points, cube.normals, neighbours, grid);
    const NeighborGraph whole = graph;
    Clustering c;
    c.label.resize(cube.points.size());
    for (int i = 0; i < int(c.label.size()); ++i) c.label[i] = i / 3; // clusters of 3 along the input order
    c.clusterCount = int(c.label.size() + 2) / 3;
    const std::unique_ptr<MergeBasis> basis = BuildMergeBasis(cube.points, cube.normals, graph, c, 0.1, nullptr);
    ASSERT_TRUE(basis);
    KeepFirstSlots(graph, 4);
    const int before = c.clusterCount, target = before / 5;
    EXPECT_EQ(MergeToCount(*basis, target, c), before - target);
    ASSERT_EQ(c.clusterCount, target);
    EXPECT_EQ(basis->adjacent, ClusterAdjacency(whole, c, ClusterMembers(c)));
}

TEST(LinkedPairs, ListsEveryLinkedPairOnceWithItsCost)
{
    const Terraces t = MakeTerraces(0.5f);
    Clustering c;
    for (int i = 0; i < t.set.Size(); ++i) c.label.push_back(i / 3); // clusters of three neighbours in a row
    c.clusterCount = (t.set.Size() + 2) / 3;
    const ClusterMembers members(c);
    const MergeCostModel model(t.set.points, t.set.normals, c, members, 1.0);
    const std::vector<std::vector<int>> adjacent = ClusterAdjacency(t.graph, c, members);
    std::set<std::pair<int, int>> expected;
    for (int i = 0; i < t.set.Size(); ++i)
        for (const int *q = t.graph.begin(i); q != t.graph.begin(i) + t.graph.found[i]; ++q)
            if (c.label[i] != c.label[*q]) expected.insert({std::min(c.label[i], c.label[*q]), std::max(c.label[i], c.label[*q])});
    const std::vector<MergePair> pairs = LinkedPairs(model, adjacent);
    ASSERT_EQ(pairs.size(), expected.size());
    auto e = expected.begin();
    for (const MergePair &p : pairs) {
        EXPECT_EQ(std::make_pair(p.a, p.b), *e++);
        EXPECT_EQ(p.cost, model.Cost(p.a, p.b));
    }
}
