#include "spacing.h"

#include <algorithm>
#include <cmath>

#include "point_tree.h"

namespace gstile {

void PointSample::Add(const float p[3])
{
    ++seen_;
    const std::array<float, 3> point{{p[0], p[1], p[2]}};
    if (points_.size() < kSize) {
        points_.push_back(point);
        return;
    }
    const std::uint64_t slot = random_() % seen_; // the bias of the modulo is below 2^-40
    if (slot < kSize) points_[std::size_t(slot)] = point;
}

double EstimateSpacing(const PointSample &sample)
{
    const std::size_t m = sample.Points().size();
    const std::size_t j = 8;
    if (m <= j) return 0;
    const PointCloud cloud{sample.Points()};
    PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    std::vector<double> local;
    local.reserve(m);
    const double toInput = std::sqrt(M_PI * double(m) / (double(sample.Seen()) * double(j)));
    for (const auto &p : sample.Points()) {
        unsigned index[j + 1];
        float squared[j + 1];
        tree.knnSearch(p.data(), j + 1, index, squared); // the point itself comes first
        local.push_back(std::sqrt(double(squared[j])) * toInput);
    }
    const std::size_t rank = local.size() * 9 / 10;
    std::nth_element(local.begin(), local.begin() + std::ptrdiff_t(rank), local.end());
    return local[rank];
}

} // namespace gstile
