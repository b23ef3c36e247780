// RejoinSingletons (paper, section 3.3): a one-point cluster joins the neighbouring
// cluster whose mean normal is closest (least 1 - <n, n_cluster>), provided that normal
// lies inside its cone of normals (chord <= maxChord); passes repeat to a fixed point.
#include <gtest/gtest.h>

#include <numeric>
#include <random>

#include <vcg_ext/gaussphere/clustering/gaussian_sphere.h>
#include <vcg_ext/gaussphere/clustering/index_propagation.h>
#include <vcg_ext/gaussphere/clustering/singleton_rejoining.h>
#include <vcg_ext/gaussphere/clustering/cluster_normalization.h>

#include "test_support.h"

namespace {

using namespace vcg::gaussphere;
using gstest::P3;
using gstest::PointArray;
using gstest::IndexArray;

P3 Tilted(double degrees)
{
    const double a = degrees * gstest::kPi / 180;
    return P3(float(std::sin(a)), 0, float(std::cos(a)));
}

const double kChord = 0.42; // d_max at n = 8: a cone of about 24 degrees

Clustering Labels(const IndexArray &label)
{
    Clustering c;
    c.label = label;
    c.clusterCount = 0;
    for (int l : label) c.clusterCount = std::max(c.clusterCount, l + 1);
    return c;
}

// The singleton's normal equals a member of cluster 1, but cluster 1's mean normal is
// tilted by 30 degrees (members at 0 and 60) while cluster 2's is tilted by 10: the score
// uses the cluster normal, so the singleton joins cluster 2.
TEST(SingletonRejoining, JoinsTheClusterWithTheClosestMeanNormal)
{
    const PointArray normals = {Tilted(0), Tilted(0), Tilted(60), Tilted(10), Tilted(10)};
    const NeighborGraph g = gstest::MakeGraph({{1, 2, 3, 4}, {2}, {1}, {4}, {3}});
    Clustering c = Labels({0, 1, 1, 2, 2});
    EXPECT_EQ(RejoinSingletons(normals, g, kChord, c), 1);
    EXPECT_EQ(c.label, (IndexArray{2, 1, 1, 2, 2}));
    EXPECT_EQ(c.clusterCount, 3) << "label 0 is left empty until Compact()";
    c.Compact();
    EXPECT_EQ(c.clusterCount, 2);
    EXPECT_EQ(c.label, (IndexArray{0, 1, 1, 0, 0}));
}

// Mirror image: with cluster 2 tilted further than cluster 1, it joins cluster 1, so the
// choice follows the normals, not the label order or the neighbour order.
TEST(SingletonRejoining, ChoiceFollowsNormalsNotOrder)
{
    const PointArray normals = {Tilted(0), Tilted(5), Tilted(5), Tilted(-20), Tilted(-20)};
    const NeighborGraph g = gstest::MakeGraph({{3, 4, 1, 2}, {2}, {1}, {4}, {3}});
    Clustering c = Labels({0, 1, 1, 2, 2});
    EXPECT_EQ(RejoinSingletons(normals, g, kChord, c), 1);
    EXPECT_EQ(c.label[0], 1);
}

// A singleton whose neighbours are all singletons stays alone: singletons never join each
// other (two singletons could otherwise swap labels).
TEST(SingletonRejoining, SingletonsWithOnlySingletonNeighboursStay)
{
    const PointArray normals = {Tilted(0), Tilted(1), Tilted(2)};
    const NeighborGraph g = gstest::MakeGraph({{1, 2}, {0, 2}, {0, 1}});
    Clustering c = Labels({0, 1, 2});
    EXPECT_EQ(RejoinSingletons(normals, g, kChord, c), 0);
    EXPECT_EQ(c.label, (IndexArray{0, 1, 2}));
}

// Within one pass decisions use the clustering before the pass: in the chain
// A - B - cluster, B joins the cluster but A (whose only neighbour B was a singleton)
// stays. The repeated passes then let A follow B.
TEST(SingletonRejoining, OnePassUsesThePreviousClusteringAndPassesRepeat)
{
    const PointArray normals(5, Tilted(0));
    const NeighborGraph g = gstest::MakeGraph({{1}, {0, 2}, {3, 1}, {2}, {0}});
    Clustering once = Labels({0, 1, 2, 2, 3});
    EXPECT_EQ(RejoinSingletons(normals, g, kChord, once, 1), 1);
    EXPECT_EQ(once.label, (IndexArray{0, 2, 2, 2, 3}));
    Clustering repeated = Labels({0, 1, 2, 2, 3});
    EXPECT_EQ(RejoinSingletons(normals, g, kChord, repeated), 3); // B, then A, then the point behind A
    EXPECT_EQ(repeated.label, (IndexArray{2, 2, 2, 2, 2}));
}

// The cone: a neighbouring cluster whose mean normal is farther than maxChord is not
// joined (15 degrees is a chord of 0.26); with a wider cone it is.
TEST(SingletonRejoining, ClustersOutsideTheConeAreNotJoined)
{
    const PointArray normals = {Tilted(0), Tilted(15), Tilted(15)};
    const NeighborGraph g = gstest::MakeGraph({{1, 2}, {2}, {1}});
    Clustering narrow = Labels({0, 1, 1});
    EXPECT_EQ(RejoinSingletons(normals, g, 0.25, narrow), 0);
    EXPECT_EQ(narrow.label[0], 0);
    Clustering wide = Labels({0, 1, 1});
    EXPECT_EQ(RejoinSingletons(normals, g, 0.27, wide), 1);
    EXPECT_EQ(wide.label[0], 1);
}

// The neighbour graph is directed: a cluster listing the singleton does not make the
// singleton join it; only the singleton's own neighbourhood N(p) counts.
TEST(SingletonRejoining, OnlyTheSingletonsOwnNeighbourhoodCounts)
{
    const PointArray normals(3, Tilted(0));
    const NeighborGraph g = gstest::MakeGraph({{}, {0, 2}, {1, 0}});
    Clustering c = Labels({0, 1, 1});
    EXPECT_EQ(RejoinSingletons(normals, g, kChord, c), 0);
    EXPECT_EQ(c.label[0], 0);
}

// Excluded points (-1) are neither moved nor used as targets.
TEST(SingletonRejoining, ExcludedPointsAreIgnored)
{
    const PointArray normals(4, Tilted(0));
    const NeighborGraph g = gstest::MakeGraph({{1, 2}, {0, 2}, {0, 1}, {0}});
    Clustering c = Labels({0, -1, -1, 1});
    c.clusterCount = 2;
    EXPECT_EQ(RejoinSingletons(normals, g, kChord, c), 0);
    EXPECT_EQ(c.label, (IndexArray{0, -1, -1, 1}));
}

// Equal scores: the smaller label wins (a deterministic tie-break).
TEST(SingletonRejoining, TiesGoToTheSmallerLabel)
{
    const PointArray normals = {Tilted(0), Tilted(10), Tilted(10), Tilted(10), Tilted(10)};
    Clustering c = Labels({0, 2, 2, 1, 1});
    EXPECT_EQ(RejoinSingletons(normals, gstest::MakeGraph({{1, 2, 3, 4}, {2}, {1}, {4}, {3}}), kChord, c), 1);
    EXPECT_EQ(c.label[0], 1);
}

/// A noisy sphere, its neighbours and its naive clustering: many singletons, many splits.
struct NoisySphere
{
    gstest::PointSet s = gstest::FibonacciSphere(20000);
    AdaptiveNeighborParams ap;
    NeighborGraph g;
    Clustering naive;

    NoisySphere()
    {
        std::mt19937 rng(9);
        std::normal_distribution<float> noise(0.f, 0.08f);
        for (P3 &n : s.normals) {
            n += P3(noise(rng), noise(rng), noise(rng));
            n.Normalize();
        }
        const GaussianSphere sphere(16);
        IndexArray triangle;
        for (const P3 &n : s.normals) triangle.push_back(sphere.TriangleOf(n));
        const PointGrid tree(s.points);
        ap.coneChord = sphere.PaperMaxEdgeLength();
        g = BuildAdaptiveNeighbors(s.points, s.normals, ap, tree);
        IndexPropagationParams pp;
        pp.inscribedRadius = sphere.PaperMaxEdgeLength() / (2 * std::sqrt(3.0));
        naive.label.assign(s.Size(), 0);
        PropagateIndices(s.normals, triangle, g, tree.Order(), pp, naive);
    }
};

// On a noisy sphere (many singletons after propagation) one and two threads give the
// same labels, and so do passes run one at a time.
TEST(SingletonRejoining, IndependentOfThreadCountAndOfPassBookkeeping)
{
    const NoisySphere f;
    const gstest::PointSet &s = f.s;
    const NeighborGraph &g = f.g;
    const AdaptiveNeighborParams &ap = f.ap;
    const Clustering &naive = f.naive;

    Clustering one = naive, two = naive;
    int joinedOne, joinedTwo;
    {
        gstest::ScopedThreadCount t(1);
        joinedOne = RejoinSingletons(s.normals, g, ap.coneChord, one);
    }
    {
        gstest::ScopedThreadCount t(2);
        joinedTwo = RejoinSingletons(s.normals, g, ap.coneChord, two);
    }
    EXPECT_GT(joinedOne, 500) << "the fixture must produce many singletons";
    EXPECT_EQ(joinedOne, joinedTwo);
    EXPECT_EQ(one.label, two.label);
    // One pass at a time, each summing the clusters afresh, gives the same labels: the sums
    // kept up to date between passes are exact.
    Clustering stepwise = naive;
    int joinedStepwise = 0, passes = 0;
    for (int moved; (moved = RejoinSingletons(s.normals, g, ap.coneChord, stepwise, 1)) > 0; ++passes)
        joinedStepwise += moved;
    EXPECT_GE(passes, 3) << "the fixture must need several passes";
    EXPECT_EQ(joinedStepwise, joinedOne);
    EXPECT_EQ(stepwise.label, one.label);
    // A point that moved was a singleton and joined the (final) cluster of one of its
    // neighbours, whose mean normal is inside its cone.
    const auto before = gstest::ClusterSizes(naive.label);
    for (int i = 0; i < s.Size(); ++i) {
        if (one.label[i] == naive.label[i]) continue;
        EXPECT_EQ(before.at(naive.label[i]), 1) << "only singletons move";
        bool neighbourHasIt = false;
        for (const int *q = g.begin(i); q != g.end(i); ++q) neighbourHasIt |= *q != i && one.label[*q] == one.label[i];
        EXPECT_TRUE(neighbourHasIt) << "point " << i << " joined a cluster outside its neighbourhood";
    }
}

// Normalization rounds examine only the clusters the last round changed, and rejoining looks
// only at singletons next to a change: the same labels, round by round, as rounds that
// examine every cluster and every singleton.
TEST(SingletonRejoining, NormalizationRoundsGiveTheLabelsOfFullRounds)
{
    const NoisySphere f;
    Clustering start = f.naive;
    RejoinSingletons(f.s.normals, f.g, f.ap.coneChord, start);
    start.Compact();
    ClusterNormalizationParams param;
    param.minSplitSize = 4;
    param.maxClusterSize = 12;
    for (int rounds = 1; rounds <= 4; ++rounds) {
        Clustering incremental = start, full = start;
        const int ran = NormalizeClusters(f.s.points, f.s.normals, f.g, param, f.ap.coneChord, rounds, incremental, [] {});
        int splitting = 0;
        for (int r = 0; r < rounds; ++r) {
            if (SplitElongatedClusters(f.s.points, param, full) == 0) break;
            ++splitting;
            RejoinSingletons(f.s.normals, f.g, f.ap.coneChord, full);
            full.Compact();
        }
        EXPECT_EQ(ran, splitting);
        if (rounds == 4) EXPECT_GE(ran, 3) << "the fixture must need several rounds";
        EXPECT_EQ(incremental.clusterCount, full.clusterCount) << rounds << " round(s)";
        EXPECT_EQ(incremental.label, full.label) << rounds << " round(s)";
    }
}

} // namespace
