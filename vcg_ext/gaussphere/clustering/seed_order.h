// The order in which index propagation (index_propagation.h) takes its seeds: the points sorted
// by a hash of their own coordinates.
//
// Algorithm 1 takes seeds one at a time, and where one cluster ends decides where the next one
// starts. In an order that follows the surface (input order, a space-filling curve) that
// dependence runs from seed to seed across a whole region of one Gaussian triangle: on a flat
// face of millions of points, the clusters near one point then depend on points arbitrarily far
// away, and two overlapping parts of a scan (gstile's tiles) cluster their common region
// differently. In an order unrelated to position, a seed waits only for the nearby seeds that
// come before it, and a chain of seeds, each before the next and within its reach, stays short
// (greedy choices in random order have dependence chains that grow only polylogarithmically with
// the count: Blelloch, Fineman and Shun 2012, for maximal independent sets): what a point's
// cluster depends on lies within a few cluster sizes of it. The hash reads the point's own
// coordinates alone and ignores a power-of-two scale (the resampler's unit scale), so a part of a
// scan gets the same order alone or inside the whole; equal hashes keep the points' own order.
// A salt mixed into the hash gives another order of the same kind: another, equally valid, draw
// of where the clusters start (bench/seed_spread.py measures how the error figures move with it).
#ifndef VCG_EXT_GAUSSPHERE_SEED_ORDER_H
#define VCG_EXT_GAUSSPHERE_SEED_ORDER_H

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>

#include <vcg/space/point3.h>

#include <vcg_ext/gaussphere/support/counting_sort.h>
#include <vcg_ext/gaussphere/support/flat_vector.h>

namespace vcg {
namespace gaussphere {

/// A 32-bit hash of a point that multiplying it by a power of two leaves alone: of each
/// coordinate's sign and mantissa, and of how many binary orders of magnitude it lies below the
/// largest one (splitmix64's mixing over them), started from a value `salt` picks. Zeros hash
/// alike at any scale.
inline std::uint32_t HashPosition(const vcg::Point3f &p, std::uint32_t salt = 0)
{
    std::uint32_t bits[3];
    int largest = 0;
    for (int d = 0; d < 3; ++d) {
        std::memcpy(&bits[d], &p[d], sizeof bits[d]);
        largest = std::max(largest, int(bits[d] >> 23 & 0xff));
    }
    std::uint64_t h = 0x9e3779b97f4a7c15ull ^ std::uint64_t(salt) * 0xd1b54a32d192ed03ull;
    for (int d = 0; d < 3; ++d) {
        const int exponent = int(bits[d] >> 23 & 0xff);
        const std::uint32_t below = exponent == 0 ? 0xffu : std::uint32_t(largest - exponent);
        h = (h ^ ((bits[d] & 0x807fffffu) | below << 23)) * 0xbf58476d1ce4e5b9ull;
        h ^= h >> 31;
        h *= 0x94d049bb133111ebull;
        h ^= h >> 29;
    }
    return std::uint32_t(h >> 32);
}

/// Output: the indices of `points` by increasing HashPosition(point, salt), equal hashes by
/// increasing index. The same for the points multiplied by any power of two (the resampler's unit
/// scale), so a part of a scan, at its own unit scale, gets its points in the same relative order
/// as the whole.
inline IndexArray SeedOrder(const PointArray &points, std::uint32_t salt = 0)
{
    const long long n = (long long)points.size();
    // The hash above the index in one word: half the bytes to sort of a (key, index) pair.
    FlatVector<std::uint64_t> keyed(static_cast<size_t>(n));
#pragma omp parallel for schedule(static)
    for (long long i = 0; i < n; ++i) keyed[size_t(i)] = std::uint64_t(HashPosition(points[size_t(i)], salt)) << 32 | std::uint64_t(i);
    RadixSortStable(keyed, [](std::uint64_t item) { return item >> 32; });
    IndexArray order(static_cast<size_t>(n));
#pragma omp parallel for schedule(static)
    for (long long s = 0; s < n; ++s) order[size_t(s)] = int(std::uint32_t(keyed[size_t(s)]));
    return order;
}

} // namespace gaussphere
} // namespace vcg

#endif
