// Nearest-rank percentiles of per-point figures, for the error metric and the resampler's
// exchanges, which must read them alike.
#ifndef VCG_EXT_SURFEL_PERCENTILE_H
#define VCG_EXT_SURFEL_PERCENTILE_H

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace vcg {
namespace gaussphere {

/// The nearest rank, from 1, of the `percent` percentile of `count` values in ascending order.
/// \pre count >= 1, 0 < percent <= 100.
inline std::size_t NearestRank(std::size_t count, double percent)
{
    // The relative shrink absorbs the rounding of percent·n/100 (99.9·41000/100 is not exactly
    // 40959 in binary), which would otherwise step to the next rank.
    const double exactRank = percent * double(count) / 100.0 * (1.0 - 1e-12);
    return std::min(count, std::max<std::size_t>(1, std::size_t(std::ceil(exactRank))));
}

/// Nearest-rank percentile: the smallest value v such that at least `percent` % of the values
/// are ≤ v. \pre `values` is non-empty, 0 < percent ≤ 100.
inline double NearestRankPercentile(std::vector<double> values, double percent)
{
    const std::size_t rank = NearestRank(values.size(), percent);
    std::nth_element(values.begin(), values.begin() + (rank - 1), values.end());
    return values[rank - 1];
}

} // namespace gaussphere
} // namespace vcg

#endif
