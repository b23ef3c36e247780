// surfel_check: checks a .surfel file, for the end-to-end tests.
//
//   surfel_check FILE [--count N | --min-count N --max-count M]
//                     [--require-ellipses | --require-no-ellipses]
//                     [--quality-sum N] [--tolerance T]
//
// Always checked: FILE reads as a .surfel file (docs/surfel_format.md), the surfel count
// lies in the given range, positions are finite, normals have unit length, radii are > 0.
//   --count N              exactly N surfels (same as --min-count N --max-count N)
//   --min-count N          at least N surfels
//   --max-count M          at most M surfels
//   --require-ellipses     every surfel has an ellipse frame: both axes tangent to the
//                          normal and orthogonal, |major| >= |minor| > 0, radius = |major|
//   --require-no-ellipses  every axis is zero (a layer saved without ellipse attributes)
//   --quality-sum N        the qualities (points each surfel represents) add up to N, e.g.
//                          the number of input points with a valid normal
//   --tolerance T          relative tolerance of the geometric checks (default 1e-4)
//
// Exit status: 0 when every check passes, 1 when some fail (one line per failed check on
// stderr), 2 for a bad command line or a file that does not read.
// Example: surfel_check out.surfel --min-count 100 --max-count 2000 --require-ellipses
#include "surfel_checks.h"

#include <surfel_file.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

const char* const kUsage =
    "usage: surfel_check FILE [--count N | --min-count N --max-count M]\n"
    "                         [--require-ellipses | --require-no-ellipses]\n"
    "                         [--quality-sum N] [--tolerance T]\n";

bool parseNumber(const char* text, double& value) {
  char* end = nullptr;
  value = std::strtod(text, &end);
  return end != text && *end == '\0' && std::isfinite(value) && value >= 0;
}

bool parseArguments(int argc, char** argv, std::string& path, SurfelExpectations& expected) {
  for (int i = 1; i < argc; ++i) {
    const std::string option = argv[i];
    if (option.compare(0, 2, "--") != 0) {
      if (!path.empty()) return false;
      path = option;
      continue;
    }
    if (option == "--require-ellipses" || option == "--require-no-ellipses") {
      if (expected.ellipses != SurfelExpectations::Ellipses::Unchecked) return false;
      expected.ellipses = option == "--require-ellipses" ? SurfelExpectations::Ellipses::Required
                                                         : SurfelExpectations::Ellipses::Absent;
      continue;
    }
    double value = 0;
    if (i + 1 >= argc || !parseNumber(argv[++i], value)) return false;
    if (option == "--count")
      expected.minCount = expected.maxCount = std::size_t(value);
    else if (option == "--min-count")
      expected.minCount = std::size_t(value);
    else if (option == "--max-count")
      expected.maxCount = std::size_t(value);
    else if (option == "--quality-sum") {
      expected.checkQualitySum = true;
      expected.qualitySum = value;
    } else if (option == "--tolerance")
      expected.tolerance = value;
    else
      return false;
  }
  return !path.empty();
}

}  // namespace

int main(int argc, char** argv) {
  std::string path;
  SurfelExpectations expected;
  if (!parseArguments(argc, argv, path, expected)) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  std::vector<surfel_io::SurfelRecord> surfels;
  std::string error;
  if (!surfel_io::readSurfelFile(path, surfels, error)) {
    std::fprintf(stderr, "surfel_check: %s: %s\n", path.c_str(), error.c_str());
    return 2;
  }
  const std::vector<std::string> failures = checkSurfels(surfels, expected);
  for (const std::string& failure : failures)
    std::fprintf(stderr, "surfel_check: %s: %s\n", path.c_str(), failure.c_str());
  if (failures.empty())
    std::printf("surfel_check: %s: %zu surfels, all checks pass\n", path.c_str(), surfels.size());
  return failures.empty() ? 0 : 1;
}
