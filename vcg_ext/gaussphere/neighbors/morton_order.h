// The order in which the resampler numbers its points: the Morton (Z-order) curve of the
// octree of power-of-two cubes aligned at the coordinate origin, exact points tied by index.
//
// Why this curve: every later stage breaks ties by point index (equal neighbour distances,
// equal hashes of the seed order, cluster numbering), so the numbering decides the result.
// A point's place on this curve depends on its own coordinates alone (the curve's cubes are
// fixed in space, not fitted to the input), so a part of an input is numbered in the same
// relative order whatever else the input holds, and resampled alike. Multiplying every
// coordinate by a power of two moves every cube boundary to another one: the order survives
// the resampler's unit scale. And like any Morton order it keeps points close in space close
// in memory, which every pass over the points profits from.
//
// How: two points are ordered by the coordinate whose exact binary expansion (sign first)
// differs from the other point's at the highest bit, x before y before z at the same bit.
// For speed, the points of one octant (the sign bits) are sorted by a 63-bit key: the octant,
// then the 20 bits of each coordinate below the highest bit where that octant's points differ
// (the bits above it are the same in all of them), interleaved. Points whose keys tie (closer
// than a millionth of their octant's extent) are then put in order by the exact comparison.
#ifndef VCG_EXT_GAUSSPHERE_MORTON_ORDER_H
#define VCG_EXT_GAUSSPHERE_MORTON_ORDER_H

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include <omp.h>

#include <vcg/space/point3.h>

#include <vcg_ext/gaussphere/support/counting_sort.h>
#include <vcg_ext/gaussphere/support/flat_vector.h>

namespace vcg {
namespace gaussphere {

/// The low 21 bits of v moved to every third bit: interleaving three of these gives a
/// 63-bit Morton (Z-order) code.
inline std::uint64_t MortonSpread(std::uint64_t v)
{
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

namespace morton_detail {

/// |x| as an integer in units of 2^-149 (the smallest float): mantissa << shift, exactly.
struct Magnitude
{
    std::uint32_t mantissa;
    int shift;
};

inline Magnitude MagnitudeOf(float x)
{
    std::uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    const std::uint32_t exponent = (bits >> 23) & 0xff, fraction = bits & 0x7fffff;
    if (exponent == 0) return {fraction, 0}; // zero or subnormal
    return {fraction | 0x800000, int(exponent) - 1};
}

inline int HighestBit(std::uint32_t v) { return 31 - __builtin_clz(v); }

/// The highest bit at which the magnitudes differ, -1 when they are equal. A larger shift
/// belongs to a normal float whose leading bit (23 + shift) is above every bit of the other.
inline int HighestDifferingBit(Magnitude a, Magnitude b)
{
    if (a.shift != b.shift) return 23 + std::max(a.shift, b.shift);
    const std::uint32_t differing = a.mantissa ^ b.mantissa;
    return differing == 0 ? -1 : a.shift + HighestBit(differing);
}

constexpr int kSignLevel = 1 << 10; ///< above every bit of a magnitude
constexpr int kWindowBits = 20;

/// The level at which a and b differ: kSignLevel for opposite signs (-0 counts as +0).
inline int DifferingLevel(float a, float b)
{
    if ((a < 0) != (b < 0)) return kSignLevel;
    return HighestDifferingBit(MagnitudeOf(a), MagnitudeOf(b));
}

/// Bits [low, low + 20) of |x|'s magnitude, inverted for a negative x (so that the window
/// grows with x within an octant).
inline std::uint64_t Window(float x, int low)
{
    const Magnitude m = MagnitudeOf(x);
    const int from = low - m.shift; // the window's lowest bit, counted in the mantissa
    std::uint64_t bits = 0;
    if (from >= 0) bits = from < 24 ? std::uint64_t(m.mantissa) >> from : 0;
    else if (from > -kWindowBits) bits = std::uint64_t(m.mantissa) << -from;
    bits &= (std::uint64_t(1) << kWindowBits) - 1;
    return x < 0 ? ~bits & ((std::uint64_t(1) << kWindowBits) - 1) : bits;
}

inline int OctantOf(const vcg::Point3f &p) { return (p[0] >= 0) << 2 | (p[1] >= 0) << 1 | (p[2] >= 0); }

/// Per octant, the lowest bit of the key's window: 19 bits below the highest bit at which
/// any two of its points differ, in any coordinate (and not below bit 0).
inline std::array<int, 8> WindowLows(const PointArray &points)
{
    std::array<std::array<float, 3>, 8> smallest, largest;
    for (auto &s : smallest) s.fill(std::numeric_limits<float>::infinity());
    for (auto &l : largest) l.fill(-1.f);
    for (const auto &p : points) {
        const int octant = OctantOf(p);
        for (int a = 0; a < 3; ++a) {
            smallest[octant][a] = std::min(smallest[octant][a], std::abs(p[a]));
            largest[octant][a] = std::max(largest[octant][a], std::abs(p[a]));
        }
    }
    std::array<int, 8> low;
    for (int o = 0; o < 8; ++o) {
        int highest = -1;
        for (int a = 0; a < 3 && largest[o][a] >= 0; ++a)
            highest = std::max(highest, HighestDifferingBit(MagnitudeOf(smallest[o][a]), MagnitudeOf(largest[o][a])));
        low[o] = std::max(0, highest - (kWindowBits - 1));
    }
    return low;
}

} // namespace morton_detail

/// Whether a precedes b on the curve (exact; equal points are not ordered).
inline bool MortonLess(const vcg::Point3f &a, const vcg::Point3f &b)
{
    int level = -1, axis = 0;
    for (int c = 0; c < 3; ++c) {
        const int differing = morton_detail::DifferingLevel(a[c], b[c]);
        if (differing > level) level = differing, axis = c;
    }
    return level >= 0 && a[axis] < b[axis];
}

/// The point indices in curve order, equal points in index order. Precondition: finite
/// points (fewer than 2^31). Linear in the points but for ties of the 63-bit key.
inline IndexArray MortonOrder(const PointArray &points)
{
    using namespace morton_detail;
    const int n = int(points.size());
    const std::array<int, 8> low = WindowLows(points);
    FlatVector<std::pair<std::uint64_t, int>> keyed(n);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
        const vcg::Point3f &p = points[i];
        const int octant = OctantOf(p);
        const std::uint64_t key = std::uint64_t(octant) << (3 * kWindowBits) | MortonSpread(Window(p[0], low[octant])) << 2 |
                                  MortonSpread(Window(p[1], low[octant])) << 1 | MortonSpread(Window(p[2], low[octant]));
        keyed[i] = {key, i};
    }
    IndexArray order = SortedIndices(keyed);
    const auto pointLess = [&points](int i, int j) { return MortonLess(points[i], points[j]); };
    for (int s = 0; s < n;) {
        int end = s + 1;
        while (end < n && keyed[end].first == keyed[s].first) ++end;
        if (end - s > 1) std::stable_sort(order.begin() + s, order.begin() + end, pointLess);
        s = end;
    }
    return order;
}

} // namespace gaussphere
} // namespace vcg

#endif
