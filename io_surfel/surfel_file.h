// Reader and writer of `.surfel` files (docs/surfel_format.md): a binary little-endian
// PLY file with one `vertex` element whose properties are, in this order,
//   float x y z nx ny nz radius major_x major_y major_z minor_x minor_y minor_z quality blend_scale
//   fit_offset
//   uchar red green blue alpha
// (version 3; version 2 files, without fit_offset, and version 1 files, without blend_scale
// either, are read too).
// No Qt, no vcg: the MeshLab plugin, tests and tools share this code (surfel_records_mesh.h
// converts to and from vcg meshes).
#ifndef GAUSSPHERE_IO_SURFEL_SURFEL_FILE_H
#define GAUSSPHERE_IO_SURFEL_SURFEL_FILE_H

#include <array>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "printable_text.h"

namespace surfel_io {

using Vec3f = std::array<float, 3>;

// One record of a `.surfel` file. The ellipse is { position + x*majorAxis + y*minorAxis :
// x^2 + y^2 <= 1 }; a surfel written from a layer without ellipse frames has zero axes.
struct SurfelRecord {
  Vec3f position{};
  Vec3f normal{};
  float radius = 0;
  Vec3f majorAxis{};
  Vec3f minorAxis{};
  float quality = 0;
  float blendScale = 1;  // factor on the axes in blending weights only (version 2; 1 in version 1)
  float fitOffset = 0;   // move along the normal that fitted the surfel to its blend (version 3; 0 before)
  std::array<std::uint8_t, 4> color{};  // red, green, blue, alpha
};

bool operator==(const SurfelRecord& a, const SurfelRecord& b);
inline bool operator!=(const SurfelRecord& a, const SurfelRecord& b) { return !(a == b); }

// The `comment` line that marks a PLY file as a `.surfel` file of the version written; the
// reader also accepts the older versions.
constexpr const char* kSurfelFileMagic = "gaussphere-surfel 3";
constexpr const char* kSurfelFileMagicVersion2 = "gaussphere-surfel 2";
constexpr const char* kSurfelFileMagicVersion1 = "gaussphere-surfel 1";

// Every reason these functions put in `error` is one line of at most kMaxReasonLength
// printable ASCII characters: text taken from the file or a path is cut and escaped
// (printableText).
constexpr std::size_t kMaxReasonLength = 200;

// Reading is strict: anything but the exact layout above (extra `comment` and `obj_info`
// lines aside), a data section shorter or longer than the header announces, a record whose
// geometry (position, normal, radius or an axis: the first 13 floats) is not finite, or an
// unreadable file fails with a reason in `error` naming what is wrong (for a record: its
// index and the property); `surfels` is then left empty.
bool readSurfels(std::istream& in, std::vector<SurfelRecord>& surfels, std::string& error);
bool readSurfelFile(const std::string& path, std::vector<SurfelRecord>& surfels, std::string& error);

// The number of records of the file at `path`, from its header, after the same checks of the
// header and of the data section's size as readSurfelFile (the records themselves are not read).
bool readSurfelCount(const std::string& path, std::uint64_t& count, std::string& error);

// Writing refuses, before writing anything, surfels the reader would refuse (non-finite
// geometry), naming the first one; quality, blend scale, fit offset and colour are written as
// they are. writeSurfelFile saves through a FileReplacement (file_replacement.h): a failed save
// leaves the previous file as it was.
bool writeSurfels(std::ostream& out, const std::vector<SurfelRecord>& surfels, std::string& error);
bool writeSurfelFile(const std::string& path, const std::vector<SurfelRecord>& surfels,
                     std::string& error);

// writeSurfels in parts, for a file written from several record lists in turn: the header
// announcing `count` records, then the lists, each refused as a whole for non-finite geometry.
void writeSurfelHeader(std::ostream& out, std::uint64_t count);
bool writeSurfelRecords(std::ostream& out, const std::vector<SurfelRecord>& surfels, std::string& error);

// True when some surfel has a non-zero axis. A file without any is one written from a layer
// without ellipse frames, and loads without the ellipse attributes.
bool hasEllipseFrames(const std::vector<SurfelRecord>& surfels);

// True when some surfel's blend scale differs from 1: only then does a loaded layer get the
// blend scale attribute.
bool hasBlendScales(const std::vector<SurfelRecord>& surfels);

// True when some surfel's fit offset is not 0: only then does a loaded layer get the fit
// offset attribute.
bool hasFitOffsets(const std::vector<SurfelRecord>& surfels);

}  // namespace surfel_io

#endif
