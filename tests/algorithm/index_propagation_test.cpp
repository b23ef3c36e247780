// PropagateIndices: naive sampling by index propagation (paper 3.2.2-3.2.3, Algorithm 1).
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <map>
#include <numeric>
#include <random>
#include <set>

#include <omp.h>

#include <vcg_ext/gaussphere/neighbors/adaptive_neighbors.h>
#include <vcg_ext/gaussphere/clustering/gaussian_sphere.h>
#include <vcg_ext/gaussphere/clustering/index_propagation.h>
#include <vcg_ext/gaussphere/clustering/seed_order.h>
#include <vcg_ext/gaussphere/neighbors/morton_order.h>

#include "test_support.h"

namespace {

using namespace vcg::gaussphere;
using gstest::P3;
using gstest::PointArray;
using gstest::IndexArray;

IndexArray Identity(int n)
{
    IndexArray v(n);
    std::iota(v.begin(), v.end(), 0);
    return v;
}

/// Path graph 0 - 1 - ... - (n-1), edges both ways; `cut` removes the edges around a point.
std::vector<std::vector<int>> PathAdjacency(int n, int cutAfter = -1)
{
    std::vector<std::vector<int>> adj(n);
    for (int i = 0; i + 1 < n; ++i) {
        if (i == cutAfter) continue;
        adj[i].push_back(i + 1);
        adj[i + 1].push_back(i);
    }
    return adj;
}

Clustering Propagate(const PointArray &normals, const IndexArray &triangle, const NeighborGraph &g,
                     const IndexArray &seedOrder, const IndexPropagationParams &p,
                     IndexArray initial = {})
{
    Clustering c;
    c.label = initial.empty() ? IndexArray(normals.size(), 0) : initial;
    PropagateIndices(normals, triangle, g, seedOrder, p, c);
    return c;
}

IndexPropagationParams PropagationParams(int depth)
{
    IndexPropagationParams p;
    p.maxDepth = depth;
    p.inscribedRadius = GaussianSphere::PaperMaxEdgeLength(8) / (2 * std::sqrt(3.0));
    return p;
}

// Known answers on a path of 200 points with one normal: from seed s the label reaches
// the points at most `depth` hops away along unlabelled points, so with seeds in path
// order the clusters are runs of depth + 1 points: ceil(200 / (depth + 1)) clusters.
TEST(IndexPropagation, DepthLimitOnAPathGivesKnownCounts)
{
    const int n = 200;
    const PointArray normals(n, P3(0, 0, 1));
    const IndexArray triangle(n, 0);
    const NeighborGraph g = gstest::MakeGraph(PathAdjacency(n));
    EXPECT_EQ(Propagate(normals, triangle, g, Identity(n), PropagationParams(1)).clusterCount, 100);
    EXPECT_EQ(Propagate(normals, triangle, g, Identity(n), PropagationParams(6)).clusterCount, 29);
    const Clustering unlimited = Propagate(normals, triangle, g, Identity(n), PropagationParams(0));
    EXPECT_EQ(unlimited.clusterCount, 1);
    for (int l : unlimited.label) EXPECT_EQ(l, 0);
    // Depth 6: the runs are exactly 0..6, 7..13, ...
    const Clustering d6 = Propagate(normals, triangle, g, Identity(n), PropagationParams(6));
    for (int i = 0; i < n; ++i) EXPECT_EQ(d6.label[i], i / 7) << i;
}

// Without a depth limit a label covers a whole connected component (same normal).
TEST(IndexPropagation, UnlimitedDepthGivesOneClusterPerComponent)
{
    const int n = 200;
    const PointArray normals(n, P3(0, 0, 1));
    const IndexArray triangle(n, 0);
    const NeighborGraph g = gstest::MakeGraph(PathAdjacency(n, 119)); // components 0..119, 120..199
    IndexArray order = Identity(n);
    std::shuffle(order.begin(), order.end(), std::mt19937(3));
    const Clustering c = Propagate(normals, triangle, g, order, PropagationParams(0));
    ASSERT_EQ(c.clusterCount, 2);
    for (int i = 0; i < n; ++i) EXPECT_EQ(c.label[i], c.label[i < 120 ? 0 : 199]) << i;
    EXPECT_NE(c.label[0], c.label[199]);
}

// The same on a real adaptive graph: a long strip (3 x 150, spacing 1) and a second strip
// far away, identical normals. Depth 1 > depth 6 > unlimited = one cluster per strip.
TEST(IndexPropagation, DepthLimitOnStripsDecreasesClusterCount)
{
    gstest::PointSet s = gstest::PlaneGrid(150, 3, 1.f);
    const int first = s.Size();
    for (int i = 0; i < first; ++i) s.Add(s.points[i] + P3(0, 100, 0), s.normals[i]);
    const PointGrid tree(s.points);
    AdaptiveNeighborParams ap;
    ap.k = 8;
    const NeighborGraph g = BuildAdaptiveNeighbors(s.points, s.normals, ap, tree);
    const IndexArray triangle(s.Size(), 5);
    const int c1 = Propagate(s.normals, triangle, g, tree.Order(), PropagationParams(1)).clusterCount;
    const int c6 = Propagate(s.normals, triangle, g, tree.Order(), PropagationParams(6)).clusterCount;
    const Clustering c0 = Propagate(s.normals, triangle, g, tree.Order(), PropagationParams(0));
    EXPECT_GT(c1, c6);
    EXPECT_GT(c6, c0.clusterCount);
    ASSERT_EQ(c0.clusterCount, 2);
    for (int i = 0; i < s.Size(); ++i) EXPECT_EQ(c0.label[i], c0.label[i < first ? 0 : first]);
    // Depth 1: a cluster is a seed and its (at most 8) direct neighbours.
    EXPECT_GE(c1, 2 * first / 9);
}

/// A bumpy height field z = 0.3 sin(x) cos(1.3 y) sampled on a 60 x 60 grid, with exact
/// normals: they span many Gaussian triangles at n = 8 and vary smoothly, so both the
/// triangle test and the inscribed-radius test of propagation are exercised.
struct BumpyGrid
{
    gstest::PointSet s;
    IndexArray triangle;
    NeighborGraph graph;
    IndexArray seedOrder;

    BumpyGrid()
    {
        for (int y = 0; y < 60; ++y)
            for (int x = 0; x < 60; ++x) {
                const float fx = x * 0.1f, fy = y * 0.1f;
                const float z = 0.3f * std::sin(fx) * std::cos(1.3f * fy);
                const float dzdx = 0.3f * std::cos(fx) * std::cos(1.3f * fy);
                const float dzdy = -0.39f * std::sin(fx) * std::sin(1.3f * fy);
                P3 n(-dzdx, -dzdy, 1);
                s.Add(P3(fx, fy, z), n / n.Norm());
            }
        const GaussianSphere sphere(8);
        for (const P3 &n : s.normals) triangle.push_back(sphere.TriangleOf(n));
        const PointGrid tree(s.points);
        AdaptiveNeighborParams ap;
        ap.coneChord = sphere.PaperMaxEdgeLength();
        graph = BuildAdaptiveNeighbors(s.points, s.normals, ap, tree);
        seedOrder = Identity(s.Size());
        std::shuffle(seedOrder.begin(), seedOrder.end(), std::mt19937(7));
    }

    /// The seed of each cluster: the first point of seedOrder carrying its label (every
    /// point before a seed in seedOrder was labelled earlier, so it has a smaller label).
    IndexArray Seeds(const Clustering &c) const
    {
        IndexArray seed(c.clusterCount, -1);
        for (int p : seedOrder)
            if (c.label[p] >= 0 && seed[c.label[p]] < 0) seed[c.label[p]] = p;
        return seed;
    }

    /// Hops from the cluster's seed to each member along graph edges between members
    /// (-1: not reachable inside the cluster).
    IndexArray HopsFromSeed(const Clustering &c) const
    {
        IndexArray hops(s.Size(), -1);
        std::deque<int> queue;
        for (int seed : Seeds(c)) { hops[seed] = 0; queue.push_back(seed); }
        while (!queue.empty()) {
            const int i = queue.front();
            queue.pop_front();
            for (const int *q = graph.begin(i); q != graph.end(i); ++q)
                if (c.label[*q] == c.label[i] && hops[*q] < 0) { hops[*q] = hops[i] + 1; queue.push_back(*q); }
        }
        return hops;
    }
};

// The fixture exercises the radius test: in several Gaussian triangles some normals are
// farther apart than the inscribed radius, so a seed at one of them cannot take the
// other: the radius test, not only the triangle test, separates clusters.
TEST(IndexPropagation, BumpyFixtureSpansMoreThanTheRadiusInsideTriangles)
{
    static const BumpyGrid d;
    const double r = PropagationParams(0).inscribedRadius;
    std::map<int, std::vector<int>> byTriangle;
    for (int i = 0; i < d.s.Size(); ++i) byTriangle[d.triangle[i]].push_back(i);
    int wide = 0;
    for (const auto &t : byTriangle) {
        double spread = 0;
        for (int a : t.second)
            for (int b : t.second) spread = std::max(spread, double((d.s.normals[a] - d.s.normals[b]).Norm()));
        wide += spread > r;
    }
    EXPECT_GT(wide, 3);
}

class IndexPropagationOnBumps : public ::testing::Test
{
protected:
    static const BumpyGrid &Data() { static const BumpyGrid g; return g; }
    static float Radius2() { const double r = PropagationParams(0).inscribedRadius; return float(r * r) * 1.0001f; }
};

// Every point is labelled, each cluster lies in its seed's Gaussian triangle, every
// member's normal is within the inscribed radius of the seed's, and each cluster is
// connected in the graph from its seed.
TEST_F(IndexPropagationOnBumps, SeedReferenceBoundsNormalsAndSharesTriangle)
{
    const BumpyGrid &d = Data();
    for (int depth : {0, 1, 6}) {
        const Clustering c = Propagate(d.s.normals, d.triangle, d.graph, d.seedOrder, PropagationParams(depth));
        const IndexArray seed = d.Seeds(c);
        const IndexArray hops = d.HopsFromSeed(c);
        for (int i = 0; i < d.s.Size(); ++i) {
            ASSERT_GE(c.label[i], 0);
            ASSERT_LT(c.label[i], c.clusterCount);
            const int root = seed[c.label[i]];
            EXPECT_EQ(d.triangle[i], d.triangle[root]) << "point " << i;
            EXPECT_LE((d.s.normals[i] - d.s.normals[root]).SquaredNorm(), Radius2()) << "point " << i;
            ASSERT_GE(hops[i], 0) << "point " << i << " is not connected to its seed inside its cluster";
            if (depth > 0) EXPECT_LE(hops[i], depth) << "point " << i << " lies beyond the depth limit";
        }
        // Sanity check of the fixture: the normals span several triangles.
        EXPECT_GT(std::set<int>(d.triangle.begin(), d.triangle.end()).size(), 10u);
    }
}

// Maximality without a depth limit: when a member of cluster c was expanded, each of its
// neighbours that qualified for c (same triangle, within the radius of c's seed) was
// either already labelled (by an earlier cluster) or taken into c. So no such neighbour
// carries a later label.
TEST_F(IndexPropagationOnBumps, UnlimitedClustersAreMaximal)
{
    const BumpyGrid &d = Data();
    const Clustering c = Propagate(d.s.normals, d.triangle, d.graph, d.seedOrder, PropagationParams(0));
    const IndexArray seed = d.Seeds(c);
    for (int i = 0; i < d.s.Size(); ++i) {
        const int l = c.label[i], root = seed[l];
        for (const int *q = d.graph.begin(i); q != d.graph.end(i); ++q) {
            const bool qualifies = d.triangle[*q] == d.triangle[root] &&
                                   (d.s.normals[*q] - d.s.normals[root]).SquaredNorm() <= Radius2() / 1.0002f;
            if (qualifies) EXPECT_LE(c.label[*q], l) << "neighbour " << *q << " of " << i << " should have joined";
        }
    }
}

// The depth-first traversal (the paper's stack) labels every point and respects the
// invariants: triangle, connectivity, depth.
TEST_F(IndexPropagationOnBumps, DepthLimitedLabellingCoversEveryPoint)
{
    const BumpyGrid &d = Data();
    const Clustering c = Propagate(d.s.normals, d.triangle, d.graph, d.seedOrder, PropagationParams(6));
    const IndexArray seed = d.Seeds(c);
    const IndexArray hops = d.HopsFromSeed(c);
    const auto sizes = gstest::ClusterSizes(c.label);
    EXPECT_EQ(int(sizes.size()), c.clusterCount) << "labels 0..count-1 are all used";
    for (int i = 0; i < d.s.Size(); ++i) {
        ASSERT_GE(c.label[i], 0);
        ASSERT_LT(c.label[i], c.clusterCount);
        EXPECT_EQ(d.triangle[i], d.triangle[seed[c.label[i]]]);
        EXPECT_GE(hops[i], 0);
        EXPECT_LE(hops[i], 6);
    }
}

// The triangles are labelled in parallel: the labels do not depend on the thread count
// (including excluded points), and they number the clusters in the order of
// their seeds in seedOrder, as the sequential algorithm does.
TEST_F(IndexPropagationOnBumps, ThreadCountDoesNotChangeLabelsAndLabelsFollowSeedOrder)
{
    const BumpyGrid &d = Data();
    IndexArray initial(d.s.Size(), 0);
    for (int i = 0; i < d.s.Size(); i += 17) initial[i] = -1;
    IndexArray positionOf(d.s.Size());
    for (int s = 0; s < d.s.Size(); ++s) positionOf[d.seedOrder[s]] = s;
    const int threadsBefore = omp_get_max_threads();
    omp_set_num_threads(1);
    const Clustering one = Propagate(d.s.normals, d.triangle, d.graph, d.seedOrder, PropagationParams(6), initial);
    const IndexArray seed = d.Seeds(one);
    for (int l = 1; l < one.clusterCount; ++l) EXPECT_LT(positionOf[seed[l - 1]], positionOf[seed[l]]);
    for (int threads : {2, 3, 7}) {
        omp_set_num_threads(threads);
        const Clustering many = Propagate(d.s.normals, d.triangle, d.graph, d.seedOrder, PropagationParams(6), initial);
        EXPECT_EQ(many.clusterCount, one.clusterCount) << threads << " threads";
        EXPECT_EQ(many.label, one.label) << threads << " threads";
    }
    omp_set_num_threads(threadsBefore);
}

// Called where OpenMP gives a team fewer threads than it asks for (inside a parallel region,
// without nesting), the threads present take the seeds of the missing ones: the same labels.
TEST_F(IndexPropagationOnBumps, AThreadTeamSmallerThanAskedGivesTheSameLabels)
{
    const BumpyGrid &d = Data();
    const int threadsBefore = omp_get_max_threads();
    const int nestedBefore = omp_get_max_active_levels();
    omp_set_num_threads(1);
    const Clustering one = Propagate(d.s.normals, d.triangle, d.graph, d.seedOrder, PropagationParams(6));
    omp_set_num_threads(4);
    omp_set_max_active_levels(1);
    Clustering inner;
    int asked = 0;
#pragma omp parallel num_threads(2)
    {
#pragma omp single
        {
            asked = omp_get_max_threads();
            inner = Propagate(d.s.normals, d.triangle, d.graph, d.seedOrder, PropagationParams(6));
        }
    }
    omp_set_max_active_levels(nestedBefore);
    omp_set_num_threads(threadsBefore);
    EXPECT_EQ(asked, 4) << "the inner team asks for 4 threads and gets 1";
    EXPECT_EQ(inner.clusterCount, one.clusterCount);
    EXPECT_EQ(inner.label, one.label);
}

// A progress callback that answers false stops the labelling on any thread count: the call
// returns false, and the progress it saw stays within [0, 1] and never falls.
TEST_F(IndexPropagationOnBumps, ProgressRisesAndACancelStopsTheLabelling)
{
    const BumpyGrid &d = Data();
    const int threadsBefore = omp_get_max_threads();
    for (int threads : {1, 3}) {
        omp_set_num_threads(threads);
        std::vector<double> seen;
        Clustering c;
        c.label.assign(d.s.Size(), 0);
        EXPECT_TRUE(PropagateIndices(d.s.normals, d.triangle, d.graph, d.seedOrder, PropagationParams(6), c, [&](double f) {
            seen.push_back(f);
            return true;
        }));
        ASSERT_GT(seen.size(), 10u) << threads << " threads";
        for (size_t i = 0; i < seen.size(); ++i) {
            EXPECT_GE(seen[i], 0.0);
            EXPECT_LE(seen[i], 1.0);
            if (i > 0) EXPECT_GE(seen[i], seen[i - 1]);
        }
        int calls = 0;
        c.label.assign(d.s.Size(), 0);
        EXPECT_FALSE(PropagateIndices(d.s.normals, d.triangle, d.graph, d.seedOrder, PropagationParams(6), c, [&](double) {
            return ++calls < 3;
        })) << threads << " threads";
        EXPECT_GT(std::count(c.label.begin(), c.label.end(), detail::kUnlabelled), 0)
            << "stopped before every point had a label";
    }
    omp_set_num_threads(threadsBefore);
}

// An empty seed order is the points' own order (the resampler's, after its spatial renumbering),
// on one thread and on several.
TEST_F(IndexPropagationOnBumps, EmptySeedOrderIsThePointOrder)
{
    const BumpyGrid &d = Data();
    IndexArray identity(d.s.Size());
    for (int i = 0; i < d.s.Size(); ++i) identity[i] = i;
    const int threadsBefore = omp_get_max_threads();
    for (int threads : {1, 2}) {
        omp_set_num_threads(threads);
        const Clustering given = Propagate(d.s.normals, d.triangle, d.graph, identity, PropagationParams(6));
        const Clustering empty = Propagate(d.s.normals, d.triangle, d.graph, IndexArray(), PropagationParams(6));
        EXPECT_EQ(empty.clusterCount, given.clusterCount) << threads << " threads";
        EXPECT_EQ(empty.label, given.label) << threads << " threads";
        EXPECT_NE(Propagate(d.s.normals, d.triangle, d.graph, d.seedOrder, PropagationParams(6)).label, empty.label)
            << "the fixture's seed order gives other labels: the comparison can fail";
    }
    omp_set_num_threads(threadsBefore);
}

// What the resampler's seed order is for: on a flat face (one normal, one Gaussian triangle), the
// clusters of the points away from a cut are the same with and without the points beyond it. A
// 240 x 40 plane; in SeedOrder the part x >= 120 alone clusters the points x >= 180 as the whole
// does. Along the Morton curve, which passes the cut-away points first, it does not.
TEST(IndexPropagation, InSeedOrderClustersAwayFromACutDoNotDependOnThePointsBeyondIt)
{
    const gstest::PointSet whole = gstest::PlaneGrid(240, 40, 1.f);
    gstest::PointSet part;
    IndexArray wholeIndex; // of each point of `part`
    for (int i = 0; i < whole.Size(); ++i)
        if (whole.points[i][0] >= 120) { part.Add(whole.points[i], whole.normals[i]); wholeIndex.push_back(i); }
    auto cluster = [](const gstest::PointSet &s, bool seedOrder) {
        const PointGrid tree(s.points);
        AdaptiveNeighborParams ap;
        ap.k = 8;
        const NeighborGraph g = BuildAdaptiveNeighbors(s.points, s.normals, ap, tree);
        const IndexArray order = seedOrder ? SeedOrder(s.points) : MortonOrder(s.points);
        return Propagate(s.normals, IndexArray(s.Size(), 0), g, order, PropagationParams(6));
    };
    // How many points x >= 180 the part clusters otherwise than the whole (a cluster of the part
    // matched to the whole's cluster of its first such point).
    auto differing = [&](bool seedOrder) {
        const Clustering a = cluster(whole, seedOrder), b = cluster(part, seedOrder);
        std::map<int, int> partToWhole;
        std::set<int> wholeUsed;
        int differ = 0;
        for (int t = 0; t < part.Size(); ++t) {
            if (part.points[t][0] < 180) continue;
            const int la = a.label[wholeIndex[t]];
            const auto found = partToWhole.find(b.label[t]);
            if (found == partToWhole.end()) {
                differ += !wholeUsed.insert(la).second;
                partToWhole.emplace(b.label[t], la);
            } else {
                differ += found->second != la;
            }
        }
        return differ;
    };
    EXPECT_EQ(differing(true), 0);
    EXPECT_GT(differing(false), 100) << "Morton order: the cut changes clusters far from it (the test can fail)";
}

// The seed order reads each point alone and ignores a power-of-two scale, with any salt: the
// same points multiplied by 8 come in the same order, and a subset keeps its points' relative order.
TEST(SeedOrder, DependsOnEachPointAloneAtAnyPowerOfTwoScale)
{
    const gstest::PointSet s = gstest::PlaneGrid(30, 30, 0.37f);
    PointArray scaled = s.points;
    for (auto &p : scaled) p = p * 8.f;
    for (std::uint32_t salt : {0u, 12345u}) {
        const IndexArray order = SeedOrder(s.points, salt);
        EXPECT_EQ(SeedOrder(scaled, salt), order) << "salt " << salt;
        PointArray half;
        IndexArray halfIndex;
        for (int i = 0; i < s.Size(); i += 2) { half.push_back(s.points[i]); halfIndex.push_back(i); }
        IndexArray expected;
        for (int i : order)
            if (i % 2 == 0) expected.push_back(i);
        IndexArray got;
        for (int t : SeedOrder(half, salt)) got.push_back(halfIndex[t]);
        EXPECT_EQ(got, expected) << "salt " << salt;
        EXPECT_NE(order, Identity(s.Size())) << "not the points' own order";
    }
}

// Salts give unrelated orders: the ranks of the points under two salts are uncorrelated
// (Spearman's coefficient near 0; 900 points give a standard error of about 0.033).
TEST(SeedOrder, SaltsGiveUnrelatedOrders)
{
    const gstest::PointSet s = gstest::PlaneGrid(30, 30, 0.37f);
    EXPECT_EQ(SeedOrder(s.points, 0), SeedOrder(s.points));
    const int n = s.Size();
    std::vector<double> rank0(n), rank1(n);
    const IndexArray order0 = SeedOrder(s.points, 0), order1 = SeedOrder(s.points, 1);
    for (int r = 0; r < n; ++r) { rank0[order0[r]] = r; rank1[order1[r]] = r; }
    double sumSquares = 0;
    for (int i = 0; i < n; ++i) sumSquares += (rank0[i] - rank1[i]) * (rank0[i] - rank1[i]);
    const double spearman = 1 - 6 * sumSquares / (double(n) * (double(n) * n - 1));
    EXPECT_LT(std::abs(spearman), 0.15);
    EXPECT_NE(order0, order1);
}

// Points pre-marked -1 are excluded: they stay -1, are never seeds, and do not carry
// labels across (a path cut by an excluded point gives two clusters).
TEST(IndexPropagation, ExcludedPointsStayExcluded)
{
    const int n = 50;
    const PointArray normals(n, P3(0, 0, 1));
    const IndexArray triangle(n, 0);
    const NeighborGraph g = gstest::MakeGraph(PathAdjacency(n));
    IndexArray initial(n, 0);
    initial[20] = -1;
    initial[0] = -1;
    const Clustering c = Propagate(normals, triangle, g, Identity(n), PropagationParams(0), initial);
    EXPECT_EQ(c.label[0], -1);
    EXPECT_EQ(c.label[20], -1);
    EXPECT_EQ(c.clusterCount, 2);
    for (int i = 1; i < 20; ++i) EXPECT_EQ(c.label[i], c.label[1]);
    for (int i = 21; i < n; ++i) EXPECT_EQ(c.label[i], c.label[21]);
    EXPECT_NE(c.label[1], c.label[21]);
}

// Neighbours in another Gaussian triangle never share a label, even with equal normals
// (the triangle ids are given by the caller).
TEST(IndexPropagation, DifferentTrianglesNeverShareALabel)
{
    const int n = 30;
    const PointArray normals(n, P3(0, 0, 1));
    IndexArray triangle(n);
    for (int i = 0; i < n; ++i) triangle[i] = (i / 5) % 2; // runs of 5 alternate
    const Clustering c = Propagate(normals, triangle, gstest::MakeGraph(PathAdjacency(n)), Identity(n), PropagationParams(0));
    EXPECT_EQ(c.clusterCount, 6);
    for (int i = 0; i < n; ++i) EXPECT_EQ(c.label[i], i / 5);
}

} // namespace
