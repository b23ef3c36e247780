// FlatVector (flat_vector.h): a std::vector whose resize() default-initializes new elements, so
// that fresh memory for trivial types is not written until the caller fills it.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

#include <vcg_ext/gaussphere/support/flat_vector.h>

using vcg::gaussphere::FlatVector;

namespace {

struct WithDefaults
{
    int value = 7;
    float weight = 0.5f;
};

TEST(FlatVector, NonTrivialElementsAreConstructed)
{
    FlatVector<WithDefaults> v(5);
    v.resize(9);
    for (const WithDefaults &w : v) {
        EXPECT_EQ(w.value, 7);
        EXPECT_EQ(w.weight, 0.5f);
    }
    FlatVector<int> filled(4, 3); // an explicit value is still copied in
    filled.resize(6, -1);
    EXPECT_EQ(filled, (FlatVector<int>{3, 3, 3, 3, -1, -1}));
}

TEST(FlatVector, GrowingAndShrinkingKeepTheValues)
{
    FlatVector<std::int64_t> v;
    const int count = 1 << 20;
    for (int i = 0; i < count; ++i) v.push_back(3 * std::int64_t(i));
    bool same = true;
    for (int i = 0; i < count; ++i) same &= v[i] == 3 * std::int64_t(i);
    EXPECT_TRUE(same);
    v.resize(10);
    v.shrink_to_fit();
    EXPECT_EQ(v.capacity(), 10u);
    EXPECT_EQ(v[9], 27);
    FlatVector<std::int64_t> copy = v, other;
    other.swap(copy);
    EXPECT_EQ(other, v);
}

#if defined(__linux__)
/// Whether the page holding p is in memory.
bool Resident(const void *p)
{
    const std::uintptr_t page = std::uintptr_t(sysconf(_SC_PAGESIZE));
    unsigned char resident = 0;
    void *start = reinterpret_cast<void *>(std::uintptr_t(p) / page * page);
    return mincore(start, page, &resident) == 0 && (resident & 1);
}

// Buffers of a huge page or more start at a huge-page boundary, so that whole huge pages can back
// them; values survive growth from the small buffers to the mapped ones and back.
TEST(FlatVector, LargeBuffersStartAtAHugePageBoundary)
{
    const size_t hugePage = size_t(2) << 20;
    FlatVector<std::int32_t> v;
    for (std::int32_t i = 0; i < (1 << 20); ++i) v.push_back(i); // through 4 KB ... 4 MB buffers
    EXPECT_EQ(std::uintptr_t(v.data()) % hugePage, 0u);
    FlatVector<char> exact(hugePage);
    EXPECT_EQ(std::uintptr_t(exact.data()) % hugePage, 0u);
    v.resize(1000);
    v.shrink_to_fit();
    bool same = v.size() == 1000;
    for (std::int32_t i = 0; i < 1000; ++i) same &= v[size_t(i)] == i;
    EXPECT_TRUE(same);
}

// A buffer no address space can hold is refused with std::bad_alloc, not a crash.
TEST(FlatVector, AnImpossibleBufferThrowsBadAlloc)
{
    FlatVector<char> v;
    EXPECT_THROW(v.reserve(size_t(1) << 50), std::bad_alloc);
    EXPECT_TRUE(v.empty());
}

// 64 MB, above glibc's largest mmap threshold: a fresh mapping whose pages stay out of memory
// until written. A FlatVector of ints leaves them so; a std::vector zeroes (touches) them all.
TEST(FlatVector, ResizeLeavesFreshPagesUntouched)
{
    const size_t count = size_t(16) << 20;
    FlatVector<int> flat;
    flat.resize(count);
    EXPECT_FALSE(Resident(flat.data() + count / 2));
    EXPECT_FALSE(Resident(flat.data() + count - 1));
    flat[count / 2] = 1;
    EXPECT_TRUE(Resident(flat.data() + count / 2));

    std::vector<int> zeroed(count);
    EXPECT_TRUE(Resident(zeroed.data() + count / 2));
}
#endif

} // namespace
