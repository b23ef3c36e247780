// The sample spacing of a scan too large to search, from a uniform sample of its points: the
// halo width is a multiple of it (docs/tiling.md).
//
// A random sample of m of the N points of a surface is a sampling of the same surface m/N times
// as dense, so its spacing is sqrt(N/m) times the input's. Each sample point's distance r to its
// j-th nearest sample point gives a local spacing r sqrt(pi m / (N j)) (j points in a disc of
// radius r, at one point per spacing squared); the estimate is a high percentile of those, so
// that the sparser parts of a scan of uneven density get a halo wide enough too.
#ifndef GSTILE_SPACING_H
#define GSTILE_SPACING_H

#include <array>
#include <cstdint>
#include <random>
#include <vector>

namespace gstile {

/// A uniform random sample of fixed size of a stream of points (reservoir sampling), seeded: the
/// same input gives the same sample.
class PointSample
{
public:
    static constexpr std::size_t kSize = 1 << 16;

    void Add(const float p[3]);
    const std::vector<std::array<float, 3>> &Points() const { return points_; }
    std::uint64_t Seen() const { return seen_; }

private:
    std::vector<std::array<float, 3>> points_;
    std::uint64_t seen_ = 0;
    std::mt19937_64 random_{1};
};

/// The spacing of the sampled input (the 90th percentile of the local estimates); 0 when the
/// sample has fewer than two distinct points.
double EstimateSpacing(const PointSample &sample);

} // namespace gstile

#endif
