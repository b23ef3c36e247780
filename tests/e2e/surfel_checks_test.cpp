// The checks of surfel_check: valid surfels pass, and each kind of broken surfel is caught.
#include "surfel_checks.h"
#include "surfel_fixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace {

using surfel_io::SurfelRecord;
using Ellipses = SurfelExpectations::Ellipses;

SurfelExpectations strict() {
  SurfelExpectations expected;
  expected.minCount = expected.maxCount = 20;
  expected.ellipses = Ellipses::Required;
  expected.checkQualitySum = true;
  expected.qualitySum = 93;  // sum of 1 + i % 9 over 20 surfels
  return expected;
}

// The failures reported for synthetic surfels whose surfel 5 is broken by `breakIt`, one
// per line (a broken property may break others with it, e.g. a NaN normal is not unit and
// has no tangent axes).
std::string failuresOf(const std::function<void(SurfelRecord&)>& breakIt) {
  std::vector<SurfelRecord> surfels = syntheticSurfels(20);
  breakIt(surfels[5]);
  std::string lines;
  for (const std::string& failure : checkSurfels(surfels, strict())) lines += failure + "\n";
  return lines;
}

TEST(SurfelChecks, SyntheticSurfelsPassEveryCheck) {
  EXPECT_TRUE(checkSurfels(syntheticSurfels(20), strict()).empty());
}

TEST(SurfelChecks, ReportsEachBrokenProperty) {
  const struct {
    const char* expected;
    std::function<void(SurfelRecord&)> breakIt;
  } cases[] = {
      {"finite position: 1 of 20 surfels fail, first surfel 5", [](SurfelRecord& s) { s.position[1] = NAN; }},
      {"unit normal", [](SurfelRecord& s) { s.normal[0] *= 1.01f; }},
      {"unit normal", [](SurfelRecord& s) { s.normal[2] = NAN; }},
      {"radius > 0", [](SurfelRecord& s) { s.radius = 0; }},
      {"|major| >= |minor| > 0", [](SurfelRecord& s) { std::swap(s.majorAxis, s.minorAxis); }},
      {"|major| >= |minor| > 0", [](SurfelRecord& s) { s.minorAxis = surfel_io::Vec3f{}; }},
      {"axes tangent to the normal", [](SurfelRecord& s) {
         for (int k = 0; k < 3; ++k) s.majorAxis[k] += 0.01f * s.normal[k];
         s.radius = std::sqrt(s.majorAxis[0] * s.majorAxis[0] + s.majorAxis[1] * s.majorAxis[1] +
                              s.majorAxis[2] * s.majorAxis[2]);
       }},
      {"axes orthogonal", [](SurfelRecord& s) {
         for (int k = 0; k < 3; ++k) s.minorAxis[k] += 0.1f * s.majorAxis[k];
       }},
      {"radius = |major|", [](SurfelRecord& s) { s.radius *= 1.5f; }},
      {"quality sum: 94", [](SurfelRecord& s) { s.quality += 1; }},
  };
  for (const auto& c : cases) {
    const std::string failures = failuresOf(c.breakIt);
    const std::size_t at = failures.find(c.expected);
    EXPECT_TRUE(at == 0 || (at != std::string::npos && failures[at - 1] == '\n'))
        << "expected a line starting with '" << c.expected << "' in:\n" << failures;
  }
}

TEST(SurfelChecks, ChecksTheCountRange) {
  SurfelExpectations expected;
  expected.minCount = 21;
  EXPECT_EQ(checkSurfels(syntheticSurfels(20), expected),
            std::vector<std::string>{"count: 20 surfels, expected 21.."});
  expected.minCount = 5;
  expected.maxCount = 10;
  EXPECT_EQ(checkSurfels(syntheticSurfels(20), expected),
            std::vector<std::string>{"count: 20 surfels, expected 5..10"});
}

TEST(SurfelChecks, AbsentEllipsesMeansZeroAxes) {
  SurfelExpectations expected;
  expected.ellipses = Ellipses::Absent;
  std::vector<SurfelRecord> surfels = syntheticSurfels(3);
  EXPECT_EQ(checkSurfels(surfels, expected).size(), 1u);
  for (SurfelRecord& s : surfels) s.majorAxis = s.minorAxis = surfel_io::Vec3f{};
  EXPECT_TRUE(checkSurfels(surfels, expected).empty());
}

}  // namespace
