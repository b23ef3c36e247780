// Synthetic surfels for the tests: valid ellipse frames on the unit sphere, every attribute
// varying from surfel to surfel (see surfel_fixture.cpp).
#ifndef GAUSSPHERE_TESTS_E2E_SURFEL_FIXTURE_H
#define GAUSSPHERE_TESTS_E2E_SURFEL_FIXTURE_H

#include <surfel_file.h>

#include <cmath>
#include <cstddef>
#include <vector>

inline std::vector<surfel_io::SurfelRecord> syntheticSurfels(std::size_t count) {
  struct V {
    double x, y, z;
    V operator*(double s) const { return {x * s, y * s, z * s}; }
    V operator+(const V& o) const { return {x + o.x, y + o.y, z + o.z}; }
    V cross(const V& o) const { return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x}; }
    V unit() const { return *this * (1 / std::sqrt(x * x + y * y + z * z)); }
    surfel_io::Vec3f toFloat() const { return {{float(x), float(y), float(z)}}; }
  };
  const double goldenAngle = M_PI * (3 - std::sqrt(5.0));
  std::vector<surfel_io::SurfelRecord> surfels(count);
  for (std::size_t i = 0; i < count; ++i) {
    // Fibonacci lattice: evenly spread normals.
    const double z = 1 - 2 * (i + 0.5) / count, ring = std::sqrt(1 - z * z);
    const V normal = V{ring * std::cos(goldenAngle * i), ring * std::sin(goldenAngle * i), z}.unit();
    const V helper = std::abs(normal.z) < 0.9 ? V{0, 0, 1} : V{1, 0, 0};
    const V u = normal.cross(helper).unit(), w = normal.cross(u);
    const double turn = 0.7 * i, majorLength = 0.05 * (1 + (i % 7) / 7.0);
    const V major = (u * std::cos(turn) + w * std::sin(turn)) * majorLength;
    const V minor = (u * -std::sin(turn) + w * std::cos(turn)) * (majorLength * (0.3 + 0.1 * (i % 5)));

    surfel_io::SurfelRecord& s = surfels[i];
    s.position = (normal * (1 + 0.01 * (i % 3))).toFloat();
    s.normal = normal.toFloat();
    s.majorAxis = major.toFloat();
    s.minorAxis = minor.toFloat();
    s.radius = std::sqrt(s.majorAxis[0] * s.majorAxis[0] + s.majorAxis[1] * s.majorAxis[1] +
                         s.majorAxis[2] * s.majorAxis[2]);
    s.quality = float(1 + i % 9);
    s.blendScale = i % 4 == 3 ? 0.25f : 1.f;
    s.fitOffset = i % 3 == 0 ? 0.f : 0.001f * (float(i % 5) - 2.5f);
    s.color = {{std::uint8_t(i * 37), std::uint8_t(i * 91), std::uint8_t(i * 53),
                std::uint8_t(i % 2 ? 200 : 255)}};
  }
  return surfels;
}

#endif
