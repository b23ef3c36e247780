// FlatVector (flat_vector.h): large buffers come 2 MB-aligned on Linux (so that whole huge pages
// can back them) and behave as std::vector across the small and the large allocation paths.
#include <gtest/gtest.h>

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include <vcg_ext/gaussphere/support/flat_vector.h>

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

#if defined(__linux__) && defined(MADV_HUGEPAGE)
/// Whether the page at p is mapped (mincore fails with ENOMEM on unmapped memory).
bool Mapped(const void *p)
{
    unsigned char resident;
    return mincore(const_cast<void *>(p), 4096, &resident) == 0;
}

TEST(FlatVector, FreedLargeBuffersAreReusedOnlyInsideAReuseScope)
{
    using vcg::gaussphere::ReuseLargeBuffers;
    using Cache = vcg::gaussphere::detail::LargeBufferCache;
    const size_t quarterPage = (size_t(2) << 20) / 4 / sizeof(int); // 512 KB: a 2 MB mapping
    const void *keptBuffer = nullptr;
    {
        const ReuseLargeBuffers reuse;
        const int *freed;
        {
            FlatVector<int> first(quarterPage);
            first.back() = 7;
            freed = first.data();
        }
        FlatVector<int> second(3 * quarterPage); // the same mapped size: the freed buffer again
        EXPECT_EQ(second.data(), freed);
        {
            FlatVector<int> tooLarge(3 * Cache::kMaxBufferBytes / sizeof(int)); // freed, not kept
        }
        EXPECT_EQ(Cache::Instance().Take(vcg::gaussphere::detail::MappedBytes(3 * Cache::kMaxBufferBytes)), nullptr);
        {
            const ReuseLargeBuffers nested; // ends before the outer one: keeps what it held
            FlatVector<int> third(quarterPage);
        }
        void *kept = Cache::Instance().Take(size_t(2) << 20);
        ASSERT_NE(kept, nullptr);
        EXPECT_TRUE(Cache::Instance().Keep(kept, size_t(2) << 20));
        keptBuffer = kept;
    }
    // The last scope unmapped what it kept, and nothing is kept without a scope.
    EXPECT_FALSE(Mapped(keptBuffer));
    EXPECT_EQ(Cache::Instance().Take(size_t(2) << 20), nullptr);
    {
        FlatVector<int> unscoped(quarterPage);
    }
    EXPECT_EQ(Cache::Instance().Take(size_t(2) << 20), nullptr);
}
/// Whether the page holding p is in memory.
bool Resident(const void *p)
{
    unsigned char resident = 0;
    void *page = reinterpret_cast<void *>(std::uintptr_t(p) / 4096 * 4096);
    return mincore(page, 4096, &resident) == 0 && (resident & 1);
}

// Cut down in place, a large buffer keeps its address and its kept elements, and its pages past
// them leave memory; a small one is shrunk to fit.
TEST(FlatVector, ReleaseUnusedCapacityDropsThePagesPastTheEnd)
{
    const size_t count = 3 * (size_t(2) << 20) / sizeof(int); // 6 MB
    FlatVector<int> large(count);
    for (size_t i = 0; i < count; ++i) large[i] = int(i);
    const int *before = large.data();
    ASSERT_TRUE(Resident(large.data() + count - 1));
    large.resize(count / 3);
    vcg::gaussphere::ReleaseUnusedCapacity(large);
    EXPECT_EQ(large.data(), before);
    EXPECT_EQ(large.size(), count / 3);
    bool same = true;
    for (size_t i = 0; i < large.size(); ++i) same &= large[i] == int(i);
    EXPECT_TRUE(same);
    EXPECT_TRUE(Resident(large.data() + large.size() - 1));
    EXPECT_FALSE(Resident(large.data() + count / 3 + 4096 / sizeof(int)));
    EXPECT_FALSE(Resident(large.data() + count - 1));
    large.resize(count); // grows again in place: the released pages come back zeroed
    EXPECT_EQ(large.data(), before);
    EXPECT_EQ(large[count - 1], 0);

    FlatVector<int> small(1000);
    small.resize(10);
    vcg::gaussphere::ReleaseUnusedCapacity(small);
    EXPECT_EQ(small.capacity(), 10u);
}
#endif
