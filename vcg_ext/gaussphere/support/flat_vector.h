// FlatVector: a std::vector for large per-point buffers.
// - resize() leaves new elements of trivial types uninitialized: buffers that are filled
//   right away (in parallel) skip a serial zeroing pass over fresh memory.
// - Allocations of 256 KB or more ask Linux for transparent huge pages (2 MB) where the
//   system leaves that choice to programs (/sys/kernel/mm/transparent_hugepage/enabled =
//   madvise, Debian's default): one page fault then maps 2 MB instead of 4 KB. First-touch
//   page faults are a large part of the resampler's time on virtual machines (measured here:
//   11 us per 4 KB page, 0.22 us per 4 KB with huge pages; on the 134,345-point igea a run
//   faulted ~2,400 fresh 4 KB pages, ~25 ms of its ~95). Such a buffer is a mapping of its own,
//   2 MB-aligned and rounded up to whole 2 MB pages, all advised: a buffer of 256 KB may thus
//   hold 2 MB, which caps the waste at 8 times the smallest such buffer; the advice goes with
//   the buffer. Elsewhere than on Linux, plain std::allocator.
// PointArray and IndexArray, FlatVectors of points and of indices, carry the per-point data
// of the algorithms.
#ifndef VCG_EXT_GAUSSPHERE_FLAT_VECTOR_H
#define VCG_EXT_GAUSSPHERE_FLAT_VECTOR_H

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <new>
#include <utility>
#include <vector>

#include <vcg/space/point3.h>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace vcg {
namespace gaussphere {

namespace detail {

constexpr std::size_t kHugePage = std::size_t(2) << 20;

#if defined(__linux__) && defined(MADV_HUGEPAGE)
constexpr std::size_t kHugePageMinBytes = std::size_t(256) << 10;

/// Bytes of the mapping that backs a large buffer: whole 2 MB pages.
inline std::size_t MappedBytes(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }

/// Freed large buffers kept for reuse while a ReuseLargeBuffers scope is open (see there).
class LargeBufferCache
{
public:
    // One huge page each, 8 in all: the buffers of inputs up to ~500,000 points, where faults
    // weigh most. Larger caps kept more memory than they saved time (1 M points: 17 B/point).
    static constexpr std::size_t kMaxBufferBytes = kHugePage;
    static constexpr std::size_t kMaxTotalBytes = 8 * kHugePage;

    LargeBufferCache() { kept_.reserve(kMaxTotalBytes / kHugePage); } // Keep() never allocates

    static LargeBufferCache &Instance()
    {
        // Never destroyed: a static FlatVector may free its buffer after the end of main().
        static LargeBufferCache *cache = new LargeBufferCache;
        return *cache;
    }
    /// A kept mapping of exactly `size` bytes, or null.
    void *Take(std::size_t size)
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (std::size_t b = 0; b < kept_.size(); ++b)
            if (kept_[b].second == size) {
                void *p = kept_[b].first;
                kept_[b] = kept_.back();
                kept_.pop_back();
                keptBytes_ -= size;
                return p;
            }
        return nullptr;
    }
    /// Keeps the mapping if a scope is open and it fits the caps; false: the caller unmaps it.
    bool Keep(void *p, std::size_t size)
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (scopes_ == 0 || size > kMaxBufferBytes || keptBytes_ + size > kMaxTotalBytes) return false;
        kept_.push_back({p, size});
        keptBytes_ += size;
        return true;
    }
    void Enter()
    {
        std::lock_guard<std::mutex> lock(mutex_);
        ++scopes_;
    }
    void Leave()
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (--scopes_ > 0) return;
        for (const auto &k : kept_) munmap(k.first, k.second);
        kept_.clear();
        keptBytes_ = 0;
    }

private:
    std::mutex mutex_;
    int scopes_ = 0;
    std::vector<std::pair<void *, std::size_t>> kept_;
    std::size_t keptBytes_ = 0;
};

/// A private mapping aligned to 2 MB, its whole 2 MB pages advised as huge pages. Its own
/// mapping, not the heap's: the advice ends with the buffer (munmap).
inline void *AllocateLarge(std::size_t bytes)
{
    const std::size_t size = MappedBytes(bytes);
    if (void *kept = LargeBufferCache::Instance().Take(size)) return kept;
    void *raw = mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(raw);
    const std::uintptr_t aligned = (start + kHugePage - 1) / kHugePage * kHugePage;
    if (aligned > start) munmap(raw, aligned - start);
    const std::size_t tail = start + size + kHugePage - (aligned + size);
    if (tail > 0) munmap(reinterpret_cast<void *>(aligned + size), tail);
    void *p = reinterpret_cast<void *>(aligned);
    madvise(p, size, MADV_HUGEPAGE); // advice only: failure is harmless
    return p;
}
inline void FreeLarge(void *p, std::size_t bytes)
{
    if (!LargeBufferCache::Instance().Keep(p, MappedBytes(bytes))) munmap(p, MappedBytes(bytes));
}
#else
constexpr std::size_t kHugePageMinBytes = ~std::size_t(0); // no huge pages to ask for
inline void *AllocateLarge(std::size_t) { throw std::bad_alloc(); }
inline void FreeLarge(void *, std::size_t) {}
#endif

} // namespace detail

/// While one of these is alive (in any thread), freed large FlatVector buffers of up to 2 MB
/// (8 of them) are kept and handed to the next request of the same mapped size, instead
/// of new mappings whose pages the kernel must fault in and zero again: a run allocates
/// dozens of per-point buffers, and a buffer of a few hundred KB still costs a 2 MB page.
/// When the last one ends, the kept buffers are unmapped: nothing outlives the run.
class ReuseLargeBuffers
{
public:
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    ReuseLargeBuffers() { detail::LargeBufferCache::Instance().Enter(); }
    ~ReuseLargeBuffers() { detail::LargeBufferCache::Instance().Leave(); }
#else
    ReuseLargeBuffers() {}
#endif
    ReuseLargeBuffers(const ReuseLargeBuffers &) = delete;
    ReuseLargeBuffers &operator=(const ReuseLargeBuffers &) = delete;
};

template <class T>
struct DefaultInitAllocator : std::allocator<T>
{
    template <class U> struct rebind { typedef DefaultInitAllocator<U> other; };
    DefaultInitAllocator() = default;
    template <class U> DefaultInitAllocator(const DefaultInitAllocator<U> &) noexcept {}

    T *allocate(std::size_t n)
    {
        if (n > std::size_t(-1) / sizeof(T)) throw std::bad_alloc();
        if (n * sizeof(T) < detail::kHugePageMinBytes) return std::allocator<T>::allocate(n);
        return static_cast<T *>(detail::AllocateLarge(n * sizeof(T)));
    }
    void deallocate(T *p, std::size_t n) noexcept
    {
        if (n * sizeof(T) < detail::kHugePageMinBytes) std::allocator<T>::deallocate(p, n);
        else detail::FreeLarge(p, n * sizeof(T));
    }

    template <class U> void construct(U *p) noexcept(noexcept(U())) { ::new (static_cast<void *>(p)) U; }
    template <class U, class... Args> void construct(U *p, Args &&...args)
    {
        ::new (static_cast<void *>(p)) U(std::forward<Args>(args)...);
    }
};

template <class T, class U>
bool operator==(const DefaultInitAllocator<T> &, const DefaultInitAllocator<U> &) { return true; }
template <class T, class U>
bool operator!=(const DefaultInitAllocator<T> &, const DefaultInitAllocator<U> &) { return false; }

template <class T>
using FlatVector = std::vector<T, DefaultInitAllocator<T>>;

/// Returns the memory past v.size() to the system, keeping v's buffer where it is: a buffer cut
/// down in place (resize) stops holding pages it no longer uses without a second buffer to copy
/// into, which would raise the peak it is cut to lower. A large buffer keeps its capacity (its
/// mapping), the pages past the last element dropped (they read as zeros if it grows again); a
/// small one, on the heap, is shrunk to fit.
template <class T>
void ReleaseUnusedCapacity(FlatVector<T> &v)
{
    const std::size_t bytes = v.capacity() * sizeof(T);
    if (bytes < detail::kHugePageMinBytes) {
        v.shrink_to_fit();
        return;
    }
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const std::size_t page = std::size_t(sysconf(_SC_PAGESIZE));
    const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(v.data());
    const std::uintptr_t used = (start + v.size() * sizeof(T) + page - 1) / page * page;
    const std::uintptr_t end = start + detail::MappedBytes(bytes);
    if (end > used) madvise(reinterpret_cast<void *>(used), end - used, MADV_DONTNEED);
#endif
}

/// Positions or normals of a point set, as the algorithms take them.
using PointArray = FlatVector<vcg::Point3f>;
/// Per-point indices (labels, Gaussian triangles, orders).
using IndexArray = FlatVector<int>;

} // namespace gaussphere
} // namespace vcg

#endif
