// Reading an oriented point set from a PLY file, safely on any input: the header is read and
// checked here before vcglib's ImporterPLY sees the file, because that reader trusts it (it
// allocates what the counts announce and reads lists into fixed-size buffers). Qt-free.
#ifndef GSRESAMPLE_PLY_INPUT_H
#define GSRESAMPLE_PLY_INPUT_H

#include <string>

#include <vcg_ext/gaussphere/oriented_point_mesh.h>

namespace gsresample {

/// Reads an oriented point set (x y z nx ny nz per vertex) from a PLY file. On failure returns false and
/// sets `error` to one line (at most 200 characters, printable ASCII only) naming the reason.
bool ReadOrientedPoints(const std::string &path, vcg::gaussphere::OrientedPointMesh &mesh, std::string &error);

} // namespace gsresample

#endif
