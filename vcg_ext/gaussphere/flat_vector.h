// FlatVector: a std::vector for large per-point buffers.
// - resize() leaves new elements of trivial types uninitialized: buffers that are filled
//   right away (in parallel) skip a serial zeroing pass over fresh memory.
// - Allocations of several megabytes ask Linux for transparent huge pages (2 MB) where the
//   system leaves that choice to programs (/sys/kernel/mm/transparent_hugepage/enabled =
//   madvise, Debian's default): one page fault then maps 2 MB instead of 4 KB. First-touch
//   page faults are a large part of the resampler's time on virtual machines (measured here:
//   11 us per 4 KB page, 0.25 us per 4 KB with huge pages). Only whole 2 MB pages inside the
//   buffer are advised, so no memory beyond the request is ever touched.
#ifndef VCG_EXT_GAUSSPHERE_FLAT_VECTOR_H
#define VCG_EXT_GAUSSPHERE_FLAT_VECTOR_H

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace vcg {
namespace gaussphere {

namespace detail {

constexpr std::size_t kHugePage = std::size_t(2) << 20;
constexpr std::size_t kHugePageMinBytes = kHugePage; // smaller ones hold no whole huge page

inline void *AllocateLarge(std::size_t bytes)
{
    void *p = nullptr;
    if (posix_memalign(&p, kHugePage, bytes) != 0) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(p, bytes / kHugePage * kHugePage, MADV_HUGEPAGE); // advice only: failure is harmless
#endif
    return p;
}

} // namespace detail

template <class T>
struct DefaultInitAllocator : std::allocator<T>
{
    template <class U> struct rebind { typedef DefaultInitAllocator<U> other; };
    DefaultInitAllocator() = default;
    template <class U> DefaultInitAllocator(const DefaultInitAllocator<U> &) noexcept {}

    T *allocate(std::size_t n)
    {
        if (n * sizeof(T) < detail::kHugePageMinBytes) return std::allocator<T>::allocate(n);
        return static_cast<T *>(detail::AllocateLarge(n * sizeof(T)));
    }
    void deallocate(T *p, std::size_t n) noexcept
    {
        if (n * sizeof(T) < detail::kHugePageMinBytes) std::allocator<T>::deallocate(p, n);
        else std::free(p);
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

} // namespace gaussphere
} // namespace vcg

#endif
