// Large oriented point sets for the scaling benchmark, generated in memory.
//
// Two families, both deterministic for a given seed (the random stream is std::mt19937_64,
// whose sequence the standard fixes, converted to doubles and Gaussians by hand rather
// than through the implementation-defined std:: distributions):
//
// - densified real model: N points uniformly distributed over the triangles of a mesh with
//   per-vertex normals (a face chosen with probability proportional to its area, a uniform
//   point in it), normal = the barycentric interpolation of the vertex normals, normalized;
// - "drilled box": the cube [-1,1]^3 with a cylindrical hole of radius 1/2 along z, with
//   exact normals: 12 box edges and 2 hole rims are sharp 90-degree features.
//
// Optional Gaussian position noise (sigma as a fraction of the bounding-box diagonal)
// models scanner noise; the normals stay exact.
#ifndef GSSCALE_POINT_GENERATOR_H
#define GSSCALE_POINT_GENERATOR_H

#include <cstdint>
#include <string>

#include <vcg_ext/gaussphere/oriented_point_mesh.h>

namespace gsscale {

struct GeneratorParams
{
    std::string shape = "dragon"; ///< "drilled-box", or a model NAME read from dataDir/NAME_mesh.ply
    std::string dataDir;          ///< where the NAME_mesh.ply files are
    long long count = 1000000;    ///< points to generate
    std::uint64_t seed = 1;
    double noise = 0;             ///< position noise sigma, as a fraction of the bbox diagonal
    /// Point order: "random" (the sampling order: no spatial coherence, the worst case for
    /// caches) or "morton" (sorted along a Z-order curve, like a well-ordered scan).
    std::string order = "random";
    // Degenerate inputs for the worst-case review (0 = off):
    long long coincident = 0;     ///< the last M points become copies of the first one
    double outlier = 0;           ///< the last point moves D bbox diagonals away from the box
};

/// Fills `out` (cleared first) with params.count oriented points (positions and unit
/// normals; no faces). Throws std::runtime_error when the source mesh cannot be read or
/// has no area or no normals.
void GeneratePoints(const GeneratorParams &params, vcg::gaussphere::OrientedPointMesh &out);

/// Writes the vertices of `mesh` as binary little-endian PLY with float x y z nx ny nz.
/// Throws std::runtime_error on an I/O error.
void WriteOrientedPly(const vcg::gaussphere::OrientedPointMesh &mesh, const std::string &path);

} // namespace gsscale

#endif
