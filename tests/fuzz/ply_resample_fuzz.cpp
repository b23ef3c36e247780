// libFuzzer target: gsresample's PLY reader (tools/gsresample/ply_input.h), then the whole
// resampling (vcg_ext/gaussphere/resampling.h) on what it reads. Both must refuse bad input
// with a reason or a std::exception; every surfel of an accepted input must be finite.
// The reader takes a path, so each input goes through one temporary file. Inputs of more than
// kMaxPoints points are read only, to keep the executions fast. One OpenMP thread: runs
// reproduce exactly.
#include <tools/gsresample/ply_input.h>
#include <vcg_ext/gaussphere/oriented_point_mesh.h>
#include <vcg_ext/gaussphere/resampling.h>

#include <omp.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

namespace {

constexpr int kMaxPoints = 3000;

std::string inputPath;

void removeInput() { std::remove(inputPath.c_str()); }

void check(bool condition, const char *what)
{
    if (condition) return;
    std::fprintf(stderr, "ply_resample_fuzz: %s\n", what);
    std::abort();
}

bool finite(const vcg::Point3f &p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

} // namespace

extern "C" int LLVMFuzzerInitialize(int *, char ***)
{
    const char *tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/ply_resample_fuzz-XXXXXX";
    const int fd = mkstemp(&pattern[0]);
    check(fd >= 0, "cannot create a temporary file");
    close(fd);
    inputPath = pattern;
    std::atexit(removeInput);
    omp_set_num_threads(1);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
    {
        std::ofstream file(inputPath, std::ios::binary | std::ios::trunc);
        file.write(reinterpret_cast<const char *>(data), std::streamsize(size));
        check(bool(file.flush()), "cannot write the temporary file");
    }
    vcg::gaussphere::OrientedPointMesh mesh;
    std::string error;
    gsresample::InputInfo info; // as gsresample reads: double coordinates near the origin
    if (!gsresample::ReadOrientedPoints(inputPath, mesh, error, &info)) {
        check(!error.empty(), "a refused file without a reason");
        return 0;
    }
    if (mesh.vert.size() > std::size_t(kMaxPoints)) return 0;

    // Small settings; the input's size picks one of the two ways to set the output size, so
    // the corpus covers the target-count search and exchanges as well as the error bound.
    vcg::gaussphere::ResamplingParams param;
    param.subdivisionLevel = 4;
    param.neighborCount = 8;
    param.tuning.maxIterations = 3;
    if (size % 2 == 0) {
        param.targetCount = int(mesh.vert.size() / 4) + 1;
        param.maxErrorExchanges = 4;
    } else {
        param.maxErrorFraction = 0.01;
    }
    try {
        const vcg::gaussphere::ResamplingResult result = vcg::gaussphere::ResamplePointSet(mesh, param);
        for (const vcg::gaussphere::Surfel &s : result.surfels) {
            check(finite(s.position) && finite(s.normal) && finite(s.majorAxis) && finite(s.minorAxis),
                  "a surfel with a non-finite position, normal or axis");
            check(std::isfinite(s.blendScale) && std::isfinite(s.fitOffset),
                  "a surfel with a non-finite blend scale or fit offset");
        }
    } catch (const std::exception &) {
        // Refused input (fewer than two usable points, ...): a clean outcome.
    }
    return 0;
}
