#ifndef GSBENCH_KNN_REFERENCE_H
#define GSBENCH_KNN_REFERENCE_H

#include "point_sets.h"

namespace gsbench {

/// Seconds for the k nearest neighbours of every point of `mesh` by nanoflann's kd-tree (leaf
/// size 10), tree build included, on the current OpenMP thread count: the first step of the
/// paper's method done by a standard library, the reference beside the whole filter's time.
/// Each query asks for k + 1 points, the point itself among them, as the resampler's k
/// neighbours leave the point out.
double TimeNanoflannNeighbors(const PointMesh &mesh, int k);

} // namespace gsbench

#endif
