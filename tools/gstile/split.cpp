#include "split.h"

#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "point_stream.h"
#include "spacing.h"
#include "target_share.h"
#include "tile_params.h"
#include "tile_writer.h"

namespace gstile {

namespace {

/// What pass 1 learns about the input.
struct Survey
{
    std::uint64_t usable = 0, skipped = 0;
    std::array<float, 3> boxMin{{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                                 std::numeric_limits<float>::max()}};
    std::array<float, 3> boxMax{{-std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                                 -std::numeric_limits<float>::max()}};
    PointSample sample;
};

/// Calls `each(chunk)` for every chunk of the input, positions relative to `origin`, with a
/// progress line every tenth.
bool StreamInput(const std::string &input, const std::array<double, 3> &origin, const std::string &pass,
                 const ProgressLine &progress,
                 const std::function<bool(const std::vector<OrientedPoint> &, std::uint64_t first)> &each,
                 std::string &error)
{
    PointStream stream;
    if (!stream.Open(input, error)) return false;
    stream.SetOrigin(origin);
    std::vector<OrientedPoint> chunk;
    int reported = 0;
    while (true) {
        const std::uint64_t first = stream.ReadSoFar();
        if (!stream.Next(chunk, error)) break;
        if (!each(chunk, first)) return false;
        const int tenth = int(10 * stream.ReadSoFar() / std::max<std::uint64_t>(1, stream.Count()));
        if (tenth > reported) {
            reported = tenth;
            char line[96];
            std::snprintf(line, sizeof line, "[split] %s: %d %% (%.1f M of %.1f M points)", pass.c_str(), 10 * tenth,
                          stream.ReadSoFar() / 1e6, stream.Count() / 1e6);
            progress(line);
        }
    }
    return error.empty();
}

/// The origin the tiles' positions are relative to, into `manifest`: for double coordinates the
/// first usable point's position (a point of the model is near enough for their precision, and
/// the same point of a moved copy moves with it); 0 for float ones.
bool ChooseOrigin(const std::string &input, Manifest &manifest, std::string &error)
{
    PointStream stream;
    if (!stream.Open(input, error)) return false;
    manifest.doubleCoordinates = stream.HasDoubleCoordinates();
    return !manifest.doubleCoordinates || stream.FirstUsablePosition(manifest.origin, error) || error.empty();
}

bool SurveyInput(const std::string &input, const std::array<double, 3> &origin, const ProgressLine &progress,
                 Survey &survey, std::string &error)
{
    return StreamInput(input, origin, "pass 1 (survey)", progress, [&survey](const std::vector<OrientedPoint> &chunk, std::uint64_t) {
        for (const OrientedPoint &p : chunk) {
            if (!IsUsable(p)) {
                ++survey.skipped;
                continue;
            }
            ++survey.usable;
            for (int a = 0; a < 3; ++a) {
                survey.boxMin[a] = std::min(survey.boxMin[a], p.position[a]);
                survey.boxMax[a] = std::max(survey.boxMax[a], p.position[a]);
            }
            survey.sample.Add(p.position);
        }
        return true;
    }, error);
}

/// The tile grid for the survey's box and sample, and the halo width, into `manifest`; false when
/// tiles of the size asked for cannot hold their halo.
bool PlanTiles(const Survey &survey, const SplitOptions &options, Manifest &manifest, const ProgressLine &progress,
               std::string &error)
{
    for (int a = 0; a < 3; ++a) {
        manifest.boxMin[a] = survey.boxMin[a];
        manifest.boxMax[a] = survey.boxMax[a];
    }
    manifest.points = survey.usable;
    manifest.skipped = survey.skipped;
    manifest.diagonal = ResamplerDiagonal(survey.boxMin, survey.boxMax);
    manifest.spacing = EstimateSpacing(survey.sample);
    manifest.haloSpacings = options.haloSpacings;
    manifest.halo = options.haloSpacings * manifest.spacing;
    OccupancyHistogram histogram(manifest.boxMin, manifest.boxMax);
    for (const auto &p : survey.sample.Points()) histogram.Add(p.data());
    histogram.Finish(double(survey.usable) / std::max<std::size_t>(1, survey.sample.Points().size()));
    const TileGridChoice choice = ChooseTileGrid(histogram, manifest.halo, double(options.tilePoints));
    manifest.grid = choice.grid;
    char line[160];
    std::snprintf(line, sizeof line,
                  "[split] %.1f M usable points (%llu skipped), spacing %.4g, halo %.4g; %dx%dx%d tiles of edge %.4g, "
                  "the fullest ~%.2f M points with its halo",
                  survey.usable / 1e6, (unsigned long long)survey.skipped, manifest.spacing, manifest.halo,
                  choice.grid.dims[0], choice.grid.dims[1], choice.grid.dims[2], choice.grid.edge,
                  choice.largestTilePoints / 1e6);
    progress(line);
    if (choice.fits) return true;
    char reason[240];
    std::snprintf(reason, sizeof reason,
                  "tiles of at most %llu points cannot hold a halo of %g spacings: the narrowest tiles allowed (as "
                  "wide as the halo) hold about %.0f points with it; raise --tile-points or lower --halo-spacings",
                  (unsigned long long)options.tilePoints, options.haloSpacings, choice.largestTilePoints);
    error = reason;
    return false;
}

bool WriteTiles(const std::string &input, const std::string &dir, const SplitOptions &options, Manifest &manifest,
                const ProgressLine &progress, std::string &error)
{
    const std::size_t bufferBytes = options.bufferBytes > 0 ? options.bufferBytes : options.tilePoints * sizeof(TilePoint);
    TileWriter writer(dir, manifest.grid.TileCount(), bufferBytes);
    const TileGrid &grid = manifest.grid;
    const double halo = manifest.halo;
    const bool read = StreamInput(input, manifest.origin, "pass 2 (tiles)", progress,
                                  [&](const std::vector<OrientedPoint> &chunk, std::uint64_t first) {
        for (std::size_t i = 0; i < chunk.size(); ++i) {
            const OrientedPoint &p = chunk[i];
            if (!IsUsable(p)) continue;
            TilePoint record{{p.position[0], p.position[1], p.position[2]}, {p.normal[0], p.normal[1], p.normal[2]},
                             first + i};
            const GridCell home = grid.CellOf(p.position);
            writer.Add(grid.IdOf(home), true, record);
            grid.ForHaloTiles(p.position, halo, home, [&](int id) { writer.Add(id, false, record); });
        }
        return writer.Error().empty();
    }, error);
    if (!read) {
        if (error.empty()) error = writer.Error();
        return false;
    }
    if (!writer.Finish(manifest.tiles)) {
        error = writer.Error();
        return false;
    }
    return true;
}

/// Creates `dir` if missing, and removes the manifest, shares and tile files of a previous split there.
bool PrepareDirectory(const std::string &dir, std::string &error)
{
    if (::mkdir(dir.c_str(), 0777) != 0 && errno != EEXIST) {
        error = "cannot create " + dir + ": " + std::strerror(errno);
        return false;
    }
    std::remove(ManifestPath(dir).c_str());
    std::remove(SharesPath(dir).c_str());
    DIR *d = ::opendir(dir.c_str());
    if (d == nullptr) {
        error = "cannot open " + dir + ": " + std::strerror(errno);
        return false;
    }
    while (const dirent *entry = ::readdir(d))
        if (std::strncmp(entry->d_name, "tile_", 5) == 0) std::remove((dir + "/" + entry->d_name).c_str());
    ::closedir(d);
    return true;
}

} // namespace

bool Split(const std::string &input, const std::string &dir, const SplitOptions &options, Manifest &manifest,
           const ProgressLine &progress, std::string &error)
{
    manifest = Manifest();
    manifest.input = input;
    Survey survey;
    if (!ChooseOrigin(input, manifest, error) || !SurveyInput(input, manifest.origin, progress, survey, error))
        return false;
    if (survey.usable < 2) {
        error = "the input has " + std::to_string(survey.usable) + " usable point(s); at least 2 are needed";
        return false;
    }
    if (!PlanTiles(survey, options, manifest, progress, error)) return false;
    if (!SetTileOptions(options.param, manifest, error) || !PrepareDirectory(dir, error) ||
        !WriteTiles(input, dir, options, manifest, progress, error))
        return false;
    std::uint64_t largest = 0, halos = 0;
    for (const TileEntry &t : manifest.tiles) {
        largest = std::max(largest, t.corePoints + t.haloPoints);
        halos += t.haloPoints;
    }
    char line[160];
    std::snprintf(line, sizeof line, "[split] %zu tiles with points, the fullest %.2f M points with its halo; halos %.2f M",
                  manifest.tiles.size(), largest / 1e6, halos / 1e6);
    progress(line);
    if (halos > manifest.points)
        progress("[split] warning: the halos hold more points than the cores: most of the work resamples halos; "
                 "raise --tile-points");
    return WriteManifest(dir, manifest, error);
}

} // namespace gstile
