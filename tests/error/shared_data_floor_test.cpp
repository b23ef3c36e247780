// The metric's floor (S' = S) on the shared scanned models: what the MLS projection itself
// costs, against which a simplification's error is read. Skipped when ../shared/data is absent.

#include "point_sets.h"

#include <vcg_ext/surfel_error/surfel_error.h>
#include <wrap/io_trimesh/import_ply.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <ostream>
#include <string>

using surfel_error_test::PointSet;
using vcg::gaussphere::metric::ComputeSurfelError;
using vcg::gaussphere::metric::SurfelErrorStats;

namespace {

struct FloorCase
{
    const char* file;
    double maxNormalizedRms; // bound with headroom over the measured floor
};

// Names the case by its file in test listings instead of dumping its bytes.
void PrintTo(const FloorCase& c, std::ostream* os)
{
    *os << c.file;
}

class SurfelErrorFloor : public ::testing::TestWithParam<FloorCase>
{};

TEST_P(SurfelErrorFloor, ModelAgainstItself)
{
    const std::string path = std::string(GAUSSPHERE_SHARED_DATA_DIR) + "/" + GetParam().file;
    if (!std::ifstream(path).good())
        GTEST_SKIP() << path << " is absent: the shared data sets are not installed here";
    PointSet model;
    int mask = 0;
    ASSERT_EQ(vcg::tri::io::ImporterPLY<PointSet>::Open(model, path.c_str(), mask), 0) << path;
    ASSERT_TRUE(mask & vcg::tri::io::Mask::IOM_VERTNORMAL) << path << " has no normals";

    const auto start = std::chrono::steady_clock::now();
    const SurfelErrorStats stats = ComputeSurfelError(model, model);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s (%zu points) against itself: D*rms %.3g D*max %.3g D*p99.9 %.3g | "
                "L2,1 own rms %.3g max %.3g | blended rms %.3g max %.3g p99.9 %.3g | "
                "unconverged %zu | %.2f s\n",
                GetParam().file, stats.originalPointCount, stats.normalizedDistance.rms,
                stats.normalizedDistance.max, stats.normalizedDistance.p999, stats.normalToOwnSurfel.rms,
                stats.normalToOwnSurfel.max, stats.normalToBlended.rms, stats.normalToBlended.max,
                stats.normalToBlended.p999, stats.unconvergedCount, seconds);

    EXPECT_EQ(stats.distance.count, model.vert.size());
    EXPECT_LT(stats.normalizedDistance.rms, GetParam().maxNormalizedRms);
    EXPECT_LT(stats.normalToBlended.rms, 0.1);
    // Every point is its own nearest surfel, except among exact duplicates of the same normal.
    EXPECT_LT(stats.normalToOwnSurfel.p999, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(SharedModels, SurfelErrorFloor,
                         ::testing::Values(FloorCase{"bunny.ply", 5e-4}, FloorCase{"dragon.ply", 5e-4}),
                         [](const ::testing::TestParamInfo<FloorCase>& info) {
                             const std::string file = info.param.file;
                             return file.substr(0, file.find('.'));
                         });

} // namespace
