#include "knn_reference.h"

#include <array>
#include <chrono>
#include <cstdint>
#include <vector>

#include <nanoflann.hpp>

namespace gsbench {
namespace {

struct PointArraySource
{
    std::vector<std::array<float, 3>> points;
    std::size_t kdtree_get_point_count() const { return points.size(); }
    float kdtree_get_pt(std::size_t i, std::size_t axis) const { return points[i][axis]; }
    template <class Box> bool kdtree_get_bbox(Box &) const { return false; }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointArraySource>,
                                                 PointArraySource, 3, std::uint32_t>;

} // namespace

double TimeNanoflannNeighbors(const PointMesh &mesh, int k)
{
    PointArraySource source;
    source.points.reserve(mesh.vert.size());
    for (const auto &v : mesh.vert)
        if (!v.IsD()) source.points.push_back({v.P()[0], v.P()[1], v.P()[2]});
    const std::size_t wanted = std::size_t(k) + 1;
    const long count = long(source.points.size());
    std::vector<std::uint32_t> kthNeighbor(source.points.size()); // the results, kept so they count

    const auto start = std::chrono::steady_clock::now();
    const Tree tree(3, source, nanoflann::KDTreeSingleIndexAdaptorParams(10)); // builds the index
#pragma omp parallel
    {
        std::vector<std::uint32_t> indices(wanted);
        std::vector<float> squaredDistances(wanted);
#pragma omp for schedule(dynamic, 1024)
        for (long i = 0; i < count; ++i) {
            nanoflann::KNNResultSet<float, std::uint32_t> result(wanted);
            result.init(indices.data(), squaredDistances.data());
#if NANOFLANN_VERSION >= 0x150
            tree.findNeighbors(result, source.points[i].data(), nanoflann::SearchParameters());
#else
            tree.findNeighbors(result, source.points[i].data(), nanoflann::SearchParams());
#endif
            kthNeighbor[i] = indices[result.size() - 1];
        }
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace gsbench
