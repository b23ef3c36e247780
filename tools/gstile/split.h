// `gstile split`: an oriented point set of any size into tiles of bounded size, in two streaming
// passes over the input (docs/tiling.md).
//   pass 1: the count, the bounding box, a uniform sample (spacing.h); from them the whole input's
//           parameters (tile_params.h), the halo width and the tile grid (tile_grid.h);
//   pass 2: every point into its tile's core file and the halo files of the tiles near it.
#ifndef GSTILE_SPLIT_H
#define GSTILE_SPLIT_H

#include <cstdint>
#include <functional>
#include <string>

#include <vcg_ext/gaussphere/resampling_params.h>

#include "manifest.h"

namespace gstile {

struct SplitOptions
{
    std::uint64_t tilePoints = 4000000; ///< aimed-at points of a tile, halo included: what bounds a run's memory
    double haloSpacings = 24;           ///< halo width in sample spacings (docs/tiling.md: why 24)
    std::size_t bufferBytes = 0;        ///< pass 2's buffers; 0 = one tile's records (tilePoints x 32 B)
    vcg::gaussphere::ResamplingParams param;
};

/// One progress line (`[split] pass 1: 40 % ...`).
typedef std::function<void(const std::string &)> ProgressLine;

/// Splits `input` into `dir` (created if missing; tile files and results of a previous split
/// there are removed) and writes its manifest, also returned in `manifest`.
bool Split(const std::string &input, const std::string &dir, const SplitOptions &options, Manifest &manifest,
           const ProgressLine &progress, std::string &error);

} // namespace gstile

#endif
