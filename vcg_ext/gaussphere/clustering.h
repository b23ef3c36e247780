// A partition of points into clusters: one label per point, and the member lists that
// the later stages walk. Points excluded from resampling carry the label -1.
#ifndef VCG_EXT_GAUSSPHERE_CLUSTERING_H
#define VCG_EXT_GAUSSPHERE_CLUSTERING_H

#include <algorithm>
#include <cstdint>
#include <vector>

#include <omp.h>

#include "flat_vector.h"

namespace vcg {
namespace gaussphere {

/// Sorts `v` and drops repeated values.
inline void SortUnique(std::vector<int> &v)
{
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
}

struct Clustering
{
    IndexArray label;        ///< per point: cluster index in [0, clusterCount) or -1
    int clusterCount = 0;

    /// Renumbers clusters 0..count-1 in order of first appearance, dropping empty ones.
    void Compact()
    {
        IndexArray remap(clusterCount, -1);
        int next = 0;
        for (int &l : label) {
            if (l < 0) continue;
            if (remap[l] < 0) remap[l] = next++;
            l = remap[l];
        }
        clusterCount = next;
    }
};

/// Below this many points ClusterMembers sorts on the calling thread alone.
constexpr int kMembersParallelMin = 1 << 16;

/// Members of every cluster, grouped: cluster c owns index[offset[c], offset[c+1]),
/// in increasing point order (a counting sort, so deterministic). Built by every stage that
/// walks clusters, so in parallel: each thread counts and places the members of its own
/// range of points, after those of the ranges before it.
struct ClusterMembers
{
    IndexArray offset;
    IndexArray index;

    explicit ClusterMembers(const Clustering &c)
        : offset(c.clusterCount + 1)
    {
        const int n = int(c.label.size()), count = c.clusterCount;
        const int ranges = n < kMembersParallelMin ? 1 : std::max(1, omp_get_max_threads());
        // cursor[r * count + k]: members of cluster k in point range r, then where they go.
        IndexArray cursor(size_t(ranges) * count);
        const auto rangeBegin = [n, ranges](int r) { return int(std::int64_t(n) * r / ranges); };
#pragma omp parallel for num_threads(ranges) schedule(static, 1)
        for (int r = 0; r < ranges; ++r) {
            int *counted = cursor.data() + size_t(r) * count;
            std::fill(counted, counted + count, 0);
            for (int i = rangeBegin(r); i < rangeBegin(r + 1); ++i)
                if (c.label[i] >= 0) ++counted[c.label[i]];
        }
        int placed = 0;
        for (int k = 0; k < count; ++k) {
            offset[k] = placed;
            for (int r = 0; r < ranges; ++r) {
                const int members = cursor[size_t(r) * count + k];
                cursor[size_t(r) * count + k] = placed;
                placed += members;
            }
        }
        offset[count] = placed;
        index.resize(placed);
#pragma omp parallel for num_threads(ranges) schedule(static, 1)
        for (int r = 0; r < ranges; ++r) {
            int *next = cursor.data() + size_t(r) * count;
            for (int i = rangeBegin(r); i < rangeBegin(r + 1); ++i)
                if (c.label[i] >= 0) index[next[c.label[i]]++] = i;
        }
    }

    int Size(int c) const { return offset[c + 1] - offset[c]; }
    const int *begin(int c) const { return index.data() + offset[c]; }
    const int *end(int c) const { return index.data() + offset[c + 1]; }
};

} // namespace gaussphere
} // namespace vcg

#endif
