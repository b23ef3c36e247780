// ResamplePointSet on analytic shapes: sharp features are never crossed, flat regions
// give few large surfels, finer Gaussian spheres give more surfels, clusters come out
// compact, and the output is deterministic and consistent with representative[].
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include <vcg_ext/gaussphere/surfels/surfel_mesh.h>

#include "pipeline_support.h"

namespace {

using namespace vcg::gaussphere;
using gstest::P3;

// A cube sampled on a 24-cell grid per edge: 6 x 23^2 face points with the face normal,
// edge points with the mean of two face normals and corners with the mean of three.
// Face normals are sqrt 2 apart and an edge normal is 0.77 from its faces, both far above
// d_max = 0.42, so no adaptive neighbourhood crosses an edge and every cluster holds points
// of one kind only: all members of a cluster have exactly the same normal.
class CubePipeline : public ::testing::Test
{
protected:
    static const gstest::PointSet &Cube() { static const gstest::PointSet s = gstest::CubeSurface(24, true); return s; }
    static const ResamplingResult &Result() { static const ResamplingResult r = gstest::Resample(Cube()); return r; }
};

TEST_F(CubePipeline, ResultIsValid)
{
    gstest::ExpectValidResult(Result(), Cube());
    EXPECT_EQ(Result().stats.inputCount, Cube().Size());
    EXPECT_EQ(Result().stats.skippedCount, 0);
}

TEST_F(CubePipeline, NoClusterStraddlesAnEdge)
{
    const auto members = gstest::MembersOf(Result());
    for (size_t c = 0; c < members.size(); ++c) {
        const int tag = Cube().tag[members[c][0]];
        const P3 n = Cube().normals[members[c][0]];
        for (int i : members[c]) {
            EXPECT_EQ(Cube().tag[i], tag) << "surfel " << c << " mixes face/edge/corner points";
            EXPECT_EQ(Cube().normals[i], n) << "surfel " << c << " mixes points of different faces or edges";
        }
        // The surfel normal of a flat cluster is exactly the shared normal.
        EXPECT_NEAR(gstest::Dot(Result().surfels[c].normal, n), 1.0, 1e-6) << "surfel " << c;
    }
}

// Flat faces of 529 points each give few surfels: large ones inside, and small ones along
// the edges, where the crease limits apply (the edge points' normals are 45 degrees away,
// the next face's 90).
TEST_F(CubePipeline, FlatFacesGiveLargeSurfelsInsideAndSmallOnesAtTheEdges)
{
    const auto members = gstest::MembersOf(Result());
    const ResamplingParams defaults;
    const float spacing = 2.f / 24;
    std::vector<int> perFace(6, 0);
    int facePoints = 0, interiorClusters = 0, interiorPoints = 0;
    for (size_t c = 0; c < members.size(); ++c) {
        const int tag = Cube().tag[members[c][0]];
        if (tag >= 6) continue;
        ++perFace[tag];
        facePoints += int(members[c].size());
        float nearest = 2;
        for (int i : members[c]) nearest = std::min(nearest, gstest::DistanceToCubeEdge(Cube(), i));
        // The cap, plus a singleton the last round's rejoining may add (normalization ends after
        // its rounds with a rejoining, cluster_normalization.h).
        if (nearest < 1.5f * spacing)
            EXPECT_LE(int(members[c].size()), defaults.tuning.creaseClusterSize + 1) << "cluster " << c << " touches an edge";
        if (nearest > 3.5f * spacing) {
            ++interiorClusters;
            interiorPoints += int(members[c].size());
        }
    }
    EXPECT_EQ(facePoints, 6 * 23 * 23);
    for (int f = 0; f < 6; ++f) {
        EXPECT_GE(perFace[f], 1);
        EXPECT_LE(perFace[f], 100) << "face " << f << ": " << 23 * 23 << " coplanar points";
    }
    ASSERT_GT(interiorClusters, 0);
    EXPECT_GE(double(interiorPoints) / interiorClusters, 1.5 * defaults.tuning.creaseClusterSize)
        << "inside the faces, surfels stay larger than the crease limit";
    EXPECT_LT(Result().surfels.size(), Cube().Size() / 4);
    std::printf("cube: %d points -> %zu surfels (per face: %d %d %d %d %d %d), %.1f points per interior surfel\n",
                Cube().Size(), Result().surfels.size(), perFace[0], perFace[1], perFace[2], perFace[3], perFace[4],
                perFace[5], double(interiorPoints) / interiorClusters);
}

// With the crease limits off, a face is a few surfels of up to MaxClusterSize points.
TEST(ResamplingPipeline, CubeWithoutCreaseLimitsKeepsFewSurfelsPerFace)
{
    const gstest::PointSet s = gstest::CubeSurface(24, true);
    ResamplingParams p;
    p.creaseAngle = 0;
    const ResamplingResult r = gstest::Resample(s, p);
    const auto members = gstest::MembersOf(r);
    std::vector<int> perFace(6, 0);
    for (const auto &m : members)
        if (s.tag[m[0]] < 6) ++perFace[s.tag[m[0]]];
    for (int f = 0; f < 6; ++f) EXPECT_LE(perFace[f], 40) << "face " << f;
}

// Without the edge points the faces are separate components of the neighbour graph.
TEST(ResamplingPipeline, CubeFacesOnlyKeepFacesApart)
{
    const gstest::PointSet s = gstest::CubeSurface(16, false);
    const ResamplingResult r = gstest::Resample(s);
    gstest::ExpectValidResult(r, s);
    const auto members = gstest::MembersOf(r);
    for (const auto &m : members)
        for (int i : m) EXPECT_EQ(s.tag[i], s.tag[m[0]]);
}

// 20k points on the unit sphere: the finer the Gaussian sphere, the more clusters (each
// cluster's normals must fit in a smaller triangle and a smaller inscribed radius).
TEST(ResamplingPipeline, SphereCountGrowsWithLevel)
{
    const gstest::PointSet s = gstest::FibonacciSphere(20000);
    int previous = 0;
    for (int level : {8, 16, 24}) {
        ResamplingParams p;
        p.subdivisionLevel = level;
        const ResamplingResult r = gstest::Resample(s, p);
        EXPECT_GT(int(r.surfels.size()), previous) << "level " << level;
        EXPECT_LT(int(r.surfels.size()), s.Size());
        if (level == 8) gstest::ExpectValidResult(r, s);
        previous = int(r.surfels.size());
    }
}

// A target at a fixed level (a tile of a tiled run): the level given, not the one searched, and
// without exchanges the splits that reached the count, recorded as surfel indices.
TEST(ResamplingPipeline, ATargetAtAFixedLevelSplitsThatLevelsClustersAndRecordsTheSplits)
{
    const gstest::PointSet s = gstest::FibonacciSphere(20000);
    ResamplingParams p;
    p.subdivisionLevel = 6;
    const int atLevel6 = int(gstest::Resample(s, p).surfels.size());
    p.subdivisionLevel = 4;
    const int atLevel = int(gstest::Resample(s, p).surfels.size());
    ASSERT_GT(atLevel6, atLevel);
    p.targetCount = atLevel6 + 50;
    p.maxErrorExchanges = 0;
    p.recordCountSteps = true;
    const ResamplingResult searched = gstest::Resample(s, p);
    p.searchLevel = false;
    const ResamplingResult fixed = gstest::Resample(s, p);
    EXPECT_GE(searched.stats.levelUsed, 6) << "the search finds level 6 or finer for this count";
    EXPECT_EQ(fixed.stats.levelUsed, 4);
    EXPECT_EQ(fixed.stats.levelsTried, 1);
    ASSERT_EQ(int(fixed.surfels.size()), p.targetCount);
    const std::vector<CountSplit> &splits = fixed.targetRecord.splits;
    ASSERT_EQ(int(splits.size()), p.targetCount - atLevel);
    for (std::size_t k = 0; k < splits.size(); ++k)
        EXPECT_EQ(splits[k].added, atLevel + int(k)) << "surfel indices of the clusters added";
    EXPECT_TRUE(fixed.targetRecord.merges.empty());
    gstest::ExpectValidResult(fixed, s);
    p.maxErrorExchanges = 4;
    EXPECT_TRUE(gstest::Resample(s, p).targetRecord.splits.empty()) << "exchanges change the clusters: no record";
    p.maxErrorExchanges = 0;
    p.recordCountSteps = false;
    EXPECT_TRUE(gstest::Resample(s, p).targetRecord.splits.empty()) << "not asked for";
}

// Below the level's count, without exchanges: the merges that reached the count, recorded with
// each vertex's cluster at the level; replayed on those clusters they give the surfels' clusters.
TEST(ResamplingPipeline, ATargetBelowTheLevelRecordsTheMergesThatGiveItsClusters)
{
    const gstest::PointSet s = gstest::FibonacciSphere(20000);
    ResamplingParams p;
    p.subdivisionLevel = 4;
    const int atLevel = int(gstest::Resample(s, p).surfels.size());
    p.targetCount = atLevel / 3;
    p.searchLevel = false;
    p.maxErrorExchanges = 0;
    p.recordCountSteps = true;
    const ResamplingResult r = gstest::Resample(s, p);
    ASSERT_EQ(int(r.surfels.size()), p.targetCount);
    const CountRecord &record = r.targetRecord;
    EXPECT_TRUE(record.splits.empty());
    ASSERT_EQ(int(record.merges.size()), atLevel - p.targetCount);
    ASSERT_EQ(record.levelRepresentative.size(), r.representative.size());
    std::vector<int> parent(static_cast<std::size_t>(atLevel));
    for (int c = 0; c < atLevel; ++c) parent[std::size_t(c)] = c;
    const auto root = [&parent](int c) {
        while (parent[std::size_t(c)] != c) c = parent[std::size_t(c)];
        return c;
    };
    int cheaper = 0;
    for (std::size_t k = 0; k < record.merges.size(); ++k) {
        const CountMerge &m = record.merges[k];
        ASSERT_EQ(root(m.kept), m.kept) << "merge " << k << ": a cluster no merge took away";
        ASSERT_EQ(root(m.gone), m.gone) << "merge " << k;
        ASSERT_NE(m.kept, m.gone);
        parent[std::size_t(m.gone)] = m.kept;
        cheaper += k > 0 && m.cost < record.merges[k - 1].cost;
    }
    EXPECT_LT(cheaper, int(record.merges.size()) / 4) << "the costs mostly rise";
    EXPECT_LT(record.merges.front().cost, record.merges.back().cost);
    // Each merged cluster of the level is one surfel, and no surfel holds two of them.
    std::vector<int> surfelOf(static_cast<std::size_t>(atLevel), -1), clusterOf(r.surfels.size(), -1);
    for (std::size_t v = 0; v < r.representative.size(); ++v) {
        ASSERT_GE(record.levelRepresentative[v], 0) << "vertex " << v << ": every point of the sphere is usable";
        ASSERT_GE(r.representative[v], 0) << "vertex " << v;
        const int c = root(record.levelRepresentative[v]), surfel = r.representative[v];
        if (surfelOf[std::size_t(c)] < 0) surfelOf[std::size_t(c)] = surfel;
        if (clusterOf[std::size_t(surfel)] < 0) clusterOf[std::size_t(surfel)] = c;
        ASSERT_EQ(surfelOf[std::size_t(c)], surfel) << "vertex " << v;
        ASSERT_EQ(clusterOf[std::size_t(surfel)], c) << "vertex " << v;
    }
    p.maxErrorExchanges = 4;
    const CountRecord none = gstest::Resample(s, p).targetRecord;
    EXPECT_TRUE(none.merges.empty() && none.levelRepresentative.empty()) << "exchanges change the clusters: no record";
    p.maxErrorExchanges = 0;
    p.recordCountSteps = false;
    const CountRecord notAsked = gstest::Resample(s, p).targetRecord;
    EXPECT_TRUE(notAsked.merges.empty() && notAsked.levelRepresentative.empty()) << "not asked for";
}

/// Largest lambda1 / lambda2 over the clusters big enough to be split.
double WorstSplittableElongation(const gstest::PointSet &s, const ResamplingResult &r, int minSplitSize)
{
    double worst = 0;
    for (const auto &m : gstest::MembersOf(r))
        if (int(m.size()) >= minSplitSize) worst = std::max(worst, gstest::ElongationOf(s, m));
    return worst;
}

// Planes and strips: normalization splits elongated clusters until every splittable one
// satisfies lambda1 / lambda2 <= threshold.
// Normalization rounds stop when one splits nothing (cluster_normalization.h). A 300 x 3
// strip is one naive cluster without a depth limit; each round halves its elongated pieces,
// and the rounds end within the cap with no splittable piece elongated. One round alone
// leaves two pieces.
TEST(ResamplingPipeline, NormalizationStopsWhenARoundSplitsNothing)
{
    const gstest::PointSet s = gstest::PlaneGrid(300, 3, 0.1f);
    ResamplingParams p;
    p.tuning.maxClusterSize = 0; // shape alone decides the splits here
    p.propagationDepth = 0;
    p.tuning.maxIterations = 100;
    const ResamplingResult settled = gstest::Resample(s, p);
    gstest::ExpectValidResult(settled, s);
    EXPECT_GT(settled.stats.iterations, 3);
    EXPECT_LT(settled.stats.iterations, p.tuning.maxIterations);
    EXPECT_LE(WorstSplittableElongation(s, settled, p.tuning.minSplitSize), p.normalizationThreshold);
    p.tuning.maxIterations = 1;
    const ResamplingResult oneRound = gstest::Resample(s, p);
    EXPECT_EQ(oneRound.stats.iterations, 1);
    EXPECT_EQ(oneRound.surfels.size(), 2u);
}

TEST(ResamplingPipeline, StripClustersAreCompact)
{
    const gstest::PointSet s = gstest::PlaneGrid(300, 3, 0.1f);
    const ResamplingParams p;
    const ResamplingResult r = gstest::Resample(s, p);
    gstest::ExpectValidResult(r, s);
    EXPECT_LE(WorstSplittableElongation(s, r, p.tuning.minSplitSize), p.normalizationThreshold);
    // A 3-wide cluster satisfies the threshold only up to length ~7 ((L^2-1)/8 <= 6), so
    // the 900 points need at least 300 / 8 clusters.
    EXPECT_GE(r.surfels.size(), 300u / 8);
}

// Without a depth limit the naive clustering of a strip is one cluster; normalization rounds
// run until none splits (enough of them allowed) and alone cut it, and the plane, into compact
// pieces.
TEST(ResamplingPipeline, ClustersAreCompactWhenNormalizationRunsToAFixedPoint)
{
    for (const gstest::PointSet &s : {gstest::PlaneGrid(60, 60, 0.1f), gstest::PlaneGrid(300, 3, 0.1f)}) {
        ResamplingParams p;
        p.propagationDepth = 0;
        p.tuning.maxIterations = 100;
        const ResamplingResult r = gstest::Resample(s, p);
        gstest::ExpectValidResult(r, s);
        EXPECT_EQ(r.stats.naiveCount, 1);
        EXPECT_LE(WorstSplittableElongation(s, r, p.tuning.minSplitSize), p.normalizationThreshold);
    }
}

/// A noisy sphere: normals jittered so that every stage has work (singletons, splits).
gstest::PointSet NoisySphere(int n, unsigned seed)
{
    gstest::PointSet s = gstest::FibonacciSphere(n);
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.f, 0.05f);
    for (P3 &v : s.normals) {
        v += P3(noise(rng), noise(rng), noise(rng));
        v.Normalize();
    }
    return s;
}

bool SameSurfels(const std::vector<Surfel> &a, const std::vector<Surfel> &b)
{
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (!(a[i].position == b[i].position) || !(a[i].normal == b[i].normal) || !(a[i].majorAxis == b[i].majorAxis) ||
            !(a[i].minorAxis == b[i].minorAxis) || a[i].memberCount != b[i].memberCount)
            return false;
    return true;
}

TEST(ResamplingPipeline, IdenticalOutputForOneAndTwoThreads)
{
    const gstest::PointSet s = NoisySphere(20000, 21);
    ResamplingResult one, two;
    {
        gstest::ScopedThreadCount t(1);
        one = gstest::Resample(s);
    }
    {
        gstest::ScopedThreadCount t(2);
        two = gstest::Resample(s);
    }
    ASSERT_EQ(one.surfels.size(), two.surfels.size());
    EXPECT_TRUE(SameSurfels(one.surfels, two.surfels));
    EXPECT_EQ(one.representative, two.representative);
    EXPECT_EQ(one.stats.naiveCount, two.stats.naiveCount);
    EXPECT_EQ(one.stats.iterations, two.stats.iterations);
    gstest::ExpectValidResult(one, s);
}

// A seed salt draws another clustering of the same kind: other clusters, a valid result, and a
// count within a few percent of the unsalted one; salt 0 is the default order.
TEST(ResamplingPipeline, ASeedSaltDrawsAnotherClusteringOfTheSameKind)
{
    const gstest::PointSet s = NoisySphere(20000, 21);
    const ResamplingResult unsalted = gstest::Resample(s);
    ResamplingParams p;
    p.tuning.seedSalt = 0;
    EXPECT_EQ(gstest::Resample(s, p).representative, unsalted.representative);
    for (std::uint32_t salt : {1u, 0x9e3779b9u}) {
        p.tuning.seedSalt = salt;
        const ResamplingResult salted = gstest::Resample(s, p);
        gstest::ExpectValidResult(salted, s);
        EXPECT_NE(salted.representative, unsalted.representative) << "salt " << salt;
        EXPECT_NEAR(double(salted.surfels.size()) / unsalted.surfels.size(), 1.0, 0.05) << "salt " << salt;
    }
}

// representative[] and memberCount agree, also when some vertices are skipped and
// deleted vertices are present; stats count them.
TEST(ResamplingPipeline, RepresentativeMatchesMemberCounts)
{
    const gstest::PointSet s = NoisySphere(5000, 22);
    OrientedPointMesh m;
    gstest::ToMesh(s, m);
    std::vector<char> skipped(s.Size(), 0);
    for (int i = 0; i < s.Size(); i += 97) { m.vert[i].N() = P3(0, 0, 0); skipped[i] = 1; }
    for (int i = 50; i < s.Size(); i += 211) { vcg::tri::Allocator<OrientedPointMesh>::DeleteVertex(m, m.vert[i]); skipped[i] = 2; }
    const ResamplingResult r = ResamplePointSet(m, ResamplingParams());
    int zero = 0, deleted = 0;
    for (char k : skipped) { zero += k == 1; deleted += k == 2; }
    EXPECT_EQ(r.stats.inputCount, s.Size() - deleted);
    EXPECT_EQ(r.stats.skippedCount, zero);
    gstest::ExpectValidResult(r, s, skipped);
}

// WriteSurfels: one vertex per surfel with position, normal, radius = |major|, quality =
// member count and the two axis attributes.
TEST(ResamplingPipeline, WriteSurfelsStoresAxesAndRadius)
{
    const gstest::PointSet s = gstest::CubeSurface(10, true);
    const ResamplingResult r = gstest::Resample(s);
    OrientedPointMesh out;
    vcg::tri::Allocator<OrientedPointMesh>::AddVertices(out, 3); // replaced, not appended
    WriteSurfels(r.surfels, out);
    ASSERT_EQ(out.vn, int(r.surfels.size()));
    ASSERT_EQ(out.vert.size(), r.surfels.size());
    ASSERT_TRUE(vcg::tri::HasPerVertexAttribute(out, kMajorAxisAttribute));
    ASSERT_TRUE(vcg::tri::HasPerVertexAttribute(out, kMinorAxisAttribute));
    auto major = vcg::tri::Allocator<OrientedPointMesh>::GetPerVertexAttribute<P3>(out, kMajorAxisAttribute);
    auto minor = vcg::tri::Allocator<OrientedPointMesh>::GetPerVertexAttribute<P3>(out, kMinorAxisAttribute);
    for (size_t i = 0; i < r.surfels.size(); ++i) {
        const Surfel &f = r.surfels[i];
        EXPECT_EQ(out.vert[i].P(), f.position);
        EXPECT_EQ(out.vert[i].N(), f.normal);
        EXPECT_EQ(major[i], f.majorAxis);
        EXPECT_EQ(minor[i], f.minorAxis);
        EXPECT_FLOAT_EQ(out.vert[i].R(), f.majorAxis.Norm());
        EXPECT_EQ(out.vert[i].Q(), float(f.memberCount));
    }
    EXPECT_TRUE(out.bbox.IsIn(r.surfels[0].position));
    // A smooth surface has no crease to narrow blends at: no blend scale attribute.
    WriteSurfels(gstest::Resample(gstest::FibonacciSphere(2000)).surfels, out);
    EXPECT_FALSE(vcg::tri::HasPerVertexAttribute(out, kBlendScaleAttribute)) << "every blend scale is 1";
}

// Surfels fitted to their blend carry their move as SurfelFitOffset, for every surfel.
TEST(ResamplingPipeline, WriteSurfelsStoresFitOffsetsWhenFitted)
{
    const gstest::PointSet s = gstest::FibonacciSphere(4000);
    const ResamplingResult r = gstest::Resample(s);
    ASSERT_GT(r.stats.surfelsFitted, 0);
    OrientedPointMesh out;
    WriteSurfels(r.surfels, out);
    ASSERT_TRUE(vcg::tri::HasPerVertexAttribute(out, kFitOffsetAttribute));
    auto fit = vcg::tri::Allocator<OrientedPointMesh>::GetPerVertexAttribute<float>(out, kFitOffsetAttribute);
    int moved = 0;
    for (size_t i = 0; i < r.surfels.size(); ++i) {
        EXPECT_EQ(fit[i], r.surfels[i].fitOffset) << i;
        moved += fit[i] != 0;
    }
    EXPECT_EQ(moved, r.stats.surfelsFitted);
    // Written again without the fit into the same mesh: no stale attribute.
    ResamplingParams p;
    p.fitOffsets = false;
    WriteSurfels(gstest::Resample(s, p).surfels, out);
    EXPECT_FALSE(vcg::tri::HasPerVertexAttribute(out, kFitOffsetAttribute));
}

// A narrowed blend (the error bound's, or around creases) is stored as SurfelBlendScale, for every surfel.
TEST(ResamplingPipeline, WriteSurfelsStoresBlendScalesWhenNarrowed)
{
    const gstest::PointSet s = gstest::CubeSurface(24, true);
    ResamplingParams p;
    p.maxErrorFraction = 1e-4;
    const ResamplingResult r = gstest::Resample(s, p);
    ASSERT_GT(r.stats.narrowingsForSurfaceBound, 0);
    OrientedPointMesh out;
    WriteSurfels(r.surfels, out);
    ASSERT_TRUE(vcg::tri::HasPerVertexAttribute(out, kBlendScaleAttribute));
    auto blend = vcg::tri::Allocator<OrientedPointMesh>::GetPerVertexAttribute<float>(out, kBlendScaleAttribute);
    for (size_t i = 0; i < r.surfels.size(); ++i) EXPECT_EQ(blend[i], r.surfels[i].blendScale) << i;
    // The default narrows around the cube's edges.
    const ResamplingResult creases = gstest::Resample(s);
    ASSERT_GT(creases.stats.surfelsNarrowedAtCreases, 0);
    WriteSurfels(creases.surfels, out);
    blend = vcg::tri::Allocator<OrientedPointMesh>::GetPerVertexAttribute<float>(out, kBlendScaleAttribute);
    for (size_t i = 0; i < creases.surfels.size(); ++i) EXPECT_EQ(blend[i], creases.surfels[i].blendScale) << i;
    // Written again without narrowing into the same mesh: no stale attribute (Clear() keeps them).
    p = ResamplingParams();
    p.tuning.creaseBlendScale = 1;
    WriteSurfels(gstest::Resample(s, p).surfels, out);
    EXPECT_FALSE(vcg::tri::HasPerVertexAttribute(out, kBlendScaleAttribute));
}

} // namespace
