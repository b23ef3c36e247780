// Surfels the resampler fitted to their blend are drawn at their unfitted positions:
// undoFitOffsets, and readPointSetFile applying a `fit_offset` vertex property.

#include "point_set_file.h"
#include "surfel_arrays.h"
#include "surfel_file.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <limits>
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
    undoFitOffsets(surfels, {0.5f, -2.0f});
    expectNear(surfels.positions, {1, 2, 2.5f, 1.2f, 1.6f, 0});

    const std::vector<float> moved = surfels.positions;
    undoFitOffsets(surfels, {});
    EXPECT_EQ(surfels.positions, moved) << "no fit offsets: nothing to move";
}

TEST(FitOffsets, NonFiniteOffsetsAndMissingNormalsMoveNothing)
{
    SurfelArrays surfels;
    surfels.positions = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    surfels.normals = {0, 0, 1, 0, 1, 0, 1, 0, 0};
    undoFitOffsets(surfels, {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 1.0f});
    expectNear(surfels.positions, {1, 2, 3, 4, 5, 6, 6, 8, 9});

    SurfelArrays unoriented;
    unoriented.positions = {1, 2, 3};
    undoFitOffsets(unoriented, {1.0f});
    EXPECT_EQ(unoriented.positions, (std::vector<float>{1, 2, 3}));
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

// The path bench/render takes: a binary .surfel (version 3) written by the io_surfel library.
TEST(FitOffsets, ReadPointSetFileAppliesTheOffsetsOfASurfelFile)
{
    std::vector<surfel_io::SurfelRecord> records(2);
    records[0].position = {{0, 0, 1}};
    records[0].normal = {{0, 0, 1}};
    records[0].fitOffset = 0.25f;
    records[1].position = {{1, 0, 0}};
    records[1].normal = {{0.6f, 0.8f, 0}};
    records[1].fitOffset = -0.5f;
    for (auto &r : records) {
        r.majorAxis = {{0.1f, 0, 0}};
        r.minorAxis = {{0, 0.05f, 0}};
    }
    const std::string path = testing::TempDir() + "fit_offset.surfel";
    std::string error;
    ASSERT_TRUE(surfel_io::writeSurfelFile(path, records, error)) << error;
    const PointSetFile file = readPointSetFile(path);
    std::remove(path.c_str());
    expectNear(file.surfels.positions, {0, 0, 0.75f, 1.3f, 0.4f, 0});
}
