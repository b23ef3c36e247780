// FlatVector: a std::vector for large per-point buffers whose resize() leaves new elements of
// trivial types uninitialized: buffers that are filled right away (in parallel) skip a serial
// zeroing pass over fresh memory. The memory comes from std::allocator: how pages are mapped,
// and whether freed memory is kept, is the host application's and the system's choice.
// PointArray and IndexArray, FlatVectors of points and of indices, carry the per-point data
// of the algorithms.
#ifndef VCG_EXT_GAUSSPHERE_FLAT_VECTOR_H
#define VCG_EXT_GAUSSPHERE_FLAT_VECTOR_H

#include <memory>
#include <new>
#include <utility>
#include <vector>

#include <vcg/space/point3.h>

namespace vcg {
namespace gaussphere {

/// std::allocator whose value-initialization (resize(n), vector(n)) is default-initialization.
template <class T>
struct DefaultInitAllocator : std::allocator<T>
{
    template <class U> struct rebind { typedef DefaultInitAllocator<U> other; };
    DefaultInitAllocator() = default;
    template <class U> DefaultInitAllocator(const DefaultInitAllocator<U> &) noexcept {}

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
