#include "surfel_arrays.h"

#include <vcg/space/index/kdtree/kdtree.h>

#include <cassert>
#include <cmath>

namespace splat {

std::vector<float> nearestNeighbourRadii(const std::vector<float> &positions, int k)
{
    const int count = int(positions.size() / 3);
    std::vector<float> radii(count, 0.0f);
    if (count < 2 || k < 1)
        return radii;

    vcg::ConstDataWrapper<vcg::Point3f> points(reinterpret_cast<const vcg::Point3f *>(positions.data()), count);
    vcg::KdTree<float> tree(points);
    const int neighboursWithSelf = std::min(k + 1, count);
#pragma omp parallel
    {
        vcg::KdTree<float>::PriorityQueue queue;
#pragma omp for schedule(static)
        for (int i = 0; i < count; ++i) {
            tree.doQueryK(points[i], neighboursWithSelf, queue);
            radii[i] = std::sqrt(queue.getTopWeight()); // the heap's top is the farthest of the k
        }
    }
    return radii;
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
