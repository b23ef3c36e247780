// The algorithm headers compile where Qt's keyword macros are defined, as in the MeshLab plugins,
// which include them after Qt's headers: a parameter named `slots` once broke the filter's build
// while every test here, built without Qt, passed.
#include <gtest/gtest.h>

// As qobjectdefs.h defines them (foreach as a function-like macro, as Q_FOREACH).
#define slots
#define signals public
#define emit
#define foreach(variable, container) for (variable : container)

#include <vcg_ext/gaussphere/resampling.h>
#include <vcg_ext/surfel_error/surfel_error.h>

#include "pipeline_support.h"

TEST(QtKeywordMacros, TheAlgorithmsBuildAndRunUnderThem)
{
    const gstest::PointSet s = gstest::PlaneGrid(20, 20);
    const vcg::gaussphere::ResamplingResult r = gstest::Resample(s);
    EXPECT_GT(r.surfels.size(), 0u);
    EXPECT_LT(r.surfels.size(), size_t(s.Size()));
}
