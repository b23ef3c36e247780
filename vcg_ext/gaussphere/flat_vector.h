// FlatVector: a std::vector whose resize() leaves new elements of trivial types
// uninitialized. Large per-point buffers that are filled right away (in parallel) then
// skip a serial zeroing pass over fresh memory, whose page faults alone cost tens of
// milliseconds per million points on some virtual machines.
#ifndef VCG_EXT_GAUSSPHERE_FLAT_VECTOR_H
#define VCG_EXT_GAUSSPHERE_FLAT_VECTOR_H

#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace vcg {
namespace gaussphere {

template <class T>
struct DefaultInitAllocator : std::allocator<T>
{
    template <class U> struct rebind { typedef DefaultInitAllocator<U> other; };
    DefaultInitAllocator() = default;
    template <class U> DefaultInitAllocator(const DefaultInitAllocator<U> &) noexcept {}
    template <class U> void construct(U *p) noexcept { ::new (static_cast<void *>(p)) U; }
    template <class U, class... Args> void construct(U *p, Args &&...args)
    {
        ::new (static_cast<void *>(p)) U(std::forward<Args>(args)...);
    }
};

template <class T>
using FlatVector = std::vector<T, DefaultInitAllocator<T>>;

} // namespace gaussphere
} // namespace vcg

#endif
