#include "surfel_checks.h"

#include <cmath>
#include <sstream>

namespace {

using surfel_io::SurfelRecord;
using surfel_io::Vec3f;

double dot(const Vec3f& a, const Vec3f& b) {
  return double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
}
double length(const Vec3f& v) { return std::sqrt(dot(v, v)); }
bool isFinite(const Vec3f& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}
std::string format(const Vec3f& v) {
  std::ostringstream text;
  text << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return text.str();
}

// Counts the surfels failing one check and remembers the first of them.
class Check {
 public:
  explicit Check(std::string what) : what_(std::move(what)) {}

  // Conditions are written as what must hold, so that NaN fails them.
  void expect(bool holds, std::size_t index, const std::string& detail) {
    if (holds) return;
    if (failures_++ == 0) firstFailure_ = "surfel " + std::to_string(index) + ": " + detail;
  }

  void report(std::size_t total, std::vector<std::string>& lines) const {
    if (failures_ > 0)
      lines.push_back(what_ + ": " + std::to_string(failures_) + " of " + std::to_string(total) +
                      " surfels fail, first " + firstFailure_);
  }

 private:
  std::string what_;
  std::size_t failures_ = 0;
  std::string firstFailure_;
};

}  // namespace

std::vector<std::string> checkSurfels(const std::vector<SurfelRecord>& surfels,
                                      const SurfelExpectations& expected) {
  std::vector<std::string> failures;
  if (surfels.size() < expected.minCount || surfels.size() > expected.maxCount) {
    std::string range = std::to_string(expected.minCount) + "..";
    if (expected.maxCount != std::numeric_limits<std::size_t>::max())
      range += std::to_string(expected.maxCount);
    failures.push_back("count: " + std::to_string(surfels.size()) + " surfels, expected " + range);
  }

  const double tol = expected.tolerance;
  Check finitePosition("finite position"), unitNormal("unit normal"), positiveRadius("radius > 0");
  Check axesLength("|major| >= |minor| > 0"), tangent("axes tangent to the normal"),
      orthogonal("axes orthogonal"), radiusIsMajor("radius = |major|"),
      noAxes("no ellipse frame (zero axes)");
  double qualitySum = 0;
  for (std::size_t i = 0; i < surfels.size(); ++i) {
    const SurfelRecord& s = surfels[i];
    finitePosition.expect(isFinite(s.position), i, "position " + format(s.position));
    unitNormal.expect(std::abs(length(s.normal) - 1) <= tol, i, "normal " + format(s.normal));
    positiveRadius.expect(s.radius > 0 && std::isfinite(s.radius), i,
                          "radius " + std::to_string(s.radius));
    qualitySum += s.quality;

    const double major = length(s.majorAxis), minor = length(s.minorAxis);
    const std::string axes = "major " + format(s.majorAxis) + ", minor " + format(s.minorAxis);
    if (expected.ellipses == SurfelExpectations::Ellipses::Required) {
      axesLength.expect(minor > 0 && minor <= major * (1 + tol), i, axes);
      tangent.expect(std::abs(dot(s.majorAxis, s.normal)) <= tol * major &&
                         std::abs(dot(s.minorAxis, s.normal)) <= tol * minor,
                     i, axes + ", normal " + format(s.normal));
      orthogonal.expect(std::abs(dot(s.majorAxis, s.minorAxis)) <= tol * major * minor, i, axes);
      radiusIsMajor.expect(std::abs(s.radius - major) <= tol * major, i,
                           "radius " + std::to_string(s.radius) + ", " + axes);
    } else if (expected.ellipses == SurfelExpectations::Ellipses::Absent) {
      noAxes.expect(major == 0 && minor == 0, i, axes);
    }
  }
  for (const Check* check : {&finitePosition, &unitNormal, &positiveRadius, &axesLength, &tangent,
                             &orthogonal, &radiusIsMajor, &noAxes})
    check->report(surfels.size(), failures);
  // Qualities are point counts: integers, exact in float up to 2^24.
  if (expected.checkQualitySum && !(std::abs(qualitySum - expected.qualitySum) < 0.5))
    failures.push_back("quality sum: " + std::to_string(qualitySum) + ", expected " +
                       std::to_string(expected.qualitySum));
  return failures;
}
