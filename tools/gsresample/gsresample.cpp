// gsresample: the Gaussian sphere resampler as a command-line program, without MeshLab.
//
// Writes the surfels as a `.surfel` file (docs/surfel_format.md: ellipse axes, fit offsets and
// blend scales included) when OUTPUT ends in .surfel, otherwise as a PLY point set with normals,
// radius and quality, at their fitted positions; prints one line of figures.
//
// Exit status: 0 done (a missed --target is a warning), 1 the input cannot be read, the
// resampling fails or the output cannot be written, 2 a bad command line or parameter. Every
// failure prints one line `gsresample: error: ...` on stderr; the command line and the
// parameters are checked before the input is read, the output path before the resampling runs,
// and the output appears only when complete (io_surfel/file_replacement.h); an output that is
// the input file is refused.
#include <cctype>
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
           "when OUTPUT ends in .surfel, otherwise a PLY. The size control is the first given of\n"
           "--max-error, --target, --percentage, else the level. Options (default; valid values):\n" +
           gsresample::OptionsUsage();
}

struct CommandLine
{
    std::string input, output;
    ResamplingParams param;
    bool help = false;
};

/// Reads the arguments: two paths and options, each option followed by its value, each
/// given at most once. False with a one-line reason on any other shape.
bool ParseCommandLine(int argc, char **argv, CommandLine &line, std::string &error)
{
    std::vector<std::string> paths, seen;
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

/// Writes `surfels` to the prepared `output` and puts the file in place; false with a message.
bool WriteOutput(const std::string &path, surfel_io::FileReplacement &output, OrientedPointMesh &surfels,
                 std::string &error)
{
    if (IsSurfelPath(path)) {
        const std::vector<surfel_io::SurfelRecord> records = surfel_io::recordsFromMesh(surfels);
        return output.write([&](std::ostream &out, std::string &reason) { return surfel_io::writeSurfels(out, records, reason); },
                            error);
    }
    const int saveMask = vcg::tri::io::Mask::IOM_VERTNORMAL | vcg::tri::io::Mask::IOM_VERTRADIUS |
                         vcg::tri::io::Mask::IOM_VERTQUALITY;
    if (vcg::tri::io::ExporterPLY<OrientedPointMesh>::Save(surfels, output.writePath().c_str(), saveMask, true) != 0) {
        error = "cannot write " + PathText(path) + ": the PLY writer failed";
        return false;
    }
    return output.commit(error);
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

    if (SameFile(line.input, line.output))
        return Fail(2, "the output " + PathText(line.output) + " is the input file: give another output path");
    OrientedPointMesh in, out;
    if (!gsresample::ReadOrientedPoints(line.input, in, error))
        return Fail(1, "cannot read " + PathText(line.input) + ": " + error);
    surfel_io::FileReplacement output; // prepared before the resampling: an unwritable path fails at once
    if (!output.open(line.output, error)) return Fail(1, error);
    const ResamplingResult r = ResamplePointSet(in, line.param);
    WriteSurfels(r.surfels, out);
    PrintFigures(r.stats);
    const std::string miss = r.stats.TargetMissReason();
    if (!miss.empty())
        std::fprintf(stderr, "gsresample: warning: %d surfels instead of the %d requested: %s\n", r.stats.outputCount,
                     r.stats.targetCount, miss.c_str());
    const std::string beyond = r.stats.ErrorBoundMissReason();
    if (!beyond.empty())
        std::fprintf(stderr, "gsresample: warning: %d point(s) remain beyond the error bound (largest distance %g x "
                     "diagonal): %s\n", r.stats.pointsAboveErrorBound, r.stats.surfaceErrorMax, beyond.c_str());
    if (!WriteOutput(line.output, output, out, error)) return Fail(1, error);
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
