// The resampling parameters of a tiled run: fixed once for the whole input by `gstile split`
// and read by every tile's run, so that a tile resamples its points as the whole run would.
//
// Two parameters are relative to the input's bounding box and would otherwise follow each tile's
// own: the weight width h (1 % of the diagonal by default) is fixed in model units, and the
// error bound, a fraction of the whole diagonal, becomes the matching fraction of each tile's.
// A target count (or percentage) is kept whole in the manifest and shared out over the tiles by
// their detail (target_share.h).
#ifndef GSTILE_TILE_PARAMS_H
#define GSTILE_TILE_PARAMS_H

#include <string>

#include <vcg_ext/gaussphere/resampling_params.h>

#include "manifest.h"

namespace gstile {

/// The bounding-box diagonal, in model units, as ResamplePointSet measures it (MeasureUnitScale in
/// usable_points.h), so that h derived from it is the one the whole run uses, to the bit.
double ResamplerDiagonal(const std::array<float, 3> &boxMin, const std::array<float, 3> &boxMax);

/// Fills manifest.options, maxErrorOfDiagonal and targetCount from the user's `param`, for an input
/// of manifest.points points and diagonal manifest.diagonal. False when a target exceeds the points.
bool SetTileOptions(const vcg::gaussphere::ResamplingParams &param, Manifest &manifest, std::string &error);

/// The parameters of a tile whose usable points have the diagonal `tileDiagonal` (ResamplerDiagonal).
bool TileParams(const Manifest &manifest, double tileDiagonal, vcg::gaussphere::ResamplingParams &param,
                std::string &error);

} // namespace gstile

#endif
