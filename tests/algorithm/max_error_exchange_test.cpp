// Exchanges for the largest error at a fixed count (max_error_exchange.h): the local measure
// (blended_distances.h) agrees with a full one, the exchange keeps the count and lowers the metric's
// Delta*max, and it runs only where it is asked for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <vcg_ext/gaussphere/size_control/blended_distances.h>
#include <vcg_ext/gaussphere/size_control/max_error_exchange.h>

#include "pipeline_support.h"

using namespace vcg::gaussphere;
using gstest::P3;

namespace {

ResamplingParams AtTarget(int count, int exchanges)
{
    ResamplingParams p;
    p.targetCount = count;
    p.maxErrorExchanges = exchanges;
    return p;
}

double Diagonal(const gstest::PointSet &s)
{
    vcg::Box3f box;
    for (const P3 &p : s.points) box.Add(p);
    return box.Diag();
}

vcg::gaussphere::SurfelSurface SurfaceOf(const std::vector<Surfel> &surfels) { return BlendedSurfaceOf(surfels); }

/// The cube's surface sampled 20 a side, jittered: on a regular grid surfel centres tie for the
/// k-th nearest, and which of them a tree returns is arbitrary (max_error_exchange.h).
gstest::PointSet JitteredCube(unsigned seed)
{
    gstest::PointSet cube = gstest::CubeSurface(20, true);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> jitter(-1e-3f, 1e-3f);
    for (P3 &p : cube.points) p += P3(jitter(rng), jitter(rng), jitter(rng));
    return cube;
}

/// What BlendedDistances::BlendedAt gives at point i of `s`, from the surface of all of `surfels`:
/// those blended at the last step of the point's projection that face it, nearest first, by
/// their `number` (-1: left out, counted in `leftOut`).
std::vector<int> BlendedOnTheWholeSurface(const std::vector<Surfel> &surfels, const std::vector<int> &number,
                                          const gstest::PointSet &s, int i, double diagonal, int &leftOut)
{
    const vcg::gaussphere::metric::SurfelErrorParams metric;
    vcg::gaussphere::SurfelSurface::Scratch scratch;
    BlendedSurfaceOf(surfels).Project(vcg::Point3d::Construct(s.points[i]), vcg::Point3d::Construct(s.normals[i]),
                                      metric.maxIterations, metric.convergenceTolerance * diagonal, scratch);
    std::vector<std::pair<float, int>> nearest;
    for (int j = 0; j < scratch.queue.getNofElements(); ++j) {
        const int b = scratch.queue.getIndex(j);
        if (number[size_t(b)] < 0) ++leftOut;
        else if (surfels[size_t(b)].normal.dot(s.normals[i]) > 0) nearest.push_back({scratch.queue.getWeight(j), number[size_t(b)]});
    }
    std::sort(nearest.begin(), nearest.end());
    std::vector<int> blended;
    for (const auto &e : nearest) blended.push_back(e.second);
    return blended;
}

/// `param` for the cube whose first `counted` points count, beside a surround: what a run without
/// exchanges at 120 surfels keeps where the points do not count (coarser than what exchanges make).
ResamplingParams BesideASurround(const gstest::PointSet &cube, int counted, ResamplingParams param)
{
    param.countedVertices = counted;
    const ResamplingResult other = gstest::Resample(cube, AtTarget(120, 0));
    std::vector<char> beyond(other.surfels.size(), 0);
    for (int i = counted; i < cube.Size(); ++i) beyond[size_t(other.representative[size_t(i)])] = 1;
    for (size_t c = 0; c < other.surfels.size(); ++c)
        if (beyond[c]) param.surroundingSurfels.push_back(other.surfels[c]);
    return param;
}

/// The surfels of `r` the crease fit moved: narrowed at a crease and off their clusters' plane.
int MovedAtCreases(const ResamplingResult &r)
{
    return int(std::count_if(r.surfels.begin(), r.surfels.end(),
                             [](const Surfel &s) { return s.blendScale < 1 && s.fitOffset != 0; }));
}

} // namespace

// A projection's reach bounds the surfels it used: a surfel added beyond it changes nothing (up to
// the rounding of sums taken in another order: the tree's), one added at the point changes the
// result.
TEST(MaxErrorExchange, ProjectionReachBoundsTheSurfelsUsed)
{
    const gstest::PointSet cube = gstest::CubeSurface(16, true);
    const ResamplingResult r = gstest::Resample(cube, AtTarget(120, 0));
    const vcg::gaussphere::metric::SurfelErrorParams metric;
    const double tolerance = metric.convergenceTolerance * Diagonal(cube);
    vcg::gaussphere::SurfelSurface::Scratch scratch;
    for (int i : {0, 100, 500, 1000}) {
        const vcg::Point3d q = vcg::Point3d::Construct(cube.points[i]), side = vcg::Point3d::Construct(cube.normals[i]);
        double reach = -1;
        const auto before = SurfaceOf(r.surfels).Project(q, side, metric.maxIterations, tolerance, scratch, &reach);
        ASSERT_GT(reach, 0) << i;
        ASSERT_TRUE(std::isfinite(reach)) << i;
        // A copy of a surfel moved to 1.01 x reach from q, along each axis direction.
        for (int axis = 0; axis < 3; ++axis) {
            std::vector<Surfel> more = r.surfels;
            Surfel far = more.front();
            vcg::Point3d offset(0, 0, 0);
            offset[axis] = 1.01 * reach;
            far.position = vcg::Point3f::Construct(q + offset);
            more.push_back(far);
            const auto after = SurfaceOf(more).Project(q, side, metric.maxIterations, tolerance, scratch);
            EXPECT_LT((after.foot - before.foot).Norm(), 1e-12) << "point " << i << " axis " << axis;
        }
        // A surfel just above q, facing its side, is blended there and lifts the surface.
        std::vector<Surfel> closer = r.surfels;
        Surfel near = closer.front();
        near.normal = vcg::Point3f::Construct(side);
        near.position = vcg::Point3f::Construct(q + side * (0.2 * reach));
        const Eigen::Vector3d tangent = detail::AnyTangent(Eigen::Vector3d(side[0], side[1], side[2])) * (0.5 * reach);
        near.majorAxis = near.minorAxis = vcg::Point3f(float(tangent[0]), float(tangent[1]), float(tangent[2]));
        closer.push_back(near);
        EXPECT_GT((SurfaceOf(closer).Project(q, side, metric.maxIterations, tolerance, scratch).foot - before.foot).Norm(),
                  0.01 * reach) << i;
    }
}

// Measuring a changed set only where its changes reach gives, point by point, the distances of
// measuring it everywhere (up to rounding: a rebuilt tree sums the same weights in another
// order; the changes themselves move distances by up to 1e-2 x diagonal).
TEST(MaxErrorExchange, LocalMeasureEqualsFullMeasure)
{
    const gstest::PointSet cube = JitteredCube(3);
    const ResamplingResult r = gstest::Resample(cube, AtTarget(200, 0));
    const double diagonal = Diagonal(cube);
    BlendedDistances local(cube.points, cube.normals, diagonal);
    local.Reset(r.surfels);
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> pick(0, int(r.surfels.size()) - 1);
    std::vector<Surfel> accepted = r.surfels, changed = r.surfels;
    for (int round = 0; round < 6; ++round) {
        if (round < 5) {
            // Move one surfel along its normal, narrow another's blend, add a copy of a third.
            Surfel &moved = changed[pick(rng)];
            moved.position += moved.normal * float(0.01 * diagonal);
            changed[pick(rng)].blendScale = 0.5f;
            Surfel extra = changed[pick(rng)];
            extra.position += extra.majorAxis * 0.5f;
            changed.push_back(extra);
        } else {
            // Two thirds vanish: the points that lose their surfels reach far beyond their old
            // reach (their surface is the nearby surfels', or every surfel's where that falls short).
            changed.resize(changed.size() / 3);
        }

        BlendedDistances::Measure m = local.Try(accepted, changed);
        if (round < 5) EXPECT_LT(m.points.size(), cube.points.size() / 2) << "round " << round << ": the changes are local";
        local.Accept(std::move(m));
        accepted = changed;
        BlendedDistances full(cube.points, cube.normals, diagonal);
        full.Reset(changed);
        for (int i = 0; i < cube.Size(); ++i)
            ASSERT_NEAR(local.Distance(i), full.Distance(i), 1e-9 * diagonal) << "round " << round << " point " << i;
        EXPECT_NEAR(local.Max(), full.Max(), 1e-9 * diagonal);
        // The surfels blended at a point, read off a surface of the surfels near it, are those
        // of the whole set's surface (facing the point, nearest first).
        std::vector<int> number(changed.size());
        for (size_t c = 0; c < changed.size(); ++c) number[c] = int(c);
        int leftOut = 0;
        for (int i = 0; i < cube.Size(); i += 97)
            EXPECT_EQ(local.BlendedAt(i, changed), BlendedOnTheWholeSurface(changed, number, cube, i, diagonal, leftOut))
                << "round " << round << " point " << i;
    }
}

// At a target count the exchange keeps the count, and the largest distance it reports is the
// metric's Delta*max, lower than without it.
TEST(MaxErrorExchange, LowersTheMetricsLargestDistanceAtTheSameCount)
{
    const gstest::PointSet cube = gstest::CubeSurface(24, true);
    for (int target : {60, 150, 400}) {
        const ResamplingResult without = gstest::Resample(cube, AtTarget(target, 0));
        const ResamplingResult with = gstest::Resample(cube, AtTarget(target, 16));
        gstest::ExpectValidResult(with, cube);
        EXPECT_EQ(int(with.surfels.size()), target);
        EXPECT_EQ(without.stats.exchangeTrials, 0);
        const gstest::Measured before = gstest::Measure(cube, without), after = gstest::Measure(cube, with);
        const ResamplingStats &s = with.stats;
        EXPECT_NEAR(s.exchangeMaxBefore, before.stats.normalizedDistance.max, 1e-7) << target;
        EXPECT_NEAR(s.exchangeMaxAfter, after.stats.normalizedDistance.max, 1e-7) << target;
        EXPECT_GT(s.exchangesForMaxError, 0) << target;
        EXPECT_LT(after.stats.normalizedDistance.max, before.stats.normalizedDistance.max) << target;
        // The figures of the kept surfels, not of the last ones tried.
        int narrowed = 0, fitted = 0;
        for (const Surfel &f : with.surfels) {
            narrowed += f.blendScale < 1;
            fitted += f.fitOffset != 0;
        }
        EXPECT_EQ(s.surfelsNarrowedAtCreases, narrowed);
        EXPECT_EQ(s.surfelsFitted, fitted);
    }
}

TEST(MaxErrorExchange, RoundCapHolds)
{
    const gstest::PointSet cube = gstest::CubeSurface(24, true);
    const ResamplingResult one = gstest::Resample(cube, AtTarget(150, 1));
    const ResamplingResult many = gstest::Resample(cube, AtTarget(150, 16));
    EXPECT_EQ(one.stats.exchangesForMaxError, 1);
    EXPECT_GT(many.stats.exchangesForMaxError, 1);
    EXPECT_LE(many.stats.exchangeMaxAfter, one.stats.exchangeMaxAfter);
    EXPECT_EQ(one.stats.exchangeMaxBefore, many.stats.exchangeMaxBefore);
}

// A tile of a tiled run lowers the largest distance among its core points, which come first: the
// others are measured and blended alike, but no exchange is made for them. Its part of the whole
// run's rounds is the first rounds of a run with them all.
TEST(MaxErrorExchange, OnlyThePointsThatCountSetTheLargestDistance)
{
    const gstest::PointSet cube = gstest::CubeSurface(24, true);
    const double diagonal = Diagonal(cube);
    const gstest::Measured before = gstest::Measure(cube, gstest::Resample(cube, AtTarget(150, 0)));
    // The points before the worst one count (600 of 3,458).
    const int first = int(std::max_element(before.distance.begin(), before.distance.end()) - before.distance.begin());
    const double wholeMax = before.distance[size_t(first)];
    ASSERT_GT(first, 0);
    const double countedMax = *std::max_element(before.distance.begin(), before.distance.begin() + first);
    ASSERT_LT(countedMax, 0.99 * wholeMax);

    ResamplingParams counted = AtTarget(150, 16);
    counted.countedVertices = first;
    const ResamplingResult r = gstest::Resample(cube, counted);
    gstest::ExpectValidResult(r, cube);
    EXPECT_EQ(int(r.surfels.size()), 150);
    ASSERT_EQ(r.exchangeMaxima.size(), std::size_t(r.stats.exchangesForMaxError) + 1);
    EXPECT_GT(r.stats.exchangesForMaxError, 0);
    EXPECT_NEAR(r.exchangeMaxima.front(), countedMax, 1e-6 * diagonal) << "the largest among the points that count";
    for (std::size_t k = 1; k < r.exchangeMaxima.size(); ++k) EXPECT_LT(r.exchangeMaxima[k], r.exchangeMaxima[k - 1]);
    const gstest::Measured after = gstest::Measure(cube, r);
    EXPECT_LE(*std::max_element(after.distance.begin(), after.distance.begin() + first),
              r.exchangeMaxima.back() + 1e-6 * diagonal) << "the crease fit raises no counted point above it";
    // No change raised a point that does not count above its share of the largest distance at
    // the time, of the first one at most (a check of the limit: the cube's halo points need not
    // come near it).
    const double uncountedLimit = kUncountedRiseShare * r.exchangeMaxima.front();
    for (int i = first; i < cube.Size(); ++i)
        ASSERT_LE(after.distance[size_t(i)], std::max<double>(before.distance[size_t(i)], uncountedLimit) + 1e-6 * diagonal)
            << "point " << i;

    // The merge halves take no cluster with a point that does not count: each final cluster with
    // such a point lies within one cluster of the run without exchanges (a merge would join two).
    ResamplingParams noExchanges = counted;
    noExchanges.exchangeRounds = 0;
    const ResamplingResult beforeExchanges = gstest::Resample(cube, noExchanges);
    std::vector<int> within(r.surfels.size(), -1);
    std::vector<char> uncountedMember(r.surfels.size(), 0);
    for (int i = first; i < cube.Size(); ++i) {
        ASSERT_GE(r.representative[size_t(i)], 0) << "the cube has no skipped point";
        uncountedMember[size_t(r.representative[size_t(i)])] = 1;
    }
    for (int i = 0; i < cube.Size(); ++i) {
        const int c = r.representative[size_t(i)], b = beforeExchanges.representative[size_t(i)];
        ASSERT_GE(c, 0);
        if (!uncountedMember[size_t(c)]) continue;
        if (within[size_t(c)] < 0) within[size_t(c)] = b;
        ASSERT_EQ(within[size_t(c)], b) << "surfel " << c << " merged clusters with a point that does not count";
    }

    const ResamplingResult all = gstest::Resample(cube, AtTarget(150, 16));
    EXPECT_NEAR(all.exchangeMaxima.front(), wholeMax, 1e-6 * diagonal);
    ResamplingParams everyVertex = AtTarget(150, 16);
    everyVertex.countedVertices = cube.Size();
    EXPECT_EQ(gstest::Resample(cube, everyVertex).representative, all.representative) << "every vertex counts: as 0";

    ResamplingParams two = counted;
    two.exchangeRounds = 2;
    const ResamplingResult part = gstest::Resample(cube, two);
    ASSERT_GE(r.stats.exchangesForMaxError, 2);
    EXPECT_EQ(part.stats.exchangesForMaxError, 2);
    EXPECT_EQ(part.exchangeMaxima, std::vector<double>(r.exchangeMaxima.begin(), r.exchangeMaxima.begin() + 3));
}

// A surround stands in for the clusters it hides: surfels of its own in their place measure as
// those clusters' did, the hidden surfels count for nothing whatever they become, and a local
// measure beside a surround still equals a full one. The surfels blended at a point are read in
// the clusters' numbering, hidden ones and the surround's left out.
TEST(MaxErrorExchange, ASurroundStandsInForTheClustersItHides)
{
    const gstest::PointSet cube = JitteredCube(5);
    const ResamplingResult r = gstest::Resample(cube, AtTarget(200, 0));
    const double diagonal = Diagonal(cube);
    FixedSurround surround;
    surround.hidden.assign(r.surfels.size(), 0);
    for (size_t c = 0; c < r.surfels.size(); c += 3) {
        surround.hidden[c] = 1;
        surround.surfels.push_back(r.surfels[c]);
    }
    BlendedDistances plain(cube.points, cube.normals, diagonal), beside(cube.points, cube.normals, diagonal, nullptr, &surround);
    plain.Reset(r.surfels);
    beside.Reset(r.surfels);
    for (int i = 0; i < cube.Size(); ++i) ASSERT_NEAR(beside.Distance(i), plain.Distance(i), 1e-9 * diagonal) << i;

    // The hidden surfels moved far off: nothing to measure again.
    std::vector<Surfel> hiddenMoved = r.surfels;
    for (size_t c = 0; c < hiddenMoved.size(); c += 3) hiddenMoved[c].position += hiddenMoved[c].normal * float(0.2 * diagonal);
    EXPECT_TRUE(beside.Try(r.surfels, hiddenMoved).points.empty());

    // Visible ones changed: the local measure is the full one, and differs from the plain run's.
    std::vector<Surfel> changed = hiddenMoved;
    for (size_t c = 1; c < changed.size(); c += 7) changed[c].position += changed[c].normal * float(0.01 * diagonal);
    BlendedDistances::Measure m = beside.Try(r.surfels, changed);
    ASSERT_FALSE(m.points.empty());
    beside.Accept(std::move(m));
    BlendedDistances full(cube.points, cube.normals, diagonal, nullptr, &surround);
    full.Reset(changed);
    for (int i = 0; i < cube.Size(); ++i) ASSERT_NEAR(beside.Distance(i), full.Distance(i), 1e-9 * diagonal) << i;

    // What a point blends: the whole surface of the surround and the visible surfels, mapped to
    // the clusters' numbering, the surround's left out.
    std::vector<Surfel> blended = surround.surfels;
    std::vector<int> cluster(surround.surfels.size(), -1);
    for (size_t c = 0; c < changed.size(); ++c)
        if (!surround.hidden[c]) {
            blended.push_back(changed[c]);
            cluster.push_back(int(c));
        }
    int surroundSeen = 0;
    for (int i = 0; i < cube.Size(); i += 41)
        EXPECT_EQ(beside.BlendedAt(i, changed), BlendedOnTheWholeSurface(blended, cluster, cube, i, diagonal, surroundSeen))
            << "point " << i;
    EXPECT_GT(surroundSeen, 0) << "the surround's surfels are blended at the points sampled";

    // Hidden and not replaced: a third of the surface is gone, the points there measure otherwise.
    FixedSurround holes;
    holes.hidden = surround.hidden;
    BlendedDistances withHoles(cube.points, cube.normals, diagonal, nullptr, &holes);
    withHoles.Reset(r.surfels);
    int moved = 0;
    for (int i = 0; i < cube.Size(); ++i) moved += std::abs(withHoles.Distance(i) - plain.Distance(i)) > 1e-3 * diagonal;
    EXPECT_GT(moved, cube.Size() / 5);
    EXPECT_GT(withHoles.Max(), plain.Max());
}

// The ownership rule of a surround: a cluster is the run's where its member of smallest key
// counts, the keys given or the point indices.
TEST(MaxErrorExchange, ARunKeepsTheClustersWhoseAnchorCounts)
{
    FixedSurround surround;
    surround.anchorKeys = {5, 1, 7, 3};
    const std::vector<char> counted = {0, 1, 1, 0};
    EXPECT_TRUE(surround.Kept({0, 1}, counted)) << "anchor: point 1";
    EXPECT_FALSE(surround.Kept({0, 2, 3}, counted)) << "anchor: point 3";
    EXPECT_TRUE(surround.Kept({2}, counted));
    EXPECT_FALSE(surround.Kept({}, counted));
    Clustering clusters;
    clusters.label = {0, 1, 1, 0, 2};
    clusters.clusterCount = 3;
    surround.anchorKeys = {5, 1, 7, 3, 0};
    const std::vector<char> countedFive = {0, 1, 1, 0, 1};
    surround.HideClustersNotKept(clusters, countedFive);
    EXPECT_EQ(surround.hidden, (std::vector<char>{1, 0, 0})) << "anchors: points 3, 1 and 4";
    surround.anchorKeys.clear();
    surround.HideClustersNotKept(clusters, {1, 0, 1, 1, 0});
    EXPECT_EQ(surround.hidden, (std::vector<char>{0, 1, 1})) << "anchors: points 0, 1 and 4";
}

// Surrounding surfels: the rounds before the seam rounds are those of the run without them; the
// seam rounds keep the count and the number of clusters the run keeps (a split keeps both halves,
// a merge joins two it keeps), lower the largest distance measured beside the surround, and keep
// the crease fit's moves but on the clusters they change.
TEST(MaxErrorExchange, TheSeamRoundsKeepWhatTheRunKeeps)
{
    const gstest::PointSet cube = gstest::CubeSurface(24, true);
    const int counted = cube.Size() / 2;
    ResamplingParams alone = AtTarget(150, 16);
    alone.countedVertices = counted;
    const ResamplingParams param = BesideASurround(cube, counted, alone);
    ASSERT_FALSE(param.surroundingSurfels.empty());

    const ResamplingResult without = gstest::Resample(cube, alone), r = gstest::Resample(cube, param);
    gstest::ExpectValidResult(r, cube);
    EXPECT_EQ(int(r.surfels.size()), 150);
    EXPECT_EQ(r.exchangeMaxima, without.exchangeMaxima) << "the rounds before the seam rounds";
    EXPECT_EQ(without.stats.seamExchanges, 0);
    EXPECT_GT(r.stats.seamExchanges, 0);
    EXPECT_LT(r.stats.seamMaxAfter, r.stats.seamMaxBefore);
    ASSERT_GT(r.stats.creaseFitsForMaxError, 0);
    EXPECT_GE(MovedAtCreases(r), r.stats.creaseFitsForMaxError - 3 * r.stats.seamExchanges)
        << "an exchange changes three clusters; the surfels refitted around them keep their crease moves";
    // The clusters the run keeps: those whose first vertex (the anchor, without anchorKeys) counts.
    const auto keptCount = [counted](const ResamplingResult &result) {
        std::vector<int> anchor(result.surfels.size(), -1);
        for (int i = 0; i < int(result.representative.size()); ++i) {
            const int c = result.representative[size_t(i)];
            if (anchor[size_t(c)] < 0) anchor[size_t(c)] = i;
        }
        return std::count_if(anchor.begin(), anchor.end(), [counted](int a) { return a < counted; });
    };
    EXPECT_EQ(keptCount(r), keptCount(without));

    ResamplingParams uncountedSurround = param;
    uncountedSurround.countedVertices = 0;
    EXPECT_NE(uncountedSurround.Validate(), "");
    ResamplingParams wrongKeys = param;
    wrongKeys.anchorKeys.assign(3, 0);
    EXPECT_THROW(gstest::Resample(cube, wrongKeys), std::invalid_argument);
}

// The seam rounds measure every point, the uncounted ones too, and pass over one that no exchange
// of the run lowers: it stops counting, and may not rise. A run whose share of the rounds is 0
// takes them all the same.
TEST(MaxErrorExchange, TheSeamRoundsPassOverAPointTheRunCannotLower)
{
    const gstest::PointSet cube = gstest::CubeSurface(24, true);
    const int counted = cube.Size() / 2;
    // 32 seam rounds: the set-asides beside the lifted surfel below, and as many after them.
    ResamplingParams alone = AtTarget(150, 32);
    alone.countedVertices = counted;
    alone.exchangeRounds = 0;
    ResamplingParams param = BesideASurround(cube, counted, alone);
    // As low as the rounds go, then down to where they went.
    param.seamTarget = 1e-6 * Diagonal(cube);
    const double reached = gstest::Resample(cube, param).stats.seamMaxAfter;
    param.seamTarget = 1.001 * reached * Diagonal(cube);
    const ResamplingResult mended = gstest::Resample(cube, param);
    EXPECT_EQ(mended.stats.exchangesForMaxError, 0);
    EXPECT_GT(mended.stats.seamExchanges, 0);
    EXPECT_LT(mended.stats.seamMaxAfter, mended.stats.seamMaxBefore);
    EXPECT_LE(mended.stats.seamMaxAfter, 1.001 * reached);

    // The surround's surfel farthest from the counted points, lifted off the surface: the points
    // beside it lie the highest, and only the surround blends there.
    size_t farthest = 0;
    double farthestDistance = -1;
    for (size_t s = 0; s < param.surroundingSurfels.size(); ++s) {
        double nearest = std::numeric_limits<double>::max();
        for (int i = 0; i < counted; ++i)
            nearest = std::min(nearest, double((cube.points[size_t(i)] - param.surroundingSurfels[s].position).Norm()));
        if (nearest > farthestDistance) farthest = s, farthestDistance = nearest;
    }
    Surfel &lifted = param.surroundingSurfels[farthest];
    lifted.position += lifted.normal * (0.2f * float(Diagonal(cube)));
    const ResamplingResult r = gstest::Resample(cube, param);
    gstest::ExpectValidResult(r, cube);
    EXPECT_EQ(int(r.surfels.size()), 150);
    EXPECT_GT(r.stats.seamSetAside, mended.stats.seamSetAside) << "the points beside the lifted surfel";
    EXPECT_EQ(r.stats.seamExchanges, mended.stats.seamExchanges) << "the rounds go on past them";
    EXPECT_EQ(r.representative, mended.representative);

    const ResamplingResult without = gstest::Resample(cube, alone);
    EXPECT_EQ(without.stats.seamExchanges, 0);
    EXPECT_EQ(without.stats.seamSetAside, 0);
}

TEST(MaxErrorExchange, IdenticalOutputForOneAndTwoThreads)
{
    const gstest::PointSet cube = gstest::CubeSurface(24, true);
    ResamplingResult one, two;
    {
        gstest::ScopedThreadCount t(1);
        one = gstest::Resample(cube, AtTarget(150, 16));
    }
    {
        gstest::ScopedThreadCount t(2);
        two = gstest::Resample(cube, AtTarget(150, 16));
    }
    EXPECT_GT(one.stats.exchangesForMaxError, 0);
    EXPECT_EQ(one.stats.exchangesForMaxError, two.stats.exchangesForMaxError);
    EXPECT_EQ(one.stats.exchangeMaxAfter, two.stats.exchangeMaxAfter);
    EXPECT_EQ(one.representative, two.representative);
    ASSERT_EQ(one.surfels.size(), two.surfels.size());
    for (size_t c = 0; c < one.surfels.size(); ++c) EXPECT_EQ(one.surfels[c].position, two.surfels[c].position) << c;
}

// Only at a target count, and not with an error bound (which sets the count itself).
TEST(MaxErrorExchange, OnlyAtATargetCount)
{
    const gstest::PointSet cube = gstest::CubeSurface(16, true);
    ResamplingParams level;
    EXPECT_EQ(gstest::Resample(cube, level).stats.exchangeTrials, 0);
    ResamplingParams bounded = AtTarget(100, 16);
    bounded.maxErrorFraction = 0.01;
    EXPECT_EQ(gstest::Resample(cube, bounded).stats.exchangeTrials, 0);
    // One surfel: nothing to exchange.
    const ResamplingResult single = gstest::Resample(cube, AtTarget(1, 16));
    EXPECT_EQ(single.surfels.size(), 1u);
    EXPECT_EQ(single.stats.exchangeTrials, 0);
    // Two surfels: no pair to merge that does not hold the split one.
    const ResamplingResult two = gstest::Resample(cube, AtTarget(2, 16));
    EXPECT_EQ(two.surfels.size(), 2u);
    EXPECT_EQ(two.stats.exchangeTrials, 0);
}

// Degenerate inputs at a target count: every point at one place (no diagonal, no merge cost),
// copies of a few points, a tiny set.
TEST(MaxErrorExchange, DegenerateInputs)
{
    gstest::PointSet same;
    for (int i = 0; i < 40; ++i) same.Add(P3(1, 2, 3), i % 2 ? P3(0, 0, 1) : P3(1, 0, 0));
    const ResamplingResult coincident = gstest::Resample(same, AtTarget(5, 16));
    gstest::ExpectValidResult(coincident, same);
    EXPECT_EQ(coincident.stats.exchangeTrials, 0);

    gstest::PointSet copies;
    const gstest::PointSet sphere = gstest::FibonacciSphere(60);
    for (int copy = 0; copy < 3; ++copy)
        for (int i = 0; i < sphere.Size(); ++i) copies.Add(sphere.points[i], sphere.normals[i]);
    const ResamplingResult tripled = gstest::Resample(copies, AtTarget(20, 16));
    gstest::ExpectValidResult(tripled, copies);
    EXPECT_EQ(tripled.surfels.size(), 20u);
    EXPECT_LE(tripled.stats.exchangeMaxAfter, tripled.stats.exchangeMaxBefore);

    gstest::PointSet three;
    three.Add(P3(0, 0, 0), P3(0, 0, 1));
    three.Add(P3(1, 0, 0), P3(0, 0, 1));
    three.Add(P3(0, 1, 0), P3(0, 1, 0));
    const ResamplingResult tiny = gstest::Resample(three, AtTarget(3, 16));
    gstest::ExpectValidResult(tiny, three);
    EXPECT_EQ(tiny.surfels.size(), 3u);
}

TEST(MaxErrorExchange, Validation)
{
    ResamplingParams p;
    p.maxErrorExchanges = -1;
    EXPECT_NE(p.Validate().find("MaxErrorExchanges"), std::string::npos);
    p.maxErrorExchanges = 100001;
    EXPECT_NE(p.Validate().find("MaxErrorExchanges"), std::string::npos);
    p.maxErrorExchanges = 0;
    EXPECT_EQ(p.Validate(), "");
}

namespace {
bool stopAtExchanges(int, const char *what) { return std::string(what).find("exchanges") == std::string::npos; }
} // namespace

TEST(MaxErrorExchange, CancelledFromTheCallback)
{
    const gstest::PointSet cube = gstest::CubeSurface(16, true);
    OrientedPointMesh m;
    gstest::ToMesh(cube, m);
    EXPECT_THROW(ResamplePointSet(m, AtTarget(100, 16), stopAtExchanges), ResamplingCancelled);
    EXPECT_NO_THROW(ResamplePointSet(m, AtTarget(100, 0), stopAtExchanges));
}

namespace {
int gExchangeReports = 0, gCancelAtExchangeReport = 0;
bool stopAtNthExchangeReport(int, const char *what)
{
    return std::string(what).find("exchanges") == std::string::npos || ++gExchangeReports < gCancelAtExchangeReport;
}
} // namespace

// Wherever the cancel comes (the merge pairs' set-up, between the first surfels' generation and
// fit, the first measure, a trial), the exchange ends without another report (a cancel between
// generation and fit used to run the fit and report once more).
TEST(MaxErrorExchange, CancelStopsAtOnceAtEveryReport)
{
    const gstest::PointSet cube = gstest::CubeSurface(16, true);
    OrientedPointMesh m;
    gstest::ToMesh(cube, m);
    for (int n = 1; n <= 12; ++n) {
        gExchangeReports = 0;
        gCancelAtExchangeReport = n;
        EXPECT_THROW(ResamplePointSet(m, AtTarget(100, 16), stopAtNthExchangeReport), ResamplingCancelled) << n;
        EXPECT_EQ(gExchangeReports, n);
    }
}

// The merge pairs are sorted as they are read, in chunks: the same order as sorting them all.
TEST(MaxErrorExchange, CheapestFirstReadsInSortedOrder)
{
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> cost(0, 50), cluster(0, 3000);
    std::vector<MergePair> pairs;
    for (int p = 0; p < 5000; ++p) { // repeated costs: the order falls back to the clusters
        const int a = cluster(rng), b = a + 1 + cluster(rng);
        pairs.push_back({double(cost(rng)), a, b});
    }
    std::vector<MergePair> sorted = pairs;
    std::sort(sorted.begin(), sorted.end());
    CheapestFirst lazy(pairs);
    for (size_t i = 0; i < sorted.size(); ++i) {
        const MergePair *p = lazy.At(i);
        ASSERT_NE(p, nullptr);
        ASSERT_TRUE(p->cost == sorted[i].cost && p->a == sorted[i].a && p->b == sorted[i].b) << i;
    }
    EXPECT_EQ(lazy.At(sorted.size()), nullptr);
    EXPECT_TRUE(CheapestFirst().Empty());
    // Keeping the 700 cheapest: the same first 700, then nothing.
    CheapestFirst kept(pairs, 700);
    for (size_t i = 0; i < 700; ++i) {
        const MergePair *p = kept.At(i);
        ASSERT_NE(p, nullptr);
        ASSERT_TRUE(p->cost == sorted[i].cost && p->a == sorted[i].a && p->b == sorted[i].b) << i;
    }
    EXPECT_EQ(kept.At(700), nullptr);
}

// The exchanges' bound on the pairs read: mergeCandidates + the pairs of the
// 3 maxRounds + 1 + 2 mergeCandidates clusters that have the most; all when that is every cluster.
TEST(MaxErrorExchange, PairsReadAtMostCountsTheBusiestClusters)
{
    // A star: cluster 0 paired with 1..40, and a chain 41-42-...-100.
    std::vector<MergePair> pairs;
    for (int b = 1; b <= 40; ++b) pairs.push_back({1.0, 0, b});
    for (int a = 41; a < 100; ++a) pairs.push_back({2.0, a, a + 1});
    MaxErrorExchangeParams param;
    param.maxRounds = 2;
    param.mergeCandidates = 3;
    // 13 excluded at most: the star's centre (40 pairs) and 12 clusters of 2 pairs.
    EXPECT_EQ(PairsReadAtMost(pairs, 101, param), size_t(3 + 40 + 12 * 2));
    param.maxRounds = 40; // 3 * 40 + 1 + 6 >= 101 clusters: every pair
    EXPECT_EQ(PairsReadAtMost(pairs, 101, param), pairs.size());
}

// A trial's label change is undone exactly, cluster count included.
TEST(MaxErrorExchange, LabelChangeUndoes)
{
    Clustering c;
    c.label = {0, 0, 1, 1, 2, 2};
    c.clusterCount = 3;
    const Clustering before = c;
    LabelChange change(c);
    change.Set(1, 3);
    change.Set(4, 0);
    change.Set(1, 2); // set twice: undone to the first value
    c.clusterCount = 4;
    EXPECT_EQ(c.label, IndexArray({0, 2, 1, 1, 0, 2}));
    change.Undo();
    EXPECT_EQ(c.label, before.label);
    EXPECT_EQ(c.clusterCount, before.clusterCount);
    { // a trial left by an exception is undone by the destructor; a kept one is not
        LabelChange dropped(c);
        dropped.Set(0, 2);
    }
    EXPECT_EQ(c.label, before.label);
    {
        LabelChange kept(c);
        kept.Set(0, 2);
        kept.Keep();
    }
    EXPECT_EQ(c.label[0], 2);
}

// The crease fit after the exchanges fits the surfels the fit leaves at creases where that lowers
// the sum of squared distances without raising the largest distance or the 99.9th percentiles: on
// a cube at low counts (every surfel merged and beside an edge), undoing its moves gives the
// metric's figures before it.
TEST(MaxErrorExchange, FitsCreaseSurfelsWhereTheErrorFalls)
{
    const gstest::PointSet cube = gstest::CubeSurface(24, true);
    for (int target : {60, 150}) {
        const ResamplingResult with = gstest::Resample(cube, AtTarget(target, 16));
        gstest::ExpectValidResult(with, cube);
        ResamplingResult without = with;
        int movedAtCreases = 0;
        for (Surfel &s : without.surfels) {
            if (!(s.blendScale < 1) || s.fitOffset == 0) continue;
            ++movedAtCreases;
            s.position -= s.normal * s.fitOffset;
            s.fitOffset = 0;
        }
        EXPECT_GT(movedAtCreases, 0) << target;
        EXPECT_GE(with.stats.creaseFitsForMaxError, movedAtCreases) << target; // reported in the stats
        const gstest::Measured before = gstest::Measure(cube, without), after = gstest::Measure(cube, with);
        const vcg::gaussphere::metric::SurfelErrorStats &b = before.stats, &a = after.stats;
        EXPECT_LT(a.normalizedDistance.rms, b.normalizedDistance.rms) << target;
        EXPECT_LE(a.normalizedDistance.max, b.normalizedDistance.max + 1e-7) << target;
        EXPECT_LE(a.normalizedDistance.p999, b.normalizedDistance.p999 + 1e-7) << target;
        EXPECT_LE(a.normalToBlended.p999, b.normalToBlended.p999 + 1e-6) << target;
        EXPECT_EQ(a.normalToOwnSurfel.rms, b.normalToOwnSurfel.rms) << target; // normals unchanged
        EXPECT_NEAR(with.stats.exchangeMaxAfter, a.normalizedDistance.max, 1e-7) << target;
    }
}

// A tile of a tiled run judges its crease fit against the whole scan's figures
// (crease_fit_limits.h). Given a run's own figures, read back from its report, the output is the
// same surfels; given no limit but the sum of squares, the fit keeps at least as many moves. The
// cube is scaled by 37 so that the limits' model units and the resampler's unit scale differ.
TEST(MaxErrorExchange, TheCreaseFitIsJudgedAgainstTheLimitsGiven)
{
    gstest::PointSet cube = gstest::CubeSurface(24, true);
    for (P3 &p : cube.points) p *= 37.f;
    const int points = int(cube.points.size());
    ResamplingParams reporting = AtTarget(150, 16);
    reporting.reportHighestAtCreaseFit = points; // every point: the report is the whole run's figures
    const ResamplingResult own = gstest::Resample(cube, reporting);
    const CreaseFitEntry &entry = own.creaseFitEntry;
    ASSERT_EQ(entry.distances.size(), std::size_t(points));
    ASSERT_EQ(entry.normalErrors.size(), std::size_t(points));
    EXPECT_TRUE(std::is_sorted(entry.distances.rbegin(), entry.distances.rend())) << "highest first";
    EXPECT_TRUE(std::is_sorted(entry.normalErrors.rbegin(), entry.normalErrors.rend()));
    ASSERT_FALSE(own.exchangeMaxima.empty());
    EXPECT_NEAR(entry.distances.front(), own.exchangeMaxima.back(), 1e-9 * Diagonal(cube))
        << "the highest distance on entry is the largest after the exchanges";
    EXPECT_GT(own.stats.creaseFitsForMaxError, 0);

    // The run's own figures given back: the 99.9th percentiles at their nearest rank from the top.
    const std::size_t fromTop = std::size_t(points) - NearestRank(std::size_t(points), 99.9);
    ResamplingParams same = AtTarget(150, 16);
    same.creaseFitLimits.given = true;
    same.creaseFitLimits.distance = entry.distances[fromTop];
    same.creaseFitLimits.normalError = entry.normalErrors[fromTop];
    const ResamplingResult judgedAlike = gstest::Resample(cube, same);
    const ResamplingResult unreported = gstest::Resample(cube, AtTarget(150, 16));
    EXPECT_EQ(judgedAlike.representative, unreported.representative);
    ASSERT_EQ(judgedAlike.surfels.size(), unreported.surfels.size());
    for (size_t c = 0; c < unreported.surfels.size(); ++c) {
        EXPECT_EQ(judgedAlike.surfels[c].position, unreported.surfels[c].position) << c;
        EXPECT_EQ(judgedAlike.surfels[c].fitOffset, unreported.surfels[c].fitOffset) << c;
    }
    EXPECT_EQ(judgedAlike.stats.creaseFitsForMaxError, own.stats.creaseFitsForMaxError);
    EXPECT_TRUE(unreported.creaseFitEntry.distances.empty()) << "no report unless asked for";

    ResamplingParams loose = same;
    loose.creaseFitLimits.distance = 1e30;
    loose.creaseFitLimits.normalError = 1e30;
    EXPECT_GE(gstest::Resample(cube, loose).stats.creaseFitsForMaxError, own.stats.creaseFitsForMaxError);

    ResamplingParams negative = same;
    negative.creaseFitLimits.distance = -1;
    EXPECT_NE(negative.Validate().find("creaseFitLimits"), std::string::npos);
}
