// SurfelMaker (surfel_recipe.h): surfels updated where a few clusters changed equal the surfels
// made whole, for splits, merges and both, with narrowed blends around creases and fitted offsets.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <vcg_ext/gaussphere/surfels/surfel_recipe.h>

#include "pipeline_support.h"

using namespace vcg::gaussphere;

namespace {

struct Scene
{
    gstest::PointSet s = gstest::CubeSurface(20, true);
    NeighborGraph graph;
    Clustering clusters;
    SurfelRecipe recipe;

    Scene()
    {
        ResamplingParams p;
        p.targetCount = 150;
        const ResamplingResult r = gstest::Resample(s, p);
        clusters.label.assign(r.representative.begin(), r.representative.end());
        clusters.clusterCount = int(r.surfels.size());
        const PointGrid grid(s.points);
        AdaptiveNeighborParams neighbors;
        neighbors.creaseAngle = 45;
        graph = BuildAdaptiveNeighbors(s.points, s.normals, neighbors, grid);
        recipe.generation.weightWidth = 0.01 * 2 * std::sqrt(3.0);
        recipe.creaseBlendScale = 0.65f;
        recipe.fitOffsets = true;
        recipe.pinnedPoints = &graph.crease;
    }
};

void ExpectSameSurfels(const std::vector<Surfel> &a, const std::vector<Surfel> &b, const char *what)
{
    ASSERT_EQ(a.size(), b.size()) << what;
    for (size_t c = 0; c < a.size(); ++c) {
        EXPECT_EQ(a[c].position, b[c].position) << what << " surfel " << c;
        EXPECT_EQ(a[c].normal, b[c].normal) << what << " surfel " << c;
        EXPECT_EQ(a[c].majorAxis, b[c].majorAxis) << what << " surfel " << c;
        EXPECT_EQ(a[c].minorAxis, b[c].minorAxis) << what << " surfel " << c;
        EXPECT_EQ(a[c].memberCount, b[c].memberCount) << what << " surfel " << c;
        EXPECT_EQ(a[c].blendScale, b[c].blendScale) << what << " surfel " << c;
        EXPECT_EQ(a[c].fitOffset, b[c].fitOffset) << what << " surfel " << c;
    }
}

/// The first cluster of 4 or more members split: its first two members stay, the others form a
/// new cluster numbered after the last.
struct FirstSplit
{
    int cluster = 0;
    std::vector<int> first, second;
    Clustering clusters;

    FirstSplit(const Clustering &before, const ClusterMembers &members)
    {
        while (members.Size(cluster) < 4) ++cluster;
        first.assign(members.begin(cluster), members.begin(cluster) + 2);
        second.assign(members.begin(cluster) + 2, members.end(cluster));
        clusters = before;
        for (int i : second) clusters.label[i] = before.clusterCount;
        clusters.clusterCount = before.clusterCount + 1;
    }
};

std::vector<int> Sorted(std::vector<int> v)
{
    std::sort(v.begin(), v.end());
    return v;
}

} // namespace

TEST(SurfelRecipe, UpdateEqualsMake)
{
    const Scene scene;
    const SurfelMaker maker(scene.s.points, scene.s.normals, scene.graph, scene.recipe);
    const SurfelMaker::Set base = maker.Make(scene.clusters);
    const ClusterMembers members(scene.clusters);
    const int count = scene.clusters.clusterCount;
    int narrowed = 0, fitted = 0;
    for (const Surfel &f : base.fitted) {
        narrowed += f.blendScale < 1;
        fitted += f.fitOffset != 0;
    }
    ASSERT_GT(narrowed, 0) << "the scene has narrowed blends";
    ASSERT_GT(fitted, 0) << "and fitted surfels";
    ExpectSameSurfels(MakeSurfels(scene.s.points, scene.s.normals, scene.graph, scene.clusters, scene.recipe), base.fitted,
                      "fitted in place");

    std::mt19937 rng(11);
    std::uniform_int_distribution<int> pick(0, count - 1);
    int splitsChecked = 0, exchangesChecked = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const int c = pick(rng);
        if (members.Size(c) < 2) continue;
        // Split c in two by member order: the second half becomes a new cluster...
        const std::vector<int> all(members.begin(c), members.end(c));
        const std::vector<int> first(all.begin(), all.begin() + all.size() / 2), second(all.begin() + all.size() / 2, all.end());
        Clustering split = scene.clusters;
        for (int i : second) split.label[i] = count;
        split.clusterCount = count + 1;
        ExpectSameSurfels(maker.Update(base, members, split, {c, count}, {first, second}).fitted,
                          maker.Make(split).fitted, "split");
        ++splitsChecked;
        // ... or takes the index of a cluster merged into another.
        const int keep = pick(rng), gone = pick(rng);
        if (keep == gone || keep == c || gone == c) continue;
        Clustering exchanged = scene.clusters;
        for (const int *i = members.begin(gone); i != members.end(gone); ++i) exchanged.label[*i] = keep;
        for (int i : second) exchanged.label[i] = gone;
        std::vector<int> merged(members.begin(keep), members.end(keep));
        merged.insert(merged.end(), members.begin(gone), members.end(gone));
        const SurfelMaker::Set update =
            maker.Update(base, members, exchanged, {c, gone, keep}, {first, second, Sorted(merged)});
        const SurfelMaker::Set whole = maker.Make(exchanged);
        ExpectSameSurfels(update.fitted, whole.fitted, "exchange");
        ExpectSameSurfels(update.unfitted, whole.unfitted, "exchange, unfitted");
        ++exchangesChecked;
    }
    EXPECT_GT(splitsChecked, 20);
    EXPECT_GT(exchangesChecked, 10);
}

// A maker whose graph was cut to the fit's slots (KeepFirstSlots, as merging and the exchanges
// do) makes and updates the same surfels as one on the whole graph, and as MakeSurfels: the narrowed blends come from flags
// taken at construction, the fit reads no further.
TEST(SurfelRecipe, MakeAndUpdateNeedOnlyTheFitsSlots)
{
    const Scene scene;
    const SurfelMaker whole(scene.s.points, scene.s.normals, scene.graph, scene.recipe);
    NeighborGraph cut = scene.graph;
    SurfelRecipe recipe = scene.recipe;
    recipe.pinnedPoints = &cut.crease;
    const SurfelMaker maker(scene.s.points, scene.s.normals, cut, recipe);
    KeepFirstSlots(cut, kOffsetNeighbors);
    ASSERT_EQ(cut.stride, kOffsetNeighbors);
    ASSERT_LT(cut.adjacency.size(), scene.graph.adjacency.size());
    const SurfelMaker::Set base = maker.Make(scene.clusters);
    ExpectSameSurfels(base.fitted, whole.Make(scene.clusters).fitted, "made");
    ExpectSameSurfels(maker.MakeFitted(scene.clusters),
                      MakeSurfels(scene.s.points, scene.s.normals, scene.graph, scene.clusters, scene.recipe),
                      "made fitted in place");
    const ClusterMembers members(scene.clusters);
    const FirstSplit split(scene.clusters, members);
    ExpectSameSurfels(maker.Update(base, members, split.clusters, {split.cluster, scene.clusters.clusterCount},
                                   {split.first, split.second})
                          .fitted,
                      whole.Make(split.clusters).fitted, "updated");
}

// Make's report between generation and fit can stop the fit (a cancel): the set's fitted
// surfels are then the unfitted ones; a report that goes on changes nothing.
TEST(SurfelRecipe, MakeSkipsTheFitWhenTheReportSaysStop)
{
    const Scene scene;
    const SurfelMaker maker(scene.s.points, scene.s.normals, scene.graph, scene.recipe);
    const SurfelMaker::Set whole = maker.Make(scene.clusters);
    int reports = 0;
    const SurfelMaker::Set goOn = maker.Make(scene.clusters, [&reports]() { return ++reports > 0; });
    EXPECT_EQ(reports, 1);
    ExpectSameSurfels(goOn.fitted, whole.fitted, "report going on");
    const SurfelMaker::Set stopped = maker.Make(scene.clusters, []() { return false; });
    ExpectSameSurfels(stopped.unfitted, whole.unfitted, "stopped, unfitted");
    ExpectSameSurfels(stopped.fitted, whole.unfitted, "stopped, fitted");
    int moved = 0;
    for (const Surfel &f : whole.fitted) moved += f.fitOffset != 0;
    EXPECT_GT(moved, 0) << "the scene's fit moves no surfel: the test would not see a skipped fit";
}

// Without a fit or narrowing, the update is the changed clusters' surfels alone.
TEST(SurfelRecipe, UpdateWithoutAdjustments)
{
    Scene scene;
    scene.recipe.fitOffsets = false;
    scene.recipe.creaseBlendScale = 1.f;
    const SurfelMaker maker(scene.s.points, scene.s.normals, scene.graph, scene.recipe);
    const SurfelMaker::Set base = maker.Make(scene.clusters);
    const ClusterMembers members(scene.clusters);
    const FirstSplit split(scene.clusters, members);
    const SurfelMaker::Set update = maker.Update(base, members, split.clusters,
                                                 {split.cluster, scene.clusters.clusterCount}, {split.first, split.second});
    ExpectSameSurfels(update.fitted, maker.Make(split.clusters).fitted, "split");
    for (const Surfel &f : update.fitted) {
        EXPECT_EQ(f.blendScale, 1.f);
        EXPECT_EQ(f.fitOffset, 0.f);
    }
}
