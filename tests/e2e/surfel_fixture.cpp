// surfel_fixture OUT.surfel [COUNT]
//
// Writes COUNT (default 200) synthetic surfels spread over the unit sphere: unit normals,
// tangent orthogonal ellipse axes (major longer than minor, radius = major length), and
// quality, colour, blend scale and fit offset that differ from surfel to surfel, so that a
// round trip which loses or mixes up any attribute shows. Deterministic: the same COUNT gives the same bytes.
#include "surfel_fixture.h"

#include <surfel_file.h>

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: %s OUT.surfel [COUNT]\n", argv[0]);
    return 2;
  }
  const long count = argc == 3 ? std::strtol(argv[2], nullptr, 10) : 200;
  if (count < 0) {
    std::fprintf(stderr, "%s: COUNT must be >= 0\n", argv[0]);
    return 2;
  }
  std::string error;
  if (!surfel_io::writeSurfelFile(argv[1], syntheticSurfels(std::size_t(count)), error)) {
    std::fprintf(stderr, "%s: %s\n", argv[0], error.c_str());
    return 1;
  }
  return 0;
}
