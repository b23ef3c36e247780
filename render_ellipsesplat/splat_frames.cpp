#include "surfel_arrays.h"

#include <vcg_ext/gaussphere/neighbors/point_grid.h>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace splat {

bool isUsableVector(const float *v)
{
    for (int c = 0; c < 3; ++c)
        if (!(std::fabs(v[c]) <= kMaxCoordinate)) // false for NaN too
            return false;
    return true;
}

std::vector<float> nearestNeighbourRadii(const std::vector<float> &positions, int k, const ProgressCallback &progress)
{
    using vcg::gaussphere::PointArray;
    using vcg::gaussphere::PointGrid;
    const std::size_t count = positions.size() / 3;
    std::vector<float> radii(count, 0.0f);
    // The grid takes finite points only, and far ones would overflow its squared distances.
    PointArray points;
    vcg::gaussphere::IndexArray surfelOf; // grid point -> surfel
    points.reserve(count);
    surfelOf.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        if (isUsableVector(&positions[3 * i])) {
            points.emplace_back(&positions[3 * i]);
            surfelOf.push_back(int(i));
        }
    }
    const int n = int(points.size());
    if (n < 2 || k < 1)
        return radii;

    // The grid's construction and the renumbering take about two fifths of the time (5 M points),
    // the search the rest.
    constexpr double kConstructionShare = 0.4;
    constexpr int kConstructionSteps = 4;
    int stepsDone = 0;
    const auto step = [&] {
        if (progress)
            progress(kConstructionShare * std::min(++stepsDone, kConstructionSteps) / kConstructionSteps);
    };
    PointGrid grid(points, PointGrid::kPointsPerCell, step);
    // The points renumbered into the grid's (Morton) order: the search then reads them, and
    // writes its radii, along memory. In a cloud's own order (random, for some files) every
    // access is a cache and TLB miss: 5 M points in random order took seven times longer.
    {
        const vcg::gaussphere::IndexArray &order = grid.Order();
        PointArray sortedPoints(n);
        vcg::gaussphere::IndexArray sortedSurfelOf(n);
#pragma omp parallel for schedule(static)
        for (int s = 0; s < n; ++s) {
            sortedPoints[s] = points[order[s]];
            sortedSurfelOf[s] = surfelOf[order[s]];
        }
        points.swap(sortedPoints); // the grid keeps a reference to `points`
        surfelOf.swap(sortedSurfelOf);
        grid.PointsRenumberedToOrder();
    }
    step();
    vcg::gaussphere::FlatVector<float> sortedRadii(n);
    grid.ForAllKNearest(
        k,
        [&](int i, const int *, const float *squaredDistances, int found) {
            sortedRadii[i] = found > 0 ? std::sqrt(squaredDistances[found - 1]) : 0.0f; // nearest first
        },
        [&](double fraction) {
            if (progress)
                progress(kConstructionShare + (1 - kConstructionShare) * fraction);
            return true;
        });
#pragma omp parallel for schedule(static)
    for (int s = 0; s < n; ++s)
        radii[surfelOf[s]] = sortedRadii[s];
    if (progress)
        progress(1.0);
    return radii;
}

std::size_t removeUnusableSurfels(SurfelArrays &surfels)
{
    const std::size_t count = surfels.size();
    assert(surfels.normals.size() == 3 * count && surfels.majorAxes.size() == 3 * count &&
           surfels.minorAxes.size() == 3 * count);
    const bool colors = surfels.hasColors();
    const auto usable = [&surfels](std::size_t i) {
        const float *n = &surfels.normals[3 * i];
        return isUsableVector(&surfels.positions[3 * i]) && isUsableVector(n) && (n[0] != 0 || n[1] != 0 || n[2] != 0) &&
               isUsableVector(&surfels.majorAxes[3 * i]) && isUsableVector(&surfels.minorAxes[3 * i]);
    };
    std::size_t kept = 0;
    for (std::size_t i = 0; i < count; ++i) {
        if (!usable(i))
            continue;
        if (kept != i) {
            for (std::vector<float> *values : {&surfels.positions, &surfels.normals, &surfels.majorAxes, &surfels.minorAxes})
                std::copy_n(values->begin() + 3 * i, 3, values->begin() + 3 * kept);
            if (colors)
                std::copy_n(surfels.colors.begin() + 4 * i, 4, surfels.colors.begin() + 4 * kept);
        }
        ++kept;
    }
    for (std::vector<float> *values : {&surfels.positions, &surfels.normals, &surfels.majorAxes, &surfels.minorAxes})
        values->resize(3 * kept);
    if (colors)
        surfels.colors.resize(4 * kept);
    return count - kept;
}

void assignCircularFrames(SurfelArrays &surfels, const std::vector<float> &radii)
{
    const std::size_t count = surfels.size();
    surfels.majorAxes.assign(3 * count, 0.0f);
    surfels.minorAxes.assign(3 * count, 0.0f);
    for (std::size_t i = 0; i < count; ++i) {
        vcg::Point3f n(&surfels.normals[3 * i]);
        if (n.SquaredNorm() == 0.0f)
            continue; // no orientation: a degenerate splat the renderer skips
        n.Normalize();
        // Any tangent will do for a circle; cross with the axis least aligned with n is stable.
        const int leastAligned = std::fabs(n[0]) < std::fabs(n[1])
                                     ? (std::fabs(n[0]) < std::fabs(n[2]) ? 0 : 2)
                                     : (std::fabs(n[1]) < std::fabs(n[2]) ? 1 : 2);
        vcg::Point3f axis(0, 0, 0);
        axis[leastAligned] = 1.0f;
        vcg::Point3f e = (axis ^ n).Normalize() * radii[i];
        vcg::Point3f f = (n ^ e);
        for (int c = 0; c < 3; ++c) {
            surfels.majorAxes[3 * i + c] = e[c];
            surfels.minorAxes[3 * i + c] = f[c];
        }
    }
}

void undoFitOffsets(SurfelArrays &surfels, const std::vector<float> &fitOffsets)
{
    assert(fitOffsets.empty() || fitOffsets.size() == surfels.size());
    if (fitOffsets.size() != surfels.size() || surfels.normals.size() != surfels.positions.size())
        return;
    for (std::size_t i = 0; i < fitOffsets.size(); ++i) {
        if (!std::isfinite(fitOffsets[i]))
            continue; // a damaged file must not throw a splat (or the framing box) to infinity
        for (int c = 0; c < 3; ++c)
            surfels.positions[3 * i + c] -= fitOffsets[i] * surfels.normals[3 * i + c];
    }
}

} // namespace splat
