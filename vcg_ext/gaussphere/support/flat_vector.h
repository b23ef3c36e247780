// FlatVector: a std::vector for large per-point buffers whose resize() leaves new elements of
// trivial types uninitialized: buffers that are filled right away (in parallel) skip a serial
// zeroing pass over fresh memory. PointArray and IndexArray, FlatVectors of points and of
// indices, carry the per-point data of the algorithms.
//
// Buffers of 2 MB or more are mapped on their own, aligned to 2 MB and marked for transparent
// huge pages (Linux), and unmapped when freed: a run touches its large buffers once, and the
// first touch of a 4 KB page costs a page fault each, 512 of them for what one huge page holds.
// Nothing is kept across buffers or runs, and the system's huge-page setting decides whether
// the mark is followed ("never" ignores it). Smaller buffers come from std::allocator.
#ifndef VCG_EXT_GAUSSPHERE_FLAT_VECTOR_H
#define VCG_EXT_GAUSSPHERE_FLAT_VECTOR_H

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include <vcg/space/point3.h>

namespace vcg {
namespace gaussphere {

namespace flat_vector_detail {

/// The size of a transparent huge page on x86-64 Linux (and arm64 with 4 KB pages), and the
/// smallest buffer mapped on its own.
constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

inline bool MappedOnItsOwn(std::size_t bytes)
{
#if defined(__linux__)
    return bytes >= kHugePageBytes;
#else
    (void)bytes;
    return false;
#endif
}

inline std::size_t MappedLength(std::size_t bytes) { return (bytes + kHugePageBytes - 1) & ~(kHugePageBytes - 1); }

/// A mapping of MappedLength(bytes) starting at a multiple of 2 MB, marked for huge pages.
/// \throws std::bad_alloc when the system has no room.
inline void *MapAligned(std::size_t bytes)
{
#if defined(__linux__)
    const std::size_t length = MappedLength(bytes);
    if (length < bytes || length + kHugePageBytes < length) throw std::bad_alloc();
    void *mapped = mmap(nullptr, length + kHugePageBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapped == MAP_FAILED) throw std::bad_alloc();
    const std::uintptr_t start = std::uintptr_t(mapped);
    const std::uintptr_t aligned = (start + kHugePageBytes - 1) & ~std::uintptr_t(kHugePageBytes - 1);
    if (aligned > start) munmap(mapped, aligned - start);
    const std::size_t tail = kHugePageBytes - (aligned - start);
    if (tail > 0) munmap(reinterpret_cast<void *>(aligned + length), tail);
    madvise(reinterpret_cast<void *>(aligned), length, MADV_HUGEPAGE);
    return reinterpret_cast<void *>(aligned);
#else
    (void)bytes;
    throw std::bad_alloc();
#endif
}

inline void Unmap(void *p, std::size_t bytes)
{
#if defined(__linux__)
    munmap(p, MappedLength(bytes));
#else
    (void)p;
    (void)bytes;
#endif
}

} // namespace flat_vector_detail

/// std::allocator whose value-initialization (resize(n), vector(n)) is default-initialization,
/// and whose buffers of 2 MB or more are mapped on their own, for huge pages (file comment).
template <class T>
struct DefaultInitAllocator : std::allocator<T>
{
    template <class U> struct rebind { typedef DefaultInitAllocator<U> other; };
    DefaultInitAllocator() = default;
    template <class U> DefaultInitAllocator(const DefaultInitAllocator<U> &) noexcept {}

    T *allocate(std::size_t n)
    {
        if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
        if (flat_vector_detail::MappedOnItsOwn(n * sizeof(T)))
            return static_cast<T *>(flat_vector_detail::MapAligned(n * sizeof(T)));
        return std::allocator<T>::allocate(n);
    }
    void deallocate(T *p, std::size_t n) noexcept
    {
        if (flat_vector_detail::MappedOnItsOwn(n * sizeof(T))) flat_vector_detail::Unmap(p, n * sizeof(T));
        else std::allocator<T>::deallocate(p, n);
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

/// Positions or normals of a point set, as the algorithms take them.
using PointArray = FlatVector<vcg::Point3f>;
/// Per-point indices (labels, Gaussian triangles, orders).
using IndexArray = FlatVector<int>;

} // namespace gaussphere
} // namespace vcg

#endif
