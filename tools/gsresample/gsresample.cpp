// gsresample: the Gaussian sphere resampler as a command-line program, without MeshLab.
//
//   gsresample INPUT.ply OUTPUT.ply|OUTPUT.surfel [--level N] [--k K] [--depth D] [--threshold T]
//              [--min-split S] [--max-cluster M] [--crease-angle DEG] [--crease-cluster M]
//              [--crease-min-split S] [--crease-blend F] [--iterations I] [--base octahedron|icosahedron]
//              [--reference seed|current] [--order dfs|bfs]
//              [--target COUNT] [--exchanges N] [--max-error FRACTION_OF_BBOX_DIAGONAL] [--fit-offsets 0|1]
//
// Writes the surfels as a `.surfel` file (docs/surfel_format.md: ellipse axes, fit offsets and
// blend scales included) when OUTPUT ends in .surfel, otherwise as a PLY point set with normals,
// radius and quality, at their fitted positions; prints one line of figures.
#include <cstdio>
#include <cstring>
#include <string>

#include <vcg_ext/gaussphere/oriented_point_mesh.h>
#include <vcg_ext/gaussphere/resampling.h>
#include <vcg_ext/gaussphere/surfel_mesh.h>
#include <io_surfel/surfel_records_mesh.h>

#include <wrap/io_trimesh/export_ply.h>
#include <wrap/io_trimesh/import_ply.h>

using namespace vcg::gaussphere;

int main(int argc, char **argv)
{
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s INPUT.ply OUTPUT.ply|OUTPUT.surfel [--level N] [--k K] [--depth D] [--threshold T]"
                             " [--min-split S] [--max-cluster M] [--crease-angle DEG] [--crease-cluster M] [--crease-min-split S] [--crease-blend F]"
                             " [--iterations I] [--base octahedron|icosahedron]"
                             " [--reference seed|current] [--order dfs|bfs] [--target COUNT] [--exchanges N] [--max-error FRACTION] [--fit-offsets 0|1]\n", argv[0]);
        return 2;
    }
    ResamplingParams param;
    for (int a = 3; a + 1 < argc; a += 2) {
        const std::string key = argv[a], value = argv[a + 1];
        if (key == "--level") param.subdivisionLevel = std::stoi(value);
        else if (key == "--k") param.neighborCount = std::stoi(value);
        else if (key == "--depth") param.propagationDepth = std::stoi(value);
        else if (key == "--threshold") param.normalizationThreshold = std::stod(value);
        else if (key == "--min-split") param.minSplitSize = std::stoi(value);
        else if (key == "--max-cluster") param.maxClusterSize = std::stoi(value);
        else if (key == "--crease-angle") param.creaseAngle = std::stod(value);
        else if (key == "--crease-cluster") param.creaseClusterSize = std::stoi(value);
        else if (key == "--crease-min-split") param.creaseMinSplitSize = std::stoi(value);
        else if (key == "--crease-blend") param.creaseBlendScale = std::stof(value);
        else if (key == "--iterations") param.maxIterations = std::stoi(value);
        else if (key == "--weight-width") param.weightWidth = std::stod(value);
        else if (key == "--convergence") param.convergenceFraction = std::stod(value);
        else if (key == "--target") param.targetCount = std::stoi(value);
        else if (key == "--exchanges") param.maxErrorExchanges = std::stoi(value);
        else if (key == "--max-error") param.maxErrorFraction = std::stod(value);
        else if (key == "--fit-offsets") param.fitOffsets = value != "0" && value != "false" && value != "off";
        else if (key == "--base") param.base = value == "icosahedron" ? BasePolyhedron::Icosahedron : BasePolyhedron::Octahedron;
        else if (key == "--reference") param.reference = value == "current" ? PropagationReference::CurrentPoint : PropagationReference::Seed;
        else if (key == "--order") param.order = value == "bfs" ? PropagationOrder::BreadthFirst : PropagationOrder::DepthFirst;
        else { std::fprintf(stderr, "unknown option %s\n", key.c_str()); return 2; }
    }
    OrientedPointMesh in, out;
    int mask = 0;
    if (vcg::tri::io::ImporterPLY<OrientedPointMesh>::Open(in, argv[1], mask) != 0) {
        std::fprintf(stderr, "cannot read %s\n", argv[1]);
        return 1;
    }
    // vcg leaves the normals of a file without them uninitialised: refuse rather than read garbage.
    if (!(mask & vcg::tri::io::Mask::IOM_VERTNORMAL)) {
        std::fprintf(stderr, "%s has no per-vertex normals (nx ny nz); compute them first, e.g. with MeshLab's "
                             "Compute normals for point sets\n", argv[1]);
        return 1;
    }
    try {
        const ResamplingResult r = ResamplePointSet(in, param);
        WriteSurfels(r.surfels, out);
        const ResamplingStats &s = r.stats;
        std::printf("input %d skipped %d output %d (%.2f%%) naive %d iterations %d neighbours %.1f L21 %.4f/%.3f level %d "
                    "(%d tried) splits %d+%d+%d merges %d exchanges %d/%d (max %.3g -> %.3g) crease-narrowed %d halvings %d above-bound %d (max %.5f) | time %.3f s (neighbours %.3f propagation %.3f normalization %.3f "
                    "refinement %.3f surfels %.3f exchanges %.3f)\n",
                    s.inputCount, s.skippedCount, s.outputCount, 100.0 * s.outputCount / s.inputCount, s.naiveCount,
                    s.iterations, s.meanAdaptiveNeighbors, s.normalErrorRms, s.normalErrorMax, s.levelUsed, s.levelsTried, s.splitsForErrorBound,
                    s.splitsForSurfaceBound, s.splitsForTarget, s.mergesForTarget, s.exchangesForMaxError, s.exchangeTrials,
                    s.exchangeMaxBefore, s.exchangeMaxAfter, s.surfelsNarrowedAtCreases, s.narrowingsForSurfaceBound, s.pointsAboveErrorBound, s.surfaceErrorMax, s.TotalSeconds(), s.secondsNeighbors, s.secondsPropagation,
                    s.secondsNormalization, s.secondsRefinement, s.secondsSurfels, s.secondsExchanges);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    const std::string output = argv[2];
    const std::string surfelExtension = ".surfel";
    if (output.size() > surfelExtension.size() &&
        output.compare(output.size() - surfelExtension.size(), surfelExtension.size(), surfelExtension) == 0) {
        std::string error;
        if (surfel_io::writeSurfelFile(output, surfel_io::recordsFromMesh(out), error)) return 0;
        std::fprintf(stderr, "cannot write %s: %s\n", argv[2], error.c_str());
        return 1;
    }
    const int saveMask = vcg::tri::io::Mask::IOM_VERTNORMAL | vcg::tri::io::Mask::IOM_VERTRADIUS |
                         vcg::tri::io::Mask::IOM_VERTQUALITY;
    if (vcg::tri::io::ExporterPLY<OrientedPointMesh>::Save(out, argv[2], saveMask, true) == 0) return 0;
    std::fprintf(stderr, "cannot write %s\n", argv[2]);
    return 1;
}
