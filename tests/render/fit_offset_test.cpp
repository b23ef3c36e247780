// Surfels the resampler fitted to their blend are drawn at their unfitted positions:
// moveToSampledSurface, and readPointSetFile applying a `fit_offset` vertex property.

#include "point_set_file.h"
#include "surfel_arrays.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

using namespace splat;

namespace {

// Two oriented points as an ASCII PLY, with the fit offsets 0.25 and 0.5 when `fitted`.
std::string writePointSet(const std::string &name, bool fitted)
{
    const std::string path = testing::TempDir() + name;
    std::ofstream out(path);
    out << "ply\nformat ascii 1.0\nelement vertex 2\n"
           "property float x\nproperty float y\nproperty float z\n"
           "property float nx\nproperty float ny\nproperty float nz\n"
        << (fitted ? "property float fit_offset\n" : "") << "end_header\n"
        << "0 0 1 0 0 1" << (fitted ? " 0.25" : "") << "\n"
        << "1 0 0 0.6 0.8 0" << (fitted ? " 0.5" : "") << "\n";
    return path;
}

void expectNear(const std::vector<float> &actual, const std::vector<float> &expected)
{
    ASSERT_EQ(actual.size(), expected.size());
    for (std::size_t i = 0; i < actual.size(); ++i)
        EXPECT_FLOAT_EQ(actual[i], expected[i]) << "coordinate " << i;
}

} // namespace

TEST(FitOffsets, MoveToSampledSurfaceMovesAlongTheNormalByTheOffset)
{
    SurfelArrays surfels;
    surfels.positions = {1, 2, 3, 0, 0, 0};
    surfels.normals = {0, 0, 1, 0.6f, 0.8f, 0};
    moveToSampledSurface(surfels, {0.5f, -2.0f});
    expectNear(surfels.positions, {1, 2, 2.5f, 1.2f, 1.6f, 0});

    const std::vector<float> moved = surfels.positions;
    moveToSampledSurface(surfels, {});
    EXPECT_EQ(surfels.positions, moved) << "no fit offsets: nothing to move";
}

TEST(FitOffsets, ReadPointSetFileAppliesTheFitOffsetProperty)
{
    const std::string fitted = writePointSet("fit_offset_fitted.ply", true);
    const PointSetFile file = readPointSetFile(fitted);
    std::remove(fitted.c_str());
    expectNear(file.surfels.positions, {0, 0, 0.75f, 0.7f, -0.4f, 0});
    expectNear(file.surfels.normals, {0, 0, 1, 0.6f, 0.8f, 0});

    const std::string plain = writePointSet("fit_offset_plain.ply", false);
    const PointSetFile withoutOffsets = readPointSetFile(plain);
    std::remove(plain.c_str());
    expectNear(withoutOffsets.surfels.positions, {0, 0, 1, 1, 0, 0});
}
