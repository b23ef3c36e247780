#include "knn_reference.h"

#include <array>
#include <chrono>
#include <cstdint>
#include <vector>

#include <tools/gstile/point_tree.h>

namespace gsbench {

double TimeNanoflannNeighbors(const PointMesh &mesh, int k)
{
    std::vector<std::array<float, 3>> points;
    points.reserve(mesh.vert.size());
    for (const auto &v : mesh.vert)
        if (!v.IsD()) points.push_back({v.P()[0], v.P()[1], v.P()[2]});
    const gstile::PointCloud cloud{points};
    const std::size_t wanted = std::size_t(k) + 1;
    const long count = long(points.size());
    std::vector<std::uint32_t> kthNeighbor(points.size()); // the results, kept so they count

    const auto start = std::chrono::steady_clock::now();
    const gstile::PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)); // builds the index
#pragma omp parallel
    {
        std::vector<std::uint32_t> indices(wanted);
        std::vector<float> squaredDistances(wanted);
#pragma omp for schedule(dynamic, 1024)
        for (long i = 0; i < count; ++i) {
            nanoflann::KNNResultSet<float, std::uint32_t> result(wanted);
            result.init(indices.data(), squaredDistances.data());
#if NANOFLANN_VERSION >= 0x150
            tree.findNeighbors(result, points[i].data(), nanoflann::SearchParameters());
#else
            tree.findNeighbors(result, points[i].data(), nanoflann::SearchParams());
#endif
            kthNeighbor[i] = indices[result.size() - 1];
        }
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace gsbench
