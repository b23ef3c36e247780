// A stable counting sort that runs in parallel with the sequential result: each thread counts
// the items of its own range per bucket, and places them after those of the ranges before it
// in every bucket. The cluster member lists (clustering.h) are built this way, and the radix
// sort below, of the grid's cell keys (point_grid.h) and of the point order (morton_order.h).
#ifndef VCG_EXT_GAUSSPHERE_COUNTING_SORT_H
#define VCG_EXT_GAUSSPHERE_COUNTING_SORT_H

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>

#include <omp.h>

#include <vcg_ext/gaussphere/support/flat_vector.h>

namespace vcg {
namespace gaussphere {

/// Below this many items the sort runs on the calling thread alone.
constexpr std::size_t kCountingSortParallelMin = std::size_t(1) << 16;

/// Sorts the items 0..n-1 into `buckets` buckets: bucketOf(i) is item i's bucket in
/// [0, buckets), or -1 to leave it out; place(i, slot) is called once for every item kept, the
/// slots numbered bucket after bucket and, within a bucket, in item order, whatever the thread
/// count. If bucketStart is given, it receives each bucket's first slot and, last, the number
/// of items placed (buckets + 1 values). Returns that number. Count: the counter type (int
/// halves the scratch of ranges x buckets counters where it suffices).
template <class Count, class BucketOf, class Place>
Count StableCountingSort(Count n, std::size_t buckets, BucketOf bucketOf, Place place, Count *bucketStart = nullptr)
{
    const int ranges = std::size_t(n) < kCountingSortParallelMin ? 1 : std::max(1, omp_get_max_threads());
    const auto rangeBegin = [n, ranges](int r) { return Count(std::int64_t(n) * r / ranges); };
    FlatVector<Count> cursor(std::size_t(ranges) * buckets); // [range][bucket]: counts, then next slots
#pragma omp parallel for num_threads(ranges) schedule(static, 1)
    for (int r = 0; r < ranges; ++r) {
        Count *counted = cursor.data() + std::size_t(r) * buckets;
        std::fill(counted, counted + buckets, Count(0));
        for (Count i = rangeBegin(r); i < rangeBegin(r + 1); ++i) {
            const auto b = bucketOf(i);
            if (b >= 0) ++counted[b];
        }
    }
    Count placed = 0;
    for (std::size_t b = 0; b < buckets; ++b) {
        if (bucketStart) bucketStart[b] = placed;
        for (int r = 0; r < ranges; ++r) {
            Count &slot = cursor[std::size_t(r) * buckets + b];
            const Count members = slot;
            slot = placed;
            placed += members;
        }
    }
    if (bucketStart) bucketStart[buckets] = placed;
#pragma omp parallel for num_threads(ranges) schedule(static, 1)
    for (int r = 0; r < ranges; ++r) {
        Count *next = cursor.data() + std::size_t(r) * buckets;
        for (Count i = rangeBegin(r); i < rangeBegin(r + 1); ++i) {
            const auto b = bucketOf(i);
            if (b >= 0) place(i, next[b]++);
        }
    }
    return placed;
}

/// Sorts `items` by keyOf(item), an unsigned 64-bit key, keeping the given order among equal
/// keys: an LSD radix sort with one stable counting pass per 11-bit digit in which the keys differ
/// (a digit that every key shares is skipped): linear in the items, about 0.5 s for 20 M
/// (key, index) pairs, short enough between two progress reports.
template <class Item, class KeyOf>
void RadixSortStable(FlatVector<Item> &items, KeyOf keyOf)
{
    constexpr int kDigitBits = 11;
    constexpr std::size_t kBuckets = std::size_t(1) << kDigitBits;
    const std::size_t n = items.size();
    std::uint64_t anyOne = 0, allOnes = ~std::uint64_t(0);
#pragma omp parallel for schedule(static) reduction(| : anyOne) reduction(& : allOnes)
    for (std::size_t e = 0; e < n; ++e) {
        anyOne |= keyOf(items[e]);
        allOnes &= keyOf(items[e]);
    }
    const std::uint64_t varying = anyOne & ~allOnes;
    FlatVector<Item> scratch(n);
    for (int shift = 0; shift < 64; shift += kDigitBits) {
        if (((varying >> shift) & (kBuckets - 1)) == 0) continue;
        StableCountingSort(
            n, kBuckets, [&](std::size_t e) { return int((keyOf(items[e]) >> shift) & (kBuckets - 1)); },
            [&](std::size_t e, std::size_t slot) { scratch[slot] = items[e]; });
        items.swap(scratch);
    }
}

/// Sorts (key, index) pairs by key, keeping the given order among equal keys (RadixSortStable).
inline void SortByKeyStable(FlatVector<std::pair<std::uint64_t, int>> &keyed)
{
    RadixSortStable(keyed, [](const std::pair<std::uint64_t, int> &item) { return item.first; });
}

/// The indices carried by `keyed` (pairs {key, index}) in increasing key order, equal keys in the
/// given order (SortByKeyStable); `keyed` is left sorted for the caller's further use.
inline IndexArray SortedIndices(FlatVector<std::pair<std::uint64_t, int>> &keyed)
{
    SortByKeyStable(keyed);
    IndexArray order(keyed.size());
#pragma omp parallel for schedule(static)
    for (long long s = 0; s < (long long)keyed.size(); ++s) order[size_t(s)] = keyed[size_t(s)].second;
    return order;
}

} // namespace gaussphere
} // namespace vcg

#endif
