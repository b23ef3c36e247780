// gsmeshdist: how far a reconstructed mesh lies from the original one (src/mesh_distance.h).
//
//   gsmeshdist RECONSTRUCTION.ply ORIGINAL.ply [--samples N] [--seed S]
//     Samples each mesh uniformly by area (N points each, default 1,000,000; seed S, default 1),
//     measures the exact distance of every sample to the nearest triangle of the other mesh and
//     prints one CSV line: the columns of --csv-header, every distance over the original mesh's
//     bounding-box diagonal.
//   gsmeshdist --csv-header
//     Prints the column names.
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "mesh_distance.h"

using namespace gsbench;

namespace {

const char *kCsvHeader =
    "reconstruction_faces,original_faces,samples,diagonal,"
    "to_original_rms,to_original_p99,to_original_max,"
    "to_reconstruction_rms,to_reconstruction_p99,to_reconstruction_max,"
    "symmetric_rms,symmetric_p99,symmetric_max";

std::size_t ParseCount(const std::string &text, const char *what)
{
    std::size_t used = 0;
    const unsigned long long value = std::stoull(text, &used);
    if (used != text.size() || value == 0) throw std::invalid_argument(std::string(what) + " must be a positive integer");
    return std::size_t(value);
}

int Usage()
{
    std::fprintf(stderr, "usage: gsmeshdist RECONSTRUCTION.ply ORIGINAL.ply [--samples N] [--seed S]\n"
                         "       gsmeshdist --csv-header\n");
    return 2;
}

} // namespace

int main(int argc, char **argv)
{
    try {
        if (argc == 2 && std::string(argv[1]) == "--csv-header") {
            std::printf("%s\n", kCsvHeader);
            return 0;
        }
        if (argc < 3 || argc % 2 == 0) return Usage();
        std::size_t samples = 1000000;
        std::uint64_t seed = 1;
        for (int a = 3; a < argc; a += 2) {
            const std::string key = argv[a], value = argv[a + 1];
            if (key == "--samples") samples = ParseCount(value, "--samples");
            else if (key == "--seed") seed = ParseCount(value, "--seed");
            else return Usage();
        }
        const std::vector<Triangle> reconstruction = LoadTriangles(argv[1]), original = LoadTriangles(argv[2]);
        const MeshDistance d = MeasureMeshDistance(reconstruction, original, samples, seed);
        std::printf("%zu,%zu,%zu,%.9g", reconstruction.size(), original.size(), samples, d.diagonal);
        for (const DistanceSummary &s : {d.toOriginal, d.toReconstruction, d.symmetric})
            std::printf(",%.6g,%.6g,%.6g", s.rms, s.p99, s.max);
        std::printf("\n");
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "gsmeshdist: %s\n", e.what());
        return 1;
    }
}
