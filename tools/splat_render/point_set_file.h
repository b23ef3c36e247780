#pragma once
// Reading a point set, a .surfel file or a triangle mesh from PLY (ascii or binary) into plain
// arrays for the splat renderer. Properties the file lacks stay empty. Surfels with a
// `fit_offset` property are moved back to their unfitted positions (undoFitOffsets).

#include "surfel_arrays.h"

#include <string>
#include <vector>

namespace splat {

struct PointSetFile
{
    SurfelArrays surfels;            // positions always; normals, colours, ellipse axes if in the file
    std::vector<float> radii;        // `radius` property, empty if absent
    std::vector<unsigned> triangles; // three vertex indices per triangle (polygons fanned)
    bool hasNormals = false;         // the file has nx ny nz and they are not all zero
};

// Throws std::runtime_error when the file cannot be read as PLY.
PointSetFile readPointSetFile(const std::string &path);

} // namespace splat
