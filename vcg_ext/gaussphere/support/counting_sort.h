// A stable counting sort that runs in parallel with the sequential result: each thread counts
// the items of its own range per bucket, and places them after those of the ranges before it
// in every bucket. The cluster member lists (clustering.h) and the grid's radix sort of cell
// keys (point_grid.h) are both built this way.
#ifndef VCG_EXT_GAUSSPHERE_COUNTING_SORT_H
#define VCG_EXT_GAUSSPHERE_COUNTING_SORT_H

#include <algorithm>
#include <cstddef>
#include <cstdint>

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

} // namespace gaussphere
} // namespace vcg

#endif
