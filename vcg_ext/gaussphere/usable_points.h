// The input as the resampler sees it: the usable vertices of a mesh, at a unit scale.
//
// A vertex is usable when it is live, its position is finite (in float) and its normal is finite
// and non-zero (its length is taken in double, so very long normals still count). The points are
// multiplied by a power of two that brings their bounding-box diagonal into [1, 2): in binary
// floating point that product is exact, so the resampling of a model in millimetres, metres or
// light years is the same result up to the scale, and no squared distance of it over- or
// underflows (coordinates near the float limit, 3e38, or near 1e-30 otherwise do). At that scale
// points closer than about 1e-19 of the diagonal share one position in the neighbour search (their
// squared distance underflows): a model next to an outlier 1e20 times its size away becomes a few
// surfels, finite ones (tests/algorithm/unit_scale_test.cpp, FarOutliersGiveFiniteSurfels).
#ifndef VCG_EXT_GAUSSPHERE_USABLE_POINTS_H
#define VCG_EXT_GAUSSPHERE_USABLE_POINTS_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <omp.h>

#include <vcg/space/box3.h>
#include <vcg/space/point3.h>

#include <vcg_ext/gaussphere/clustering/clustering.h>

namespace vcg {
namespace gaussphere {

/// Why a vertex is left out, or kUsable.
enum class VertexUse { kUsable, kDeleted, kBadPosition, kBadNormal };

template <class VertexType>
VertexUse ClassifyVertex(const VertexType &v)
{
    if (v.IsD()) return VertexUse::kDeleted;
    const vcg::Point3f p = vcg::Point3f::Construct(v.cP());
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) return VertexUse::kBadPosition;
    const double length = vcg::Point3d::Construct(v.cN()).Norm();
    if (!(std::isfinite(length) && length > 1e-30)) return VertexUse::kBadNormal;
    return VertexUse::kUsable;
}

struct UsablePointCounts
{
    int usable = 0;
    int deleted = 0;
    int badPosition = 0; ///< live vertices whose position is not finite in float
    int badNormal = 0;   ///< live vertices with a finite position and a zero or non-finite normal
    int Live() const { return usable + badPosition + badNormal; }
};

template <class MeshType>
UsablePointCounts CountUsablePoints(const MeshType &mesh)
{
    UsablePointCounts counts;
    for (const auto &v : mesh.vert) {
        switch (ClassifyVertex(v)) {
        case VertexUse::kUsable: ++counts.usable; break;
        case VertexUse::kDeleted: ++counts.deleted; break;
        case VertexUse::kBadPosition: ++counts.badPosition; break;
        case VertexUse::kBadNormal: ++counts.badNormal; break;
        }
    }
    return counts;
}

/// The usable vertices of `mesh` as flat float arrays with unit normals; source[i] = the vertex
/// of point i. One parallel pass: each thread copies the usable vertices of its range of the
/// mesh to the front of the same range of the arrays, then the ranges are closed up (nothing
/// moves when every vertex is usable, the usual case).
template <class MeshType>
UsablePointCounts ReadUsablePoints(const MeshType &mesh, PointArray &points, PointArray &normals, IndexArray &source)
{
    const int vertexCount = int(mesh.vert.size());
    points.resize(vertexCount);
    normals.resize(vertexCount);
    source.resize(vertexCount);
    const int ranges = std::max(1, omp_get_max_threads());
    const auto rangeBegin = [vertexCount, ranges](int r) { return int(std::int64_t(vertexCount) * r / ranges); };
    std::vector<int> kept(size_t(ranges), 0);
    int deleted = 0, badPosition = 0, badNormal = 0;
#pragma omp parallel for num_threads(ranges) schedule(static, 1) reduction(+ : deleted, badPosition, badNormal)
    for (int r = 0; r < ranges; ++r) {
        int next = rangeBegin(r);
        for (int vi = rangeBegin(r); vi < rangeBegin(r + 1); ++vi) {
            const auto &v = mesh.vert[vi];
            switch (ClassifyVertex(v)) {
            case VertexUse::kDeleted: ++deleted; continue;
            case VertexUse::kBadPosition: ++badPosition; continue;
            case VertexUse::kBadNormal: ++badNormal; continue;
            case VertexUse::kUsable: break;
            }
            const vcg::Point3d normal = vcg::Point3d::Construct(v.cN());
            points[next] = vcg::Point3f::Construct(v.cP());
            normals[next] = vcg::Point3f::Construct(normal / normal.Norm());
            source[next] = vi;
            ++next;
        }
        kept[size_t(r)] = next - rangeBegin(r);
    }
    int total = 0;
    for (int r = 0; r < ranges; ++r) {
        const int from = rangeBegin(r), count = kept[size_t(r)];
        if (from != total) { // forward moves: the destination lies before the source
            std::copy(points.begin() + from, points.begin() + from + count, points.begin() + total);
            std::copy(normals.begin() + from, normals.begin() + from + count, normals.begin() + total);
            std::copy(source.begin() + from, source.begin() + from + count, source.begin() + total);
        }
        total += count;
    }
    points.resize(total);
    normals.resize(total);
    source.resize(total);
    UsablePointCounts counts;
    counts.usable = total;
    counts.deleted = deleted;
    counts.badPosition = badPosition;
    counts.badNormal = badNormal;
    return counts;
}

/// The power of two 2^e that brings `diagonal` into [1, 2); 1 for a zero or non-finite diagonal.
inline double UnitScaleOf(double diagonal)
{
    if (!(diagonal > 0 && std::isfinite(diagonal))) return 1.0;
    int exponent = 0;
    std::frexp(diagonal, &exponent); // diagonal = m 2^exponent, m in [0.5, 1)
    return std::ldexp(1.0, 1 - exponent);
}

/// The gap between a float and the next larger one at `magnitude`: the step in which float
/// coordinates that far from the origin are held (about 2^-23 of it).
inline double FloatStepAt(double magnitude)
{
    const float f = float(std::abs(magnitude));
    return double(std::nextafter(f, std::numeric_limits<float>::infinity())) - double(f);
}

/// Float coordinates whose step exceeds this fraction of the bounding-box diagonal are coarse:
/// they lie more than about 100 diagonals from the origin (georeferenced scans lie a million
/// and more away), so rounding moves points by a visible part of their spacing and merges close
/// ones. At the model's own scale the step is 2^-23 of its size.
constexpr double kCoarseFloatStep = 1e-5;

/// The step of float coordinates up to `farthest` from the origin when it is coarse for a model
/// of that bounding-box `diagonal` (kCoarseFloatStep), else 0.
inline double CoarseFloatStep(double farthest, double diagonal)
{
    const double step = FloatStepAt(farthest);
    return diagonal > 0 && step > kCoarseFloatStep * diagonal ? step : 0;
}

/// How the resampler measures points whose bounding box is `box` (model units).
struct UnitScaleBox
{
    double scale = 1;    ///< UnitScaleOf the box's diagonal (taken in double: a float box near 3e38 overflows)
    double diagonal = 0; ///< the diagonal of the box at that scale, computed in float like every length
                         ///< derived from it (exact multiples of the model's, so that a part of an input
                         ///< measures as it does inside the whole)
};

inline UnitScaleBox MeasureUnitScale(const vcg::Box3f &box)
{
    UnitScaleBox measured;
    if (box.IsNull()) return measured;
    const vcg::Point3d lo = vcg::Point3d::Construct(box.min), hi = vcg::Point3d::Construct(box.max);
    measured.scale = UnitScaleOf((hi - lo).Norm());
    const vcg::Box3f unit(vcg::Point3f::Construct(lo * measured.scale), vcg::Point3f::Construct(hi * measured.scale));
    measured.diagonal = unit.Diag();
    return measured;
}

/// points *= scale, exactly for a power of two whose products stay normal floats.
inline void ScalePoints(double scale, PointArray &points)
{
#pragma omp parallel for schedule(static)
    for (int i = 0; i < int(points.size()); ++i)
        points[i] = vcg::Point3f::Construct(vcg::Point3d::Construct(points[i]) * scale);
}

} // namespace gaussphere
} // namespace vcg

#endif
