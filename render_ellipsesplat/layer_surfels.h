#pragma once
// Turning a MeshLab layer into splats: which layers can be splatted, their ellipses, and a
// cheap fingerprint telling when a layer changed since its splats were uploaded.

#include "surfel_arrays.h"

#include <cstdint>

class MeshModel;

namespace splat {

// True when at least one live vertex has a non-zero normal. MeshLab loads a PLY without
// normals with all-zero normals, so the values are the only way to tell.
bool layerHasNormals(const MeshModel &layer);

// How a layer becomes splats: the neighbour count that sizes circles, and where surfels fitted
// to their blend stand (the settings panel's choices).
struct LayerSplatOptions
{
    int neighbours = kDefaultSplatNeighbours;
    bool atFittedPositions = false; // true: P; false: P - SurfelFitOffset N (undoFitOffsets)
};

// Surfels of every live vertex: ellipses from the EllipseMajorAxis/EllipseMinorAxis
// attributes when the layer has both, otherwise circles whose radius is R() when the radius
// component is enabled and positive, else the distance to the k-th nearest neighbour
// (nearestNeighbourRadii, which reports its progress). With the SurfelFitOffset attribute they
// stand at their unfitted positions unless options say otherwise. Vertices that cannot be drawn
// (removeUnusableSurfels: non-finite or huge coordinates, zero normals) are left out and
// counted in `skipped`.
SurfelArrays surfelsOfLayer(const MeshModel &layer, const LayerSplatOptions &options, std::size_t &skipped,
                            const ProgressCallback &progress = nullptr);

// Changes whenever anything surfelsOfLayer reads changes (positions, normals, colours,
// radii, ellipse attributes, fit offsets, which of them exist, and the options).
std::uint64_t layerFingerprint(const MeshModel &layer, const LayerSplatOptions &options);

} // namespace splat
