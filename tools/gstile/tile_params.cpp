#include "tile_params.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <vcg/space/box3.h>
#include <vcg_ext/gaussphere/usable_points.h>

#include <tools/gsresample/resampling_options.h>

using namespace vcg::gaussphere;

namespace gstile {

double ResamplerDiagonal(const std::array<float, 3> &boxMin, const std::array<float, 3> &boxMax)
{
    const vcg::Box3f box(vcg::Point3f(boxMin[0], boxMin[1], boxMin[2]), vcg::Point3f(boxMax[0], boxMax[1], boxMax[2]));
    const UnitScaleBox unit = MeasureUnitScale(box);
    return unit.diagonal / unit.scale;
}

bool SetTileOptions(const ResamplingParams &param, Manifest &manifest, std::string &error)
{
    if (param.spreadEvenly) {
        // Its clusters grow across the whole input from single points: no share of them is a tile's.
        error = "--spread-evenly does not run in tiles; resample the input whole with gsresample";
        return false;
    }
    ResamplingParams tile = param;
    if (tile.weightWidth == 0) tile.weightWidth = 0.01 * manifest.diagonal;
    const SizeControl mode = tile.SizeMode(); // the error bound overrides a target
    manifest.maxErrorOfDiagonal = tile.maxErrorFraction;
    tile.maxErrorFraction = 0;
    manifest.targetCount = 0;
    if (mode == SizeControl::TargetCount) {
        manifest.targetCount = tile.targetCount > 0
                                   ? std::uint64_t(tile.targetCount)
                                   : std::max<std::uint64_t>(1, std::uint64_t(std::llround(
                                                                    tile.targetPercentage / 100.0 * double(manifest.points))));
        if (manifest.targetCount > manifest.points) {
            error = "--target " + std::to_string(manifest.targetCount) + " exceeds the " + std::to_string(manifest.points) +
                    " usable points of the input";
            return false;
        }
        tile.targetCount = 0; // each tile's count comes from its share (target_share.h)
        tile.targetPercentage = 0;
    }
    manifest.options.clear();
    for (const ParameterSpec &spec : ParameterTable()) {
        if (spec.option == nullptr || spec.get == nullptr) continue;
        char value[32];
        std::snprintf(value, sizeof value, "%.17g", spec.get(tile));
        manifest.options.emplace_back(spec.option, value);
    }
    return true;
}

bool TileParams(const Manifest &manifest, double tileDiagonal, ResamplingParams &param, std::string &error)
{
    param = ResamplingParams();
    for (const auto &option : manifest.options) {
        const ParameterSpec *spec = gsresample::FindOption(option.first);
        if (spec == nullptr || !gsresample::SetOption(*spec, option.second, param, error)) {
            error = "manifest option " + option.first + " " + option.second + ": " + (spec ? error : "unknown");
            return false;
        }
    }
    if (manifest.maxErrorOfDiagonal > 0 && tileDiagonal > 0) {
        // A tile much smaller than the bound's length needs no split: the largest valid fraction.
        const double fraction = manifest.maxErrorOfDiagonal * manifest.diagonal / tileDiagonal;
        param.maxErrorFraction = std::min(fraction, std::nextafter(1.0, 0.0));
    }
    error = param.Validate();
    return error.empty();
}

} // namespace gstile
