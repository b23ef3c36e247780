// The checks behind the surfel_check program (surfel_check.cpp), kept apart so that unit
// tests can feed them broken surfels.
#ifndef GAUSSPHERE_TESTS_E2E_SURFEL_CHECKS_H
#define GAUSSPHERE_TESTS_E2E_SURFEL_CHECKS_H

#include <surfel_file.h>

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

struct SurfelExpectations {
  enum class Ellipses { Unchecked, Required, Absent };

  std::size_t minCount = 0;
  std::size_t maxCount = std::numeric_limits<std::size_t>::max();
  Ellipses ellipses = Ellipses::Unchecked;
  bool checkQualitySum = false;
  double qualitySum = 0;
  // Relative tolerance of the geometric checks (unit length, tangency, orthogonality, ...).
  double tolerance = 1e-4;
};

// Always checked: the count range, finite positions, unit normals and radii > 0.
// Ellipses::Required: every surfel has axes tangent to its normal, orthogonal to each other,
// |major| >= |minor| > 0, and radius = |major|. Ellipses::Absent: every axis is zero.
// Returns one line per failed check, naming how many surfels fail it and the first of them;
// empty when everything holds.
std::vector<std::string> checkSurfels(const std::vector<surfel_io::SurfelRecord>& surfels,
                                      const SurfelExpectations& expected);

#endif
