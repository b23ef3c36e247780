// PointGrid::ForAllKNearest against brute force: the grid blocks, their growth to larger
// rings, and the kd-tree fallback (nanoflann) for isolated points must all give the exact k nearest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <vcg_ext/gaussphere/neighbors/point_grid.h>

#include "test_support.h"

namespace {

using vcg::gaussphere::PointGrid;
using gstest::P3;
using gstest::PointArray;
using gstest::IndexArray;

/// The k nearest others of point i by brute force, sorted by (distance, index).
std::vector<std::pair<float, int>> BruteForce(const PointArray &pts, int i, int k)
{
    std::vector<std::pair<float, int>> d;
    for (int j = 0; j < int(pts.size()); ++j)
        if (j != i) d.push_back({(pts[j] - pts[i]).SquaredNorm(), j});
    std::sort(d.begin(), d.end());
    d.resize(std::min<size_t>(d.size(), size_t(k)));
    return d;
}

/// Every point is reported once, with exactly the brute-force neighbours in the same
/// order (ties resolved by index), and never itself.
void ExpectExactAllKNearest(const PointArray &pts, int k)
{
    const PointGrid grid(pts);
    IndexArray calls(pts.size(), 0);
    std::vector<std::vector<float>> got(pts.size());
    std::vector<std::vector<int>> ids(pts.size());
    grid.ForAllKNearest(k, [&](int i, const int *idx, const float *d2, int found) {
        ++calls[i];
        got[i].assign(d2, d2 + found);
        ids[i].assign(idx, idx + found);
    });
    for (int i = 0; i < int(pts.size()); ++i) {
        ASSERT_EQ(calls[i], 1) << "point " << i;
        const std::vector<std::pair<float, int>> expected = BruteForce(pts, i, k);
        ASSERT_EQ(got[i].size(), expected.size()) << "point " << i;
        for (size_t t = 0; t < expected.size(); ++t) {
            EXPECT_EQ(got[i][t], expected[t].first) << "point " << i << " rank " << t;
            EXPECT_EQ(ids[i][t], expected[t].second) << "point " << i << " rank " << t;
        }
    }
    IndexArray order = grid.Order();
    std::sort(order.begin(), order.end());
    for (int i = 0; i < int(order.size()); ++i) EXPECT_EQ(order[i], i) << "Order() is a permutation";
}

PointArray SpherePoints(int n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::normal_distribution<float> g(0.f, 1.f);
    PointArray pts;
    for (int i = 0; i < n; ++i) {
        P3 p(g(rng), g(rng), g(rng));
        pts.push_back(p / p.Norm());
    }
    return pts;
}

TEST(PointGrid, SurfaceSamplingMatchesBruteForce)
{
    ExpectExactAllKNearest(SpherePoints(3000, 1), 16);
}

// Dense clumps far apart: most cells hold many points and the clumps' sparse halo forces
// the block to grow; two lone outliers are left to the final scan of every point.
TEST(PointGrid, UnevenDensityAndOutliersMatchBruteForce)
{
    PointArray pts = SpherePoints(1500, 2);
    for (P3 &p : pts) p *= 0.01f;
    for (const P3 &p : SpherePoints(200, 3)) pts.push_back(p * 0.3f);
    pts.push_back(P3(50, 0, 0));
    pts.push_back(P3(-40, 30, 10));
    ExpectExactAllKNearest(pts, 16);
}

TEST(PointGrid, DuplicatesAndTinySetsMatchBruteForce)
{
    PointArray pts = SpherePoints(300, 4);
    const PointArray copy = pts;
    pts.insert(pts.end(), copy.begin(), copy.end());
    for (int c = 0; c < 40; ++c) pts.push_back(copy[0]);
    ExpectExactAllKNearest(pts, 16);
    ExpectExactAllKNearest(PointArray(25, P3(1, 2, 3)), 16); // all coincide
    ExpectExactAllKNearest(SpherePoints(5, 5), 16);                // fewer than k
    ExpectExactAllKNearest(SpherePoints(1, 6), 16);                // nobody to find
    // More coincident candidates than the ranking takes: the selection path answers.
    PointArray crowded = SpherePoints(400, 7);
    for (int c = 0; c < 300; ++c) crowded.push_back(crowded[c % 3]);
    ExpectExactAllKNearest(crowded, 16);
}

// Many exact copies of one position are answered from the copies alone (else M copies cost
// M^2): in a crowded cell among other points (with a group of exactly k copies, which the
// search must answer, beside it), and among the far outliers that bypass the grid.
TEST(PointGrid, ManyCopiesOfOnePositionMatchBruteForce)
{
    PointArray crowded = SpherePoints(2000, 8);
    for (int c = 0; c < 600; ++c) crowded.push_back(crowded[0]);
    for (int c = 0; c < 15; ++c) crowded.push_back(crowded[1]); // 16 copies: k - 1 others each
    std::swap(crowded[5], crowded[2300]); // copies not only at the end of the index range
    ExpectExactAllKNearest(crowded, 16);

    PointArray farCopies = SpherePoints(3500, 9);
    for (int c = 0; c < 3; ++c) farCopies.push_back(P3(1e5f, 0, 0)); // < 0.1 %: outside the grid
    farCopies.push_back(P3(-1e5f, 0, 0));
    ExpectExactAllKNearest(farCopies, 2);
}

// A dense clump the cell size does not resolve (more than 64 x 8 points in one cell, none
// coincident) is answered by the kd-tree, exactly.
TEST(PointGrid, DenseClumpMatchesBruteForce)
{
    PointArray pts = SpherePoints(2000, 10);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> jitter(-1e-4f, 1e-4f);
    for (int c = 0; c < 700; ++c) pts.push_back(pts[0] + P3(jitter(rng), jitter(rng), jitter(rng)));
    ExpectExactAllKNearest(pts, 16);
}

// The kd-tree orders equal distances by index too: a clump that is a lattice of 11^3 points at
// a power-of-two step (exact distances: ties at every rank, and across the k-th at k = 16, where
// the 12 neighbours at sqrt 2 follow the 6 at 1) is answered by it, exactly.
TEST(PointGrid, DenseLatticeTiesMatchBruteForce)
{
    PointArray pts = SpherePoints(2000, 12);
    const float step = 1.f / (1 << 20);
    for (int x = -5; x <= 5; ++x)
        for (int y = -5; y <= 5; ++y)
            for (int z = -5; z <= 5; ++z) pts.push_back(P3(x * step, y * step, z * step));
    for (int k : {6, 16, 26}) {
        SCOPED_TRACE(k);
        ExpectExactAllKNearest(pts, k);
    }
}

TEST(PointGrid, PlanarGridMatchesBruteForce)
{
    PointArray pts;
    for (int x = 0; x < 40; ++x)
        for (int y = 0; y < 40; ++y) pts.push_back(P3(x * 0.1f, y * 0.1f, 0));
    ExpectExactAllKNearest(pts, 16);
}

// Integer coordinates make exact ties, which counting ranks cannot order: at k = 12 the 12
// nearest of an inner point are 4 at distance 1, 4 at sqrt 2 and 4 at 2, so ties lie inside
// the k nearest with none across the k-th (what the sum of the ranks catches); at k = 16 the
// next four (sqrt 5, of eight) cross it (what the count catches).
TEST(PointGrid, ExactTiesMatchBruteForce)
{
    PointArray pts;
    for (int x = 0; x < 24; ++x)
        for (int y = 0; y < 24; ++y) pts.push_back(P3(float(x), float(y), 0));
    for (int k : {12, 16}) {
        SCOPED_TRACE(k);
        ExpectExactAllKNearest(pts, k);
    }
}

/// With `setting` (a PointGrid switch) set to false: a sphere, crowded cells, planar and integer
/// lattices against brute force. Restores the setting.
void ExpectExactWithSwitchOff(bool &setting)
{
    const bool before = setting;
    setting = false;
    ExpectExactAllKNearest(SpherePoints(3000, 1), 16);
    PointArray crowded = SpherePoints(400, 7);
    for (int c = 0; c < 300; ++c) crowded.push_back(crowded[c % 3]);
    ExpectExactAllKNearest(crowded, 16);
    PointArray planar;
    for (int x = 0; x < 40; ++x)
        for (int y = 0; y < 40; ++y) planar.push_back(P3(x * 0.1f, y * 0.1f, 0));
    ExpectExactAllKNearest(planar, 16);
    PointArray integer;
    for (int x = 0; x < 24; ++x)
        for (int y = 0; y < 24; ++y) integer.push_back(P3(float(x), float(y), 0));
    for (int k : {12, 16}) ExpectExactAllKNearest(integer, k);
    setting = before;
}

// The portable loops (used on CPUs without AVX2) give the same exact answers as the AVX2
// kernels: the hard cases again, with the kernels switched off.
TEST(PointGrid, PortableKernelsMatchBruteForce) { ExpectExactWithSwitchOff(PointGrid::Avx2Kernels()); }

// Grids too large for a dense cell array look cells up in a hash table: the same cases with
// every grid using the table.
TEST(PointGrid, HashedCellTableMatchesBruteForce) { ExpectExactWithSwitchOff(PointGrid::DenseCellTables()); }

} // namespace

namespace {

// A stray point 10^5 model sizes away must not stretch the cells: the grid keeps about
// six points per cell for the model (before, every point fell into one cell and the
// search became quadratic), and the stray point is still answered exactly.
TEST(PointGrid, FarOutlierDoesNotStretchTheCells)
{
    PointArray pts = SpherePoints(20000, 7);
    pts.push_back(P3(1e5f, 0, 0));
    const PointGrid grid(pts);
    EXPECT_GT(grid.CellCount(), 20000 / 20);
    int reported = 0;
    grid.ForAllKNearest(16, [&](int i, const int *, const float *d2, int found) {
        if (i == 20000) {
            EXPECT_EQ(found, 16);
            EXPECT_GT(d2[0], 1e9f);
            ++reported;
        }
    });
    EXPECT_EQ(reported, 1);
}

} // namespace

// The Morton order comes from a radix sort that runs in parallel from 65,536 points on: the same
// order for any thread count, and every point once.
TEST(PointGrid, OrderIsTheSameForAnyThreadCount)
{
    const PointArray pts = SpherePoints(100000, 3);
    IndexArray reference;
    for (int threads : {1, 2, 3}) {
        SCOPED_TRACE(threads);
        const gstest::ScopedThreadCount count(threads);
        const PointGrid grid(pts);
        if (reference.empty()) {
            reference = grid.Order();
            std::vector<char> seen(pts.size(), 0);
            for (int i : reference) seen[i] = 1;
            EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), long(pts.size()));
        } else {
            EXPECT_TRUE(grid.Order() == reference);
        }
    }
}
