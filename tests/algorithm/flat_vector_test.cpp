// FlatVector (flat_vector.h): large buffers come 2 MB-aligned on Linux (so that whole huge pages
// can back them) and behave as std::vector across the small and the large allocation paths.
#include <gtest/gtest.h>

#include <cstdint>

#include <vcg_ext/gaussphere/flat_vector.h>

using vcg::gaussphere::FlatVector;

TEST(FlatVector, LargeBuffersAreAlignedToHugePages)
{
    const size_t hugePage = size_t(2) << 20;
    FlatVector<int> small(1000), large(3 * hugePage / sizeof(int) + 5);
#if defined(__linux__)
    EXPECT_EQ(std::uintptr_t(large.data()) % hugePage, 0u);
#endif
    small[999] = 1;
    large.back() = 2;
    EXPECT_EQ(small[999] + large.back(), 3);
}

TEST(FlatVector, GrowingAcrossTheLargeThresholdKeepsTheValues)
{
    FlatVector<std::int64_t> v;
    const int count = 1 << 20; // 8 MB: starts small, ends large
    for (int i = 0; i < count; ++i) v.push_back(3 * std::int64_t(i));
    bool same = true;
    for (int i = 0; i < count; ++i) same &= v[i] == 3 * std::int64_t(i);
    EXPECT_TRUE(same);
    v.resize(10);
    v.shrink_to_fit(); // back to the small path: the large buffer is unmapped
    EXPECT_EQ(v[9], 27);
}
