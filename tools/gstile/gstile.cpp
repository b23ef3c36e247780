// gstile: the Gaussian sphere resampler on scans of any size, tile by tile (docs/tiling.md).
//
//   gstile split INPUT.ply TILEDIR [--tile-points N] [--halo-spacings X] [gsresample options]
//   gstile run TILEDIR TILE_ID
//   gstile probe TILEDIR TILE_ID, gstile share TILEDIR   (with a target, before run: target_share.h)
//   gstile adjust TILEDIR                                (with a target, after run: target_share.h)
//   gstile merge TILEDIR OUTPUT.surfel|OUTPUT.ply
//   gstile all INPUT.ply OUTPUT.surfel|OUTPUT.ply [--tile-dir DIR] [split options]
//   gstile tiles TILEDIR [--pending | --to-probe]
//
// Exit status: 0 done, 1 a failure (one line `gstile: error: ...`, naming the tile when a tile
// failed), 2 a bad command line.
#include <cstdio>
#include <string>
#include <vector>

#include <tools/gsresample/resampling_options.h>
#include <tools/gsresample/strict_parse.h>

#include "manifest.h"
#include "merge.h"
#include "split.h"
#include "tile_run.h"

namespace gstile {
namespace {

const char *const kUsage =
    "usage: gstile split INPUT.ply TILEDIR [--tile-points N] [--halo-spacings X] [OPTION VALUE]...\n"
    "       gstile run TILEDIR TILE_ID\n"
    "       gstile probe TILEDIR TILE_ID, then gstile share TILEDIR   (with a target, before run)\n"
    "       gstile adjust TILEDIR   (with a target, after run: then run the tiles of tiles --pending)\n"
    "       gstile merge TILEDIR OUTPUT.surfel|OUTPUT.ply\n"
    "       gstile all INPUT.ply OUTPUT.surfel|OUTPUT.ply [--tile-dir DIR] [split options]\n"
    "       gstile tiles TILEDIR [--pending | --to-probe]   (the ids of the tiles, of those left to run, or\n"
    "                                                       of those to probe before the share, one a line)\n"
    "split streams a binary little-endian PLY (x y z nx ny nz) into tiles of about N points with\n"
    "their halo (default 4000000; a run takes up to about 200 B a point), X sample spacings wide\n"
    "(default 24); run resamples one tile and keeps the surfels it owns; merge concatenates them;\n"
    "all does the three in turn, the tiles in DIR (default OUTPUT.tiles). With --target or\n"
    "--percentage, probe runs the tiles --to-probe lists (again, until it lists none: the level\n"
    "search, then the priorities of the splits there), share divides the count as the whole run\n"
    "would spend it, and adjust gives the tiles that missed their share a new count, up to 3 times\n"
    "a tile, and shares the whole run's rounds of exchanges, then its crease fit limits, then takes the\n"
    "seam step: every tile runs again beside the surfels its neighbours keep.\n"
    "gsresample's options:\n";

struct UsageError
{
    std::string message;
};

void PrintLine(const std::string &line)
{
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
}

/// Reads `--option value` pairs from argv[first...] into `options`; `paths` receives the rest.
void ParseSplitArguments(int argc, char **argv, int first, SplitOptions &options, std::string *tileDir,
                         std::vector<std::string> &paths)
{
    std::vector<std::string> seen;
    for (int a = first; a < argc; ++a) {
        const std::string arg = argv[a];
        if (arg.size() < 2 || arg[0] != '-') {
            paths.push_back(arg);
            continue;
        }
        if (a + 1 >= argc) throw UsageError{arg + " needs a value"};
        for (const std::string &s : seen)
            if (s == arg) throw UsageError{arg + " is given twice"};
        seen.push_back(arg);
        const std::string value = argv[++a];
        std::string error;
        bool ok = true;
        if (arg == "--tile-points") {
            int points = 0;
            ok = gsresample::ParseInt(value, 1000, 2000000000, points, error);
            options.tilePoints = std::uint64_t(points);
        } else if (arg == "--halo-spacings") {
            ok = gsresample::ParseDouble(value, 0, 1000, options.haloSpacings, error);
        } else if (arg == "--tile-dir" && tileDir != nullptr) {
            *tileDir = value;
        } else if (const vcg::gaussphere::ParameterSpec *spec = gsresample::FindOption(arg)) {
            ok = gsresample::SetOption(*spec, value, options.param, error);
        } else {
            throw UsageError{"unknown option " + gsresample::Quoted(arg) + " (see --help)"};
        }
        if (!ok) throw UsageError{arg + ": " + error};
    }
    const std::string invalid = options.param.Validate();
    if (!invalid.empty()) throw UsageError{invalid};
}

int TileId(const std::string &text)
{
    int id = 0;
    std::string error;
    if (!gsresample::ParseInt(text, 0, 2000000000, id, error)) throw UsageError{"TILE_ID: " + error};
    return id;
}

void Expect(bool condition, const char *shape)
{
    if (!condition) throw UsageError{std::string("expected ") + shape + " (see --help)"};
}

int Fail(const std::string &error)
{
    std::fprintf(stderr, "gstile: error: %s\n", error.c_str());
    return 1;
}

int WriteAndReportShares(const std::string &dir, const Manifest &manifest)
{
    ShareDecision decision;
    bool written = false;
    std::string error;
    if (!WriteShares(dir, manifest, decision, written, error)) return Fail(error);
    if (!decision.shared)
        return Fail("the probes are not complete: probe the tiles `gstile tiles " + dir + " --to-probe` lists first");
    char line[200];
    std::uint64_t runCount = 0;
    for (const TileShare &share : decision.shares.tiles) runCount += share.target;
    std::snprintf(line, sizeof line, "[share] %llu surfels over %zu tiles at level %d (%llu made with halos)%s",
                  (unsigned long long)manifest.targetCount, decision.shares.tiles.size(), decision.shares.level,
                  (unsigned long long)runCount, written ? "" : ", shared already");
    PrintLine(line);
    return 0;
}

/// Probes the tiles until the share is decided, then writes it.
int ProbeAndShare(const std::string &dir, const Manifest &manifest)
{
    std::vector<int> ids;
    std::string error;
    while (TilesToProbe(dir, manifest, ids, error) && !ids.empty()) {
        for (std::size_t t = 0; t < ids.size(); ++t) {
            ProbeFigures figures;
            if (!ProbeTile(dir, manifest, ids[t], figures, error)) return Fail(error);
            PrintLine(ProbeLine(figures, t + 1, ids.size()));
        }
    }
    if (!error.empty()) return Fail(error);
    return WriteAndReportShares(dir, manifest);
}

/// Runs the tiles `ids` and prints each one's figures line.
int RunTiles(const std::string &dir, const Manifest &manifest, const std::vector<int> &ids)
{
    for (std::size_t t = 0; t < ids.size(); ++t) {
        TileRunFigures figures;
        std::string error;
        if (!RunTile(dir, manifest, ids[t], figures, error)) return Fail(error);
        PrintLine(FiguresLine(figures, t + 1, ids.size()));
    }
    return 0;
}

/// One round of adjustment (target_share.h); `rerun` receives the tiles to run again.
int AdjustAndReport(const std::string &dir, const Manifest &manifest, std::vector<int> &rerun)
{
    AdjustFigures figures;
    std::string error;
    if (!AdjustShares(dir, manifest, figures, error)) return Fail(error);
    char line[200];
    std::snprintf(line, sizeof line, "[adjust] the merge keeps %llu of %llu surfels; %zu tile(s) to run again",
                  (unsigned long long)figures.kept, (unsigned long long)manifest.targetCount, figures.rerun.size());
    PrintLine(line);
    const vcg::gaussphere::CreaseFitLimits &limits = figures.sharedLimits;
    if (limits.given) {
        std::snprintf(line, sizeof line,
                      "[adjust] the scan's crease fit limits, its 99.9th percentiles: distance %.6g, blended "
                      "normal error %.6g",
                      limits.distance, limits.normalError);
        PrintLine(line);
    }
    if (figures.seamTaken)
        PrintLine("[adjust] the seam step: every tile runs again with the surfels its neighbours keep around it");
    rerun = figures.rerun;
    return 0;
}

int RunAll(const std::string &dir, const Manifest &manifest)
{
    if (manifest.targetCount > 0)
        if (const int status = ProbeAndShare(dir, manifest)) return status;
    std::vector<int> ids;
    for (const TileEntry &tile : manifest.tiles) ids.push_back(tile.id);
    while (!ids.empty()) {
        if (const int status = RunTiles(dir, manifest, ids)) return status;
        if (manifest.targetCount == 0) break;
        if (const int status = AdjustAndReport(dir, manifest, ids)) return status;
    }
    return 0;
}

int MergeTiles(const std::string &dir, const Manifest &manifest, const std::string &output)
{
    MergeFigures figures;
    std::string error;
    if (!Merge(dir, manifest, output, figures, error)) return Fail(error);
    char line[400];
    std::snprintf(line, sizeof line,
                  "[merge] %llu surfels (%.2f%% of %llu points; %llu kept for %llu border points no tile kept nor covered) "
                  "representing %llu points into %s",
                  (unsigned long long)figures.surfels, 100.0 * figures.surfels / double(manifest.points),
                  (unsigned long long)manifest.points, (unsigned long long)figures.rescued,
                  (unsigned long long)figures.uncovered, (unsigned long long)figures.members, output.c_str());
    PrintLine(line);
    if (figures.coarseStep > 0) {
        std::snprintf(line, sizeof line,
                      "[merge] warning: the .surfel format holds float coordinates, which this far from the origin are "
                      "rounded to steps of %.3g; a PLY output keeps the input's double coordinates", figures.coarseStep);
        PrintLine(line);
    }
    return 0;
}

int LoadManifest(const std::string &dir, Manifest &manifest)
{
    std::string error;
    return ReadManifest(dir, manifest, error) ? 0 : Fail(error);
}

int Dispatch(const std::string &command, int argc, char **argv)
{
    std::vector<std::string> paths;
    Manifest manifest;
    std::string error;
    if (command == "split" || command == "all") {
        SplitOptions options;
        std::string tileDir;
        ParseSplitArguments(argc, argv, 2, options, command == "all" ? &tileDir : nullptr, paths);
        Expect(paths.size() == 2, command == "all" ? "INPUT.ply OUTPUT" : "INPUT.ply TILEDIR");
        if (command == "split") return Split(paths[0], paths[1], options, manifest, PrintLine, error) ? 0 : Fail(error);
        if (tileDir.empty()) tileDir = paths[1] + ".tiles";
        if (!Split(paths[0], tileDir, options, manifest, PrintLine, error)) return Fail(error);
        const int status = RunAll(tileDir, manifest);
        return status != 0 ? status : MergeTiles(tileDir, manifest, paths[1]);
    }
    for (int a = 2; a < argc; ++a) paths.push_back(argv[a]);
    Expect(!paths.empty(), "TILEDIR");
    if (const int status = LoadManifest(paths[0], manifest)) return status;
    if (command == "run") {
        Expect(paths.size() == 2, "TILEDIR TILE_ID");
        TileRunFigures figures;
        const int id = TileId(paths[1]);
        if (!RunTile(paths[0], manifest, id, figures, error)) return Fail(error);
        PrintLine(FiguresLine(figures, std::size_t(manifest.Find(id) - manifest.tiles.data()) + 1, manifest.tiles.size()));
        return 0;
    }
    if ((command == "probe" || command == "share" || command == "adjust") && manifest.targetCount == 0)
        return Fail(paths[0] + " was split without a target (--target or --percentage): nothing to share");
    if (command == "probe") {
        Expect(paths.size() == 2, "TILEDIR TILE_ID");
        ProbeFigures figures;
        const int id = TileId(paths[1]);
        if (!ProbeTile(paths[0], manifest, id, figures, error)) return Fail(error);
        PrintLine(ProbeLine(figures, std::size_t(manifest.Find(id) - manifest.tiles.data()) + 1, manifest.tiles.size()));
        return 0;
    }
    if (command == "share") {
        Expect(paths.size() == 1, "TILEDIR");
        return WriteAndReportShares(paths[0], manifest);
    }
    if (command == "adjust") {
        Expect(paths.size() == 1, "TILEDIR");
        std::vector<int> rerun;
        return AdjustAndReport(paths[0], manifest, rerun);
    }
    if (command == "merge") {
        Expect(paths.size() == 2, "TILEDIR OUTPUT");
        return MergeTiles(paths[0], manifest, paths[1]);
    }
    Expect(command == "tiles" && (paths.size() == 1 || (paths.size() == 2 && (paths[1] == "--pending" || paths[1] == "--to-probe"))),
           "a command: split, run, probe, share, adjust, merge, all or tiles");
    std::vector<int> ids;
    for (const TileEntry &tile : manifest.tiles) ids.push_back(tile.id);
    if (paths.size() == 2 && paths[1] == "--pending" && !PendingTiles(paths[0], manifest, ids, error)) return Fail(error);
    if (paths.size() == 2 && paths[1] == "--to-probe") {
        if (manifest.targetCount == 0) return Fail(paths[0] + " was split without a target: no tile to probe");
        if (!TilesToProbe(paths[0], manifest, ids, error)) return Fail(error);
    }
    for (const int id : ids) std::printf("%d\n", id);
    return 0;
}

} // namespace
} // namespace gstile

int main(int argc, char **argv)
{
    const std::string command = argc > 1 ? argv[1] : "";
    if (command == "--help" || command == "-h") {
        std::fputs(gstile::kUsage, stdout);
        std::fputs(gsresample::OptionsUsage().c_str(), stdout);
        return 0;
    }
    try {
        return gstile::Dispatch(command, argc, argv);
    } catch (const gstile::UsageError &e) {
        std::fprintf(stderr, "gstile: error: %s\n", e.message.c_str());
        return 2;
    } catch (const std::bad_alloc &) {
        return gstile::Fail("out of memory");
    } catch (const std::exception &e) {
        return gstile::Fail(e.what());
    }
}
