// gsresample: the Gaussian sphere resampler as a command-line program, without MeshLab.
//
// Writes the surfels as a `.surfel` file (docs/surfel_format.md: ellipse axes, fit offsets and
// blend scales included) when OUTPUT ends in .surfel, otherwise as a PLY point set with normals,
// radius and quality, at their fitted positions; prints one line of figures.
//
// Exit status: 0 done (a missed --target is a warning), 1 the input cannot be read, the
// resampling fails or the output cannot be written, 2 a bad command line or parameter. Every
// failure prints one line `gsresample: error: ...` on stderr; the command line and the
// parameters are checked before the input is read, and the output appears only when complete.
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <vcg_ext/gaussphere/oriented_point_mesh.h>
#include <vcg_ext/gaussphere/resampling.h>
#include <vcg_ext/gaussphere/surfel_mesh.h>
#include <io_surfel/surfel_records_mesh.h>

#include <wrap/io_trimesh/export_ply.h>

#include "ply_input.h"
#include "strict_parse.h"

using namespace vcg::gaussphere;

namespace {

const char kUsage[] =
    "usage: gsresample INPUT.ply OUTPUT.ply|OUTPUT.surfel [--level N] [--k K] [--depth D] [--threshold T]\n"
    "                  [--min-split S] [--max-cluster M] [--crease-angle DEG] [--crease-cluster M]\n"
    "                  [--crease-min-split S] [--crease-blend F] [--iterations I] [--weight-width H]\n"
    "                  [--convergence F] [--base octahedron|icosahedron] [--reference seed|current]\n"
    "                  [--order dfs|bfs] [--target COUNT] [--exchanges N]\n"
    "                  [--max-error FRACTION_OF_BBOX_DIAGONAL] [--fit-offsets 0|1]\n"
    "       gsresample --help\n"
    "INPUT holds x y z nx ny nz per vertex. The parameters are those of the MeshLab filter\n"
    "(README.md); the output is a .surfel file when OUTPUT ends in .surfel, otherwise a PLY.\n";

constexpr std::size_t kMaxPathChars = 100;
constexpr std::size_t kMaxMessageChars = 300;
const double kInfinity = std::numeric_limits<double>::infinity();
const int kIntMax = std::numeric_limits<int>::max();

int Fail(int status, const std::string &message)
{
    std::fprintf(stderr, "gsresample: error: %s\n", gsresample::Printable(message, kMaxMessageChars).c_str());
    return status;
}

std::string PathText(const std::string &path) { return gsresample::Printable(path, kMaxPathChars); }

/// One option taking a value: `set` parses it into the parameters or explains why it cannot.
struct Option
{
    std::string name;
    std::function<bool(const std::string &value, ResamplingParams &param, std::string &error)> set;
};

Option IntOption(const char *name, int min, int max, int ResamplingParams::*field)
{
    return {name, [=](const std::string &value, ResamplingParams &param, std::string &error) {
                return gsresample::ParseInt(value, min, max, param.*field, error);
            }};
}

Option DoubleOption(const char *name, double min, double max, double ResamplingParams::*field)
{
    return {name, [=](const std::string &value, ResamplingParams &param, std::string &error) {
                return gsresample::ParseDouble(value, min, max, param.*field, error);
            }};
}

template <class Field>
Option ChoiceOption(const char *name, std::vector<std::string> choices, std::vector<Field> values,
                    Field ResamplingParams::*field)
{
    return {name, [=](const std::string &value, ResamplingParams &param, std::string &error) {
                int index = 0;
                if (!gsresample::ParseChoice(value, choices, index, error)) return false;
                param.*field = values[std::size_t(index)];
                return true;
            }};
}

// The ranges are the ones ResamplingParams::Validate accepts where those are plain intervals;
// Validate, run next, rejects the rest (open bounds, excluded values).
std::vector<Option> Options()
{
    typedef ResamplingParams P;
    return {
        IntOption("--level", 2, 256, &P::subdivisionLevel),
        IntOption("--k", 1, 255, &P::neighborCount),
        IntOption("--depth", 0, kIntMax, &P::propagationDepth),
        DoubleOption("--threshold", 1, kInfinity, &P::normalizationThreshold),
        IntOption("--min-split", 0, kIntMax, &P::minSplitSize),
        IntOption("--max-cluster", 0, kIntMax, &P::maxClusterSize),
        DoubleOption("--crease-angle", 0, 120, &P::creaseAngle),
        IntOption("--crease-cluster", 0, kIntMax, &P::creaseClusterSize),
        IntOption("--crease-min-split", 0, kIntMax, &P::creaseMinSplitSize),
        {"--crease-blend",
         [](const std::string &value, ResamplingParams &param, std::string &error) {
             double scale = 0;
             if (!gsresample::ParseDouble(value, 0, 1, scale, error)) return false;
             param.creaseBlendScale = float(scale);
             return true;
         }},
        IntOption("--iterations", 0, kIntMax, &P::maxIterations),
        DoubleOption("--weight-width", -kInfinity, kInfinity, &P::weightWidth),
        DoubleOption("--convergence", 0, kInfinity, &P::convergenceFraction),
        IntOption("--target", 0, kIntMax, &P::targetCount),
        IntOption("--exchanges", 0, 100000, &P::maxErrorExchanges),
        DoubleOption("--max-error", 0, 1, &P::maxErrorFraction),
        ChoiceOption<bool>("--fit-offsets", {"0", "1"}, {false, true}, &P::fitOffsets),
        ChoiceOption<BasePolyhedron>("--base", {"octahedron", "icosahedron"},
                                     {BasePolyhedron::Octahedron, BasePolyhedron::Icosahedron}, &P::base),
        ChoiceOption<PropagationReference>("--reference", {"seed", "current"},
                                           {PropagationReference::Seed, PropagationReference::CurrentPoint}, &P::reference),
        ChoiceOption<PropagationOrder>("--order", {"dfs", "bfs"},
                                       {PropagationOrder::DepthFirst, PropagationOrder::BreadthFirst}, &P::order),
    };
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
    const std::vector<Option> options = Options();
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
        const Option *option = nullptr;
        for (const Option &o : options)
            if (o.name == arg) option = &o;
        if (!option) {
            error = "unknown option '" + gsresample::Printable(arg) + "' (see --help)";
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
        if (!option->set(argv[++a], line.param, error)) {
            error = arg + ": " + error;
            return false;
        }
    }
    if (paths.size() != 2) {
        error = paths.size() < 2 ? "expected INPUT.ply and OUTPUT.ply|OUTPUT.surfel (see --help)"
                                 : "unexpected argument '" + gsresample::Printable(paths[2]) + "': expected only INPUT and OUTPUT";
        return false;
    }
    line.input = paths[0];
    line.output = paths[1];
    return true;
}

bool EndsWith(const std::string &text, const std::string &suffix)
{
    return text.size() > suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// Writes `surfels` to `path` through `path`.part, renamed when complete.
bool WriteOutput(const std::string &path, OrientedPointMesh &surfels, std::string &error)
{
    if (EndsWith(path, ".surfel")) return surfel_io::writeSurfelFile(path, surfel_io::recordsFromMesh(surfels), error);
    const std::string partPath = path + ".part";
    const int saveMask = vcg::tri::io::Mask::IOM_VERTNORMAL | vcg::tri::io::Mask::IOM_VERTRADIUS |
                         vcg::tri::io::Mask::IOM_VERTQUALITY;
    if (vcg::tri::io::ExporterPLY<OrientedPointMesh>::Save(surfels, partPath.c_str(), saveMask, true) == 0 &&
        std::rename(partPath.c_str(), path.c_str()) == 0)
        return true;
    std::remove(partPath.c_str());
    error = "the PLY writer failed";
    return false;
}

/// Why the output count differs from a requested target, or empty when it does not.
std::string TargetMissReason(const ResamplingParams &param, const ResamplingStats &s)
{
    if (param.targetCount <= 0 || s.outputCount == param.targetCount) return std::string();
    const int usable = s.inputCount - s.skippedCount;
    if (s.outputCount < param.targetCount)
        return usable < param.targetCount
                   ? "the input has only " + std::to_string(usable) + " usable point(s)"
                   : "no cluster left to split";
    return param.maxErrorFraction > 0 ? "the error bound needs more" : "no neighbouring clusters left to merge";
}

void PrintFigures(const ResamplingStats &s)
{
    std::printf("input %d skipped %d output %d (%.2f%%) naive %d iterations %d neighbours %.1f L21 %.4f/%.3f level %d "
                "(%d tried) splits %d+%d+%d merges %d exchanges %d/%d (max %.3g -> %.3g) crease-narrowed %d halvings %d above-bound %d (max %.5f) | time %.3f s (neighbours %.3f propagation %.3f normalization %.3f "
                "refinement %.3f surfels %.3f exchanges %.3f)\n",
                s.inputCount, s.skippedCount, s.outputCount, 100.0 * s.outputCount / s.inputCount, s.naiveCount,
                s.iterations, s.meanAdaptiveNeighbors, s.normalErrorRms, s.normalErrorMax, s.levelUsed, s.levelsTried, s.splitsForErrorBound,
                s.splitsForSurfaceBound, s.splitsForTarget, s.mergesForTarget, s.exchangesForMaxError, s.exchangeTrials,
                s.exchangeMaxBefore, s.exchangeMaxAfter, s.surfelsNarrowedAtCreases, s.narrowingsForSurfaceBound, s.pointsAboveErrorBound, s.surfaceErrorMax, s.TotalSeconds(), s.secondsNeighbors, s.secondsPropagation,
                s.secondsNormalization, s.secondsRefinement, s.secondsSurfels, s.secondsExchanges);
}

int Run(int argc, char **argv)
{
    CommandLine line;
    std::string error;
    if (!ParseCommandLine(argc, argv, line, error)) return Fail(2, error);
    if (line.help) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    const std::string invalid = line.param.Validate();
    if (!invalid.empty()) return Fail(2, invalid);

    OrientedPointMesh in, out;
    if (!gsresample::ReadOrientedPoints(line.input, in, error))
        return Fail(1, "cannot read " + PathText(line.input) + ": " + error);
    const ResamplingResult r = ResamplePointSet(in, line.param);
    WriteSurfels(r.surfels, out);
    PrintFigures(r.stats);
    const std::string miss = TargetMissReason(line.param, r.stats);
    if (!miss.empty())
        std::fprintf(stderr, "gsresample: warning: %d surfels instead of the %d requested: %s\n", r.stats.outputCount,
                     line.param.targetCount, miss.c_str());
    if (!WriteOutput(line.output, out, error))
        return Fail(1, "cannot write " + PathText(line.output) + ": " + error);
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
