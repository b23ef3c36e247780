// ClusterMembers: every labelled point once, grouped by cluster in increasing point order,
// whatever the thread count (the parallel counting sort places each range of points after
// those before it).
#include <gtest/gtest.h>

#include <vector>

#include <vcg_ext/gaussphere/clustering/clustering.h>

#include "test_support.h"

namespace {

using vcg::gaussphere::ClusterMembers;
using vcg::gaussphere::Clustering;

TEST(ClusterMembers, GroupsEveryPointInIncreasingOrderForAnyThreadCount)
{
    for (int n : {1000, 3 * int(vcg::gaussphere::kCountingSortParallelMin) + 7}) { // the serial and the parallel sort
        SCOPED_TRACE(n);
        Clustering c;
        c.clusterCount = 5000;
        c.label.resize(n);
        std::uint32_t state = 12345;
        std::vector<std::vector<int>> expected(c.clusterCount);
        for (int i = 0; i < n; ++i) {
            state = state * 1664525u + 1013904223u;
            int l = int(state >> 8) % (c.clusterCount + 200) - 200; // about 4 % unlabelled
            if (l == 7) l = 8;                                     // cluster 7 stays empty
            c.label[i] = l < 0 ? -1 : l;
            if (l >= 0) expected[l].push_back(i);
        }
        for (int threads : {1, 2, 3}) {
            SCOPED_TRACE(threads);
            const gstest::ScopedThreadCount count(threads);
            const ClusterMembers m(c);
            ASSERT_EQ(int(m.offset.size()), c.clusterCount + 1);
            EXPECT_EQ(m.offset[0], 0);
            int mismatched = 0;
            for (int k = 0; k < c.clusterCount; ++k)
                mismatched += std::vector<int>(m.begin(k), m.end(k)) != expected[k];
            EXPECT_EQ(mismatched, 0);
            EXPECT_EQ(m.Size(7), 0);
        }
    }
}

} // namespace
