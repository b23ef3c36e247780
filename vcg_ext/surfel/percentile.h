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

/// Nearest-rank percentile: the smallest value v such that at least `percent` % of the values
/// are ≤ v. \pre `values` is non-empty, 0 < percent ≤ 100.
inline double NearestRankPercentile(std::vector<double> values, double percent)
{
    // The relative shrink absorbs the rounding of percent·n/100 (99.9·41000/100 is not exactly
    // 40959 in binary), which would otherwise step to the next rank.
    const double exactRank = percent * double(values.size()) / 100.0 * (1.0 - 1e-12);
    const std::size_t rank =
        std::min(values.size(), std::max<std::size_t>(1, std::size_t(std::ceil(exactRank))));
    std::nth_element(values.begin(), values.begin() + (rank - 1), values.end());
    return values[rank - 1];
}

} // namespace gaussphere
} // namespace vcg

#endif
