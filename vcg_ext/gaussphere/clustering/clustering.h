// A partition of points into clusters: one label per point, and the member lists that
// the later stages walk. Points excluded from resampling carry the label -1.
#ifndef VCG_EXT_GAUSSPHERE_CLUSTERING_H
#define VCG_EXT_GAUSSPHERE_CLUSTERING_H

#include <algorithm>
#include <vector>

#include <vcg_ext/gaussphere/support/counting_sort.h>
#include <vcg_ext/gaussphere/support/flat_vector.h>

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

    /// Renumbers clusters 0..count-1 in order of first appearance, dropping empty ones. Returns
    /// each old cluster's new index (-1: empty).
    IndexArray Compact()
    {
        IndexArray remap(clusterCount, -1);
        int next = 0;
        for (int &l : label) {
            if (l < 0) continue;
            if (remap[l] < 0) remap[l] = next++;
            l = remap[l];
        }
        clusterCount = next;
        return remap;
    }
};

/// Members of every cluster, grouped: cluster c owns index[offset[c], offset[c+1]),
/// in increasing point order (a counting sort, so deterministic; built by every stage that
/// walks clusters, so in parallel: counting_sort.h).
struct ClusterMembers
{
    IndexArray offset;
    IndexArray index;

    explicit ClusterMembers(const Clustering &c)
        : offset(c.clusterCount + 1), index(c.label.size())
    {
        const int placed = StableCountingSort(
            int(c.label.size()), size_t(c.clusterCount), [&c](int i) { return c.label[i]; },
            [this](int i, int slot) { index[slot] = i; }, offset.data());
        index.resize(placed);
    }

    int Size(int c) const { return offset[c + 1] - offset[c]; }
    const int *begin(int c) const { return index.data() + offset[c]; }
    const int *end(int c) const { return index.data() + offset[c + 1]; }
    /// Whether a member of cluster c is flagged in `flags` (one flag per point).
    bool AnyFlagged(int c, const FlatVector<char> &flags) const
    {
        return std::any_of(begin(c), end(c), [&flags](int i) { return flags[i] != 0; });
    }
};

} // namespace gaussphere
} // namespace vcg

#endif
