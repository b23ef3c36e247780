// A partition of points into clusters: one label per point, and the member lists that
// the later stages walk. Points excluded from resampling carry the label -1.
#ifndef VCG_EXT_GAUSSPHERE_CLUSTERING_H
#define VCG_EXT_GAUSSPHERE_CLUSTERING_H

#include <algorithm>
#include <vector>

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

/// Members of every cluster, grouped: cluster c owns index[offset[c], offset[c+1]),
/// in increasing point order (a counting sort, so deterministic).
struct ClusterMembers
{
    IndexArray offset;
    IndexArray index;

    explicit ClusterMembers(const Clustering &c)
        : offset(c.clusterCount + 1, 0)
    {
        for (int l : c.label)
            if (l >= 0) ++offset[l + 1];
        for (int k = 0; k < c.clusterCount; ++k) offset[k + 1] += offset[k];
        index.resize(offset.back());
        IndexArray cursor(offset.begin(), offset.end() - 1);
        for (int i = 0; i < int(c.label.size()); ++i)
            if (c.label[i] >= 0) index[cursor[c.label[i]]++] = i;
    }

    int Size(int c) const { return offset[c + 1] - offset[c]; }
    const int *begin(int c) const { return index.data() + offset[c]; }
    const int *end(int c) const { return index.data() + offset[c + 1]; }
};

} // namespace gaussphere
} // namespace vcg

#endif
