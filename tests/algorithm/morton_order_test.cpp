// The resampler's point order (morton_order.h): the Z-order of integer lattice points as the
// known answer, the fast key-then-ties sort against a plain sort by the exact comparison on
// awkward floats, and the two properties the resampler relies on: a part of an input keeps its
// relative order whatever else is added, and scaling by a power of two changes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <vcg_ext/gaussphere/neighbors/morton_order.h>

namespace {

using vcg::gaussphere::IndexArray;
using vcg::gaussphere::MortonLess;
using vcg::gaussphere::MortonOrder;
using vcg::gaussphere::PointArray;

std::vector<int> AsVector(const IndexArray &order) { return std::vector<int>(order.begin(), order.end()); }

/// The order of a plain stable sort by the exact comparison.
std::vector<int> ReferenceOrder(const PointArray &points)
{
    std::vector<int> order(points.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = int(i);
    std::stable_sort(order.begin(), order.end(), [&points](int i, int j) { return MortonLess(points[i], points[j]); });
    return order;
}

/// Floats of every kind: both signs, zeros of both signs, subnormals, tiny and huge
/// magnitudes, exact duplicates, and clumps closer than the fast key resolves.
PointArray AwkwardPoints(int n, unsigned seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> unit(-1.f, 1.f);
    std::uniform_int_distribution<int> kind(0, 7), exponent(-140, 120);
    const auto coordinate = [&]() -> float {
        switch (kind(random)) {
        case 0: return 0.f;
        case 1: return -0.f;
        case 2: return unit(random) * std::numeric_limits<float>::denorm_min() * 1000;
        case 3: return std::ldexp(unit(random), exponent(random));
        case 4: return 1.f + unit(random) * 1e-7f; // a clump around 1
        default: return unit(random);
        }
    };
    PointArray points;
    for (int i = 0; i < n; ++i) {
        if (i > 0 && kind(random) == 0) points.push_back(points[size_t(random() % i)]); // a duplicate
        else points.push_back(vcg::Point3f(coordinate(), coordinate(), coordinate()));
    }
    return points;
}

TEST(MortonOrder, OrdersLatticePointsByTheirInterleavedBits)
{
    PointArray points;
    std::vector<std::pair<std::uint64_t, int>> keyed;
    std::mt19937 random(3);
    for (int i = 0; i < 4000; ++i) {
        const int x = int(random() % 1024), y = int(random() % 1024), z = int(random() % 1024);
        points.push_back(vcg::Point3f(float(x), float(y), float(z)));
        std::uint64_t key = 0; // x's bit above y's above z's, level by level
        for (int bit = 9; bit >= 0; --bit)
            key = key << 3 | std::uint64_t((x >> bit) & 1) << 2 | std::uint64_t((y >> bit) & 1) << 1 | ((z >> bit) & 1);
        keyed.push_back({key, i});
    }
    std::stable_sort(keyed.begin(), keyed.end(), [](const auto &a, const auto &b) { return a.first < b.first; });
    std::vector<int> expected;
    for (const auto &k : keyed) expected.push_back(k.second);
    EXPECT_EQ(AsVector(MortonOrder(points)), expected);
}

TEST(MortonOrder, NegativeCoordinatesComeFirstAndGrowAlongTheCurve)
{
    // One coordinate apart: the order is that coordinate's, whatever the signs and magnitudes.
    const PointArray points = {vcg::Point3f(0, 5, 0), vcg::Point3f(0, -3e20f, 0), vcg::Point3f(0, -1e-40f, 0),
                               vcg::Point3f(0, 0, 0), vcg::Point3f(0, 1e-3f, 0), vcg::Point3f(0, -2, 0)};
    EXPECT_EQ(AsVector(MortonOrder(points)), (std::vector<int>{1, 5, 2, 3, 4, 0}));
}

TEST(MortonOrder, IsTheExactComparisonsStableOrder)
{
    for (unsigned seed = 1; seed <= 5; ++seed) {
        const PointArray points = AwkwardPoints(3000, seed);
        EXPECT_EQ(AsVector(MortonOrder(points)), ReferenceOrder(points)) << "seed " << seed;
    }
}

TEST(MortonOrder, ExactComparisonIsAStrictWeakOrder)
{
    const PointArray p = AwkwardPoints(120, 9);
    const auto equivalent = [](const vcg::Point3f &a, const vcg::Point3f &b) { return !MortonLess(a, b) && !MortonLess(b, a); };
    for (const auto &a : p) {
        EXPECT_FALSE(MortonLess(a, a));
        for (const auto &b : p) {
            EXPECT_FALSE(MortonLess(a, b) && MortonLess(b, a));
            for (const auto &c : p) {
                if (MortonLess(a, b) && MortonLess(b, c)) EXPECT_TRUE(MortonLess(a, c));
                if (equivalent(a, b) && equivalent(b, c)) EXPECT_TRUE(equivalent(a, c));
            }
        }
    }
}

TEST(MortonOrder, APartKeepsItsOrderWhateverIsAddedAndAfterScalingByPowersOfTwo)
{
    std::mt19937 random(11);
    std::uniform_real_distribution<float> near(-0.1f, 0.1f), far(-1e4f, 1e4f);
    PointArray part;
    for (int i = 0; i < 5000; ++i) part.push_back(vcg::Point3f(near(random), 0.05f + near(random), near(random)));
    const std::vector<int> alone = AsVector(MortonOrder(part));

    PointArray whole; // the part's points every third place, others around them and far away
    std::vector<int> wholeIndexOf;
    for (int i = 0; i < int(part.size()); ++i) {
        whole.push_back(vcg::Point3f(far(random), far(random), far(random)));
        wholeIndexOf.push_back(int(whole.size()));
        whole.push_back(part[size_t(i)]);
        whole.push_back(vcg::Point3f(near(random), near(random), near(random)));
    }
    std::vector<int> partIndexOf(whole.size(), -1);
    for (int i = 0; i < int(part.size()); ++i) partIndexOf[size_t(wholeIndexOf[size_t(i)])] = i;
    std::vector<int> within;
    for (int w : AsVector(MortonOrder(whole)))
        if (partIndexOf[size_t(w)] >= 0) within.push_back(partIndexOf[size_t(w)]);
    EXPECT_EQ(within, alone);

    for (int e : {-60, -1, 3, 70}) {
        PointArray scaled = part;
        for (auto &p : scaled) p = vcg::Point3f(std::ldexp(p[0], e), std::ldexp(p[1], e), std::ldexp(p[2], e));
        EXPECT_EQ(AsVector(MortonOrder(scaled)), alone) << "scaled by 2^" << e;
    }
}

} // namespace
