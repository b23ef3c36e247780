// gsresample: the Gaussian sphere resampler as a command-line program, without MeshLab.
//
// Writes the surfels as a `.surfel` file (docs/surfel_format.md: ellipse axes, fit offsets and
// blend scales included) when OUTPUT ends in .surfel, otherwise as a PLY point set with normals,
// radius and quality, at their fitted positions; prints one line of figures.
//
// Double-precision input coordinates are resampled near the origin and written back in double,
// so georeferenced scans keep their precision (ply_input.h); float coordinates far from the
// origin, and a .surfel output of such input, are held in coarse steps, with a warning.
//
// Exit status: 0 done (a missed --target is a warning), 1 the input cannot be read, the
// resampling fails or the output cannot be written, 2 a bad command line or parameter. Every
// failure prints one line `gsresample: error: ...` on stderr; the command line and the
// parameters are checked before the input is read, the output path before the resampling runs,
// and the output appears only when complete (io_surfel/file_replacement.h); an output that is
// the input file is refused.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <sys/stat.h>

#include <vcg_ext/gaussphere/oriented_point_mesh.h>
#include <vcg_ext/gaussphere/resampling.h>
#include <vcg_ext/gaussphere/surfels/surfel_mesh.h>
#include <io_surfel/file_replacement.h>
#include <io_surfel/printable_text.h>
#include <io_surfel/surfel_file.h>
#include <io_surfel/surfel_records_mesh.h>

#include <wrap/io_trimesh/export_ply.h>

#include "ply_input.h"
#include "resampling_options.h"
#include "strict_parse.h"

using namespace vcg::gaussphere;

namespace {

// Lengths in messages (surfel_io::printableText): 100 characters of a path, 300 of a message,
// each with the "..." of a cut.
constexpr std::size_t kMaxPathChars = 103;
constexpr std::size_t kMaxMessageChars = 303;

int Fail(int status, const std::string &message)
{
    std::fprintf(stderr, "gsresample: error: %s\n", surfel_io::printableText(message, kMaxMessageChars).c_str());
    return status;
}

std::string PathText(const std::string &path) { return surfel_io::printableText(path, kMaxPathChars); }

/// Usage and the options, from the parameter table (resampling_params.h).
std::string Usage()
{
    return "usage: gsresample INPUT.ply OUTPUT.ply|OUTPUT.surfel [OPTION VALUE]...\n"
           "       gsresample --help\n"
           "INPUT holds x y z nx ny nz per vertex; the output is a .surfel file (ellipse axes included)\n"
           "when OUTPUT ends in .surfel, otherwise a PLY, with double coordinates when INPUT has them\n"
           "(kept at full precision however far from the origin). The size control is the first given of\n"
           "--max-error, --target, --percentage, else the level. Options (default; valid values):\n" +
           gsresample::OptionsUsage();
}

struct CommandLine
{
    std::string input, output;
    ResamplingParams param;
    std::vector<std::string> options; ///< the options given, as typed
    bool help = false;
};

/// Reads the arguments: two paths and options, each option followed by its value, each
/// given at most once. False with a one-line reason on any other shape.
bool ParseCommandLine(int argc, char **argv, CommandLine &line, std::string &error)
{
    std::vector<std::string> paths;
    std::vector<std::string> &seen = line.options;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        if (arg == "--help" || arg == "-h") {
            line.help = true;
            return true;
        }
        if (arg.size() < 2 || arg[0] != '-') {
            paths.push_back(arg);
            continue;
        }
        const ParameterSpec *option = gsresample::FindOption(arg);
        if (!option) {
            error = "unknown option " + gsresample::Quoted(arg) + " (see --help)";
            return false;
        }
        if (a + 1 >= argc) {
            error = arg + " needs a value";
            return false;
        }
        for (const std::string &s : seen) {
            if (s == arg) {
                error = arg + " is given twice";
                return false;
            }
        }
        seen.push_back(arg);
        if (!gsresample::SetOption(*option, argv[++a], line.param, error)) {
            error = arg + ": " + error;
            return false;
        }
    }
    if (paths.size() != 2) {
        error = paths.size() < 2 ? "expected INPUT.ply and OUTPUT.ply|OUTPUT.surfel (see --help)"
                                 : "unexpected argument " + gsresample::Quoted(paths[2]) + ": expected only INPUT and OUTPUT";
        return false;
    }
    line.input = paths[0];
    line.output = paths[1];
    return true;
}

/// True when `path` ends in .surfel, in any case (MeshLab reads the suffix so too).
bool IsSurfelPath(const std::string &path)
{
    const std::string suffix = ".surfel";
    if (path.size() <= suffix.size()) return false;
    for (size_t i = 0; i < suffix.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(path[path.size() - suffix.size() + i])) != suffix[i]) return false;
    return true;
}

/// True when both paths name one existing file (the same device and inode).
bool SameFile(const std::string &a, const std::string &b)
{
    struct stat sa, sb;
    return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

/// Writes `mesh` as a binary PLY point set with normals, radius, quality and (`colours`) colours
/// to the prepared `output`, and puts the file in place; false with a message.
template <class MeshType>
bool WritePly(const std::string &path, surfel_io::FileReplacement &output, MeshType &mesh, bool colours,
              std::string &error)
{
    const int saveMask = vcg::tri::io::Mask::IOM_VERTNORMAL | vcg::tri::io::Mask::IOM_VERTRADIUS |
                         vcg::tri::io::Mask::IOM_VERTQUALITY | (colours ? vcg::tri::io::Mask::IOM_VERTCOLOR : 0);
    if (vcg::tri::io::ExporterPLY<MeshType>::Save(mesh, output.writePath().c_str(), saveMask, true) != 0) {
        error = "cannot write " + PathText(path) + ": the PLY writer failed";
        return false;
    }
    return output.commit(error);
}

/// The surfels of `result` in `mesh`, each with the mean colour of its points when the input has
/// colours.
template <class MeshType>
void SurfelMesh(const ResamplingResult &result, const OrientedPointMesh &input, const gsresample::InputInfo &info,
                MeshType &mesh)
{
    WriteSurfels(result.surfels, mesh);
    if (info.vertexColours) ColourSurfelsByMembers(input, result.representative, mesh);
}

/// The .surfel records of the surfels, moved back to where the input lay. The format holds float
/// coordinates: when that rounds them coarsely (far from the origin), a warning says so.
std::vector<surfel_io::SurfelRecord> SurfelRecords(const ResamplingResult &result, const OrientedPointMesh &input,
                                                   const gsresample::InputInfo &info)
{
    OrientedPointMesh mesh;
    SurfelMesh(result, input, info, mesh);
    std::vector<surfel_io::SurfelRecord> records = surfel_io::recordsFromMesh(mesh);
    if (!info.doubleCoordinates) return records;
    double farthest = 0;
    for (surfel_io::SurfelRecord &record : records) {
        for (int d = 0; d < 3; ++d) {
            const double exact = double(record.position[d]) + info.origin[d];
            farthest = std::max(farthest, std::abs(exact));
            record.position[d] = float(exact);
        }
    }
    const double diagonal = result.stats.diagonal, step = CoarseFloatStep(farthest, diagonal);
    if (step > 0)
        std::fprintf(stderr, "gsresample: warning: the .surfel format holds float coordinates, which up to %.7g from the "
                     "origin are rounded to steps of %.3g (%.2g of the bounding-box diagonal); a PLY output keeps "
                     "the input's double coordinates\n", farthest, step, step / diagonal);
    return records;
}

/// Writes the surfels of `result` to the prepared `output`, where the input lay, coloured as it
/// is (`info`), and puts the file in place; false with a message. A PLY output of
/// double-precision input is double too.
bool WriteOutput(const std::string &path, surfel_io::FileReplacement &output, const ResamplingResult &result,
                 const OrientedPointMesh &input, const gsresample::InputInfo &info, std::string &error)
{
    if (IsSurfelPath(path)) {
        const std::vector<surfel_io::SurfelRecord> records = SurfelRecords(result, input, info);
        return output.write([&](std::ostream &out, std::string &reason) { return surfel_io::writeSurfels(out, records, reason); },
                            error);
    }
    if (!info.doubleCoordinates) {
        OrientedPointMesh mesh;
        SurfelMesh(result, input, info, mesh);
        return WritePly(path, output, mesh, info.vertexColours, error);
    }
    gsresample::DoublePointMesh mesh;
    SurfelMesh(result, input, info, mesh);
    for (gsresample::DoublePointVertex &v : mesh.vert) v.P() += info.origin;
    return WritePly(path, output, mesh, info.vertexColours, error);
}

void PrintFigures(const ResamplingStats &s)
{
    std::printf("input %d skipped %d output %d (%.2f%%) naive %d iterations %d neighbours %.1f L21 %.4f/%.3f level %d "
                "(%d tried) splits %d+%d+%d merges %d exchanges %d/%d (max %.3g -> %.3g) crease-narrowed %d rim %d stray-splits %d halvings %d above-bound %d (max %.3g) coincident %d | time %.3f s (neighbours %.3f propagation %.3f normalization %.3f "
                "refinement %.3f surfels %.3f exchanges %.3f)\n",
                s.inputCount, s.skippedCount, s.outputCount, 100.0 * s.outputCount / s.inputCount, s.naiveCount,
                s.iterations, s.meanAdaptiveNeighbors, s.normalErrorRms, s.normalErrorMax, s.levelUsed, s.levelsTried, s.splitsForErrorBound,
                s.splitsForSurfaceBound, s.splitsForTarget, s.mergesForTarget, s.exchangesForMaxError, s.exchangeTrials,
                s.exchangeMaxBefore, s.exchangeMaxAfter, s.surfelsNarrowedAtCreases, s.rimPoints, s.straySplits, s.narrowingsForSurfaceBound, s.pointsAboveErrorBound, s.surfaceErrorMax, s.coincidentPoints, s.TotalSeconds(), s.secondsNeighbors, s.secondsPropagation,
                s.secondsNormalization, s.secondsRefinement, s.secondsSurfels, s.secondsExchanges);
}

int Run(int argc, char **argv)
{
    CommandLine line;
    std::string error;
    if (!ParseCommandLine(argc, argv, line, error)) return Fail(2, error);
    if (line.help) {
        std::fputs(Usage().c_str(), stdout);
        return 0;
    }
    const std::string invalid = line.param.Validate();
    if (!invalid.empty()) return Fail(2, invalid);
    for (const std::string &warning : gsresample::OverriddenOptions(line.options, line.param))
        std::fprintf(stderr, "gsresample: warning: %s\n", warning.c_str());

    if (SameFile(line.input, line.output))
        return Fail(2, "the output " + PathText(line.output) + " is the input file: give another output path");
    OrientedPointMesh in;
    gsresample::InputInfo info;
    if (!gsresample::ReadOrientedPoints(line.input, in, error, &info))
        return Fail(1, "cannot read " + PathText(line.input) + ": " + error);
    surfel_io::FileReplacement output; // prepared before the resampling: an unwritable path fails at once
    if (!output.open(line.output, error)) return Fail(1, error);
    const ResamplingResult r = ResamplePointSet(in, line.param);
    PrintFigures(r.stats);
    const std::string miss = r.stats.TargetMissReason();
    if (!miss.empty())
        std::fprintf(stderr, "gsresample: warning: %d surfels instead of the %d requested: %s\n", r.stats.outputCount,
                     r.stats.targetCount, miss.c_str());
    const std::string beyond = r.stats.ErrorBoundMissReason();
    if (!beyond.empty())
        std::fprintf(stderr, "gsresample: warning: %d point(s) remain beyond the error bound (largest distance %g x "
                     "diagonal): %s\n", r.stats.pointsAboveErrorBound, r.stats.surfaceErrorMax, beyond.c_str());
    const std::string coarse = r.stats.CoarsePositionsReason();
    if (!coarse.empty()) std::fprintf(stderr, "gsresample: warning: %s\n", coarse.c_str());
    if (!WriteOutput(line.output, output, r, in, info, error)) return Fail(1, error);
    return 0;
}

} // namespace

int main(int argc, char **argv)
{
    try {
        return Run(argc, argv);
    } catch (const std::bad_alloc &) {
        return Fail(1, "out of memory");
    } catch (const std::exception &e) {
        return Fail(1, e.what());
    } catch (...) {
        return Fail(1, "unexpected failure");
    }
}
