#include "surfel_file.h"

#include "file_replacement.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <istream>
#include <limits>
#include <ostream>
#include <sstream>

namespace surfel_io {
namespace {

static_assert(std::numeric_limits<float>::is_iec559 && sizeof(float) == 4,
              "the file stores IEEE 754 single precision floats");

// Each version appends one float property to the previous one's: version 2 blend_scale,
// version 3 fit_offset.
constexpr std::size_t kFloatPropertyCount = 16;
constexpr std::size_t kColorPropertyCount = 4;
constexpr const char* kFloatPropertyNames[kFloatPropertyCount] = {
    "x", "y", "z", "nx", "ny", "nz", "radius", "major_x", "major_y", "major_z",
    "minor_x", "minor_y", "minor_z", "quality", "blend_scale", "fit_offset"};
constexpr const char* kColorPropertyNames[kColorPropertyCount] = {"red", "green", "blue", "alpha"};

// Position, normal, radius and the two axes: the first floats of a record, which must be finite
// (docs/surfel_format.md). The others have a documented reading of any value.
constexpr std::size_t kGeometryFloatCount = 13;

std::size_t recordBytes(std::size_t floatCount) { return floatCount * 4 + kColorPropertyCount; }

struct Version {
  const char* magic;
  std::size_t floatCount;
};
constexpr Version kVersions[] = {{kSurfelFileMagic, kFloatPropertyCount},
                                 {kSurfelFileMagicVersion2, kFloatPropertyCount - 1},
                                 {kSurfelFileMagicVersion1, kFloatPropertyCount - 2}};

// The version whose `comment` text is `text`, or null.
const Version* findVersion(const std::string& text) {
  for (const Version& version : kVersions)
    if (text == version.magic) return &version;
  return nullptr;
}

// Where the float properties of a record live in a SurfelRecord, in kFloatPropertyNames' order.
std::array<float*, kFloatPropertyCount> floatFields(SurfelRecord& s) {
  return {{&s.position[0], &s.position[1], &s.position[2], &s.normal[0], &s.normal[1],
           &s.normal[2], &s.radius, &s.majorAxis[0], &s.majorAxis[1], &s.majorAxis[2],
           &s.minorAxis[0], &s.minorAxis[1], &s.minorAxis[2], &s.quality, &s.blendScale,
           &s.fitOffset}};
}

// Explicit byte order, so the file is little-endian whatever the host is.
void storeFloat(float value, unsigned char* out) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  for (int i = 0; i < 4; ++i) out[i] = static_cast<unsigned char>(bits >> (8 * i));
}

float loadFloat(const unsigned char* in) {
  std::uint32_t bits = 0;
  for (int i = 0; i < 4; ++i) bits |= std::uint32_t(in[i]) << (8 * i);
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

void encode(SurfelRecord surfel, unsigned char* out) {
  for (float* field : floatFields(surfel)) {
    storeFloat(*field, out);
    out += 4;
  }
  std::copy(surfel.color.begin(), surfel.color.end(), out);
}

// A record of `floatCount` float properties (older versions lack the last ones: they keep
// their defaults).
SurfelRecord decode(const unsigned char* in, std::size_t floatCount) {
  SurfelRecord surfel;
  const std::array<float*, kFloatPropertyCount> fields = floatFields(surfel);
  for (std::size_t f = 0; f < floatCount; ++f) {
    *fields[f] = loadFloat(in);
    in += 4;
  }
  std::copy(in, in + kColorPropertyCount, surfel.color.begin());
  return surfel;
}

// The reason for refusing surfel `index` when one of its geometry floats is not finite, or an
// empty string when all are.
std::string nonFiniteGeometry(SurfelRecord surfel, std::size_t index) {
  const std::array<float*, kFloatPropertyCount> fields = floatFields(surfel);
  for (std::size_t f = 0; f < kGeometryFloatCount; ++f) {
    const float value = *fields[f];
    if (!std::isfinite(value))
      return "surfel " + std::to_string(index) + " has a non-finite " + kFloatPropertyNames[f] + " (" +
             (std::isnan(value) ? "nan" : value > 0 ? "inf" : "-inf") +
             "): positions, normals, radii and ellipse axes must be finite";
  }
  return std::string();
}

// Records are streamed through a buffer of this many, to keep memory flat on big files.
constexpr std::size_t kRecordsPerChunk = 4096;

// A garbage file without newlines must not be read whole as one "header line".
constexpr std::size_t kMaxHeaderBytes = 64 * 1024;

// One header line without its line break (PLY headers written on Windows end in "\r\n").
bool readHeaderLine(std::istream& in, std::size_t& headerBytes, std::string& line) {
  line.clear();
  for (int c = in.get(); c != std::char_traits<char>::eof(); c = in.get()) {
    if (++headerBytes > kMaxHeaderBytes) return false;
    if (c == '\n') {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      return true;
    }
    line.push_back(static_cast<char>(c));
  }
  return false;
}

std::vector<std::string> splitWords(const std::string& line) {
  std::istringstream words(line);
  std::vector<std::string> result;
  for (std::string word; words >> word;) result.push_back(word);
  return result;
}

// Everything after the first word, e.g. the text of a comment.
std::string afterKeyword(const std::string& line) {
  std::size_t start = line.find_first_not_of(" \t", line.find_first_of(" \t"));
  return start == std::string::npos ? std::string() : line.substr(start);
}

bool parseCount(const std::string& text, std::uint64_t& count) {
  if (text.empty() || text.size() > 19 ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return false;
  count = std::stoull(text);
  return true;
}

// PLY names each scalar type two ways.
bool isFloatType(const std::string& type) { return type == "float" || type == "float32"; }
bool isUcharType(const std::string& type) { return type == "uchar" || type == "uint8"; }

bool fail(std::string& error, const std::string& reason) {
  error = printableText(reason, kMaxReasonLength);
  return false;
}

// Fails with the reason for the first surfel whose geometry is not finite.
bool checkGeometry(const std::vector<SurfelRecord>& surfels, std::string& error) {
  for (std::size_t index = 0; index < surfels.size(); ++index) {
    const std::string reason = nonFiniteGeometry(surfels[index], index);
    if (!reason.empty()) return fail(error, reason);
  }
  return true;
}

// A header line or word quoted in a reason: short enough to leave room for the explanation.
std::string quoted(const std::string& text) { return "'" + printableText(text, 60) + "'"; }

// Checks the header against the layout of docs/surfel_format.md and returns the number of
// records it announces and their float properties (by version); the stream is left at the first
// data byte.
bool readHeader(std::istream& in, std::uint64_t& count, std::size_t& floatCount, std::string& error) {
  std::size_t headerBytes = 0;
  std::string line;
  if (!readHeaderLine(in, headerBytes, line) || line != "ply")
    return fail(error, "not a PLY file: it does not start with a 'ply' line");

  bool hasFormat = false, hasMagic = false, hasVertexElement = false;
  std::vector<std::string> properties; // checked once the version is known
  for (;;) {
    if (!readHeaderLine(in, headerBytes, line))
      return fail(error, "the PLY header has no 'end_header' line");
    const std::vector<std::string> words = splitWords(line);
    if (words.empty()) continue;
    const std::string& keyword = words[0];
    if (keyword == "end_header") break;
    if (keyword == "obj_info") continue;
    if (keyword == "comment") {
      const std::string text = afterKeyword(line);
      if (const Version* version = findVersion(text)) {
        if (hasMagic && version->floatCount != floatCount)
          return fail(error, "two different .surfel versions in the PLY header");
        hasMagic = true;
        floatCount = version->floatCount;
      } else if (text.compare(0, 18, "gaussphere-surfel ") == 0) {
        std::string known;
        for (const Version& v : kVersions) known += std::string(known.empty() ? "" : ", ") + "'" + v.magic + "'";
        return fail(error, "unsupported .surfel version " + quoted(text) + " (this reader reads " + known + ")");
      }
    } else if (keyword == "format") {
      if (words.size() != 3 || words[1] != "binary_little_endian" || words[2] != "1.0")
        return fail(error, "unsupported PLY encoding " + quoted(line) +
                               ": .surfel files are binary_little_endian 1.0");
      hasFormat = true;
    } else if (keyword == "element") {
      if (hasVertexElement || words.size() != 3 || words[1] != "vertex")
        return fail(error, "unexpected " + quoted(line) + ": a .surfel file has one vertex element");
      if (!parseCount(words[2], count))
        return fail(error, "invalid vertex count in " + quoted(line));
      hasVertexElement = true;
    } else if (keyword == "property") {
      if (!hasVertexElement || words.size() != 3)
        return fail(error, "unexpected " + quoted(line) + " (vertex property " +
                               std::to_string(properties.size() + 1) + " of the .surfel layout)");
      properties.push_back(line);
    } else {
      return fail(error, "unknown PLY header line " + quoted(line));
    }
  }
  if (!hasFormat) return fail(error, "the PLY header has no 'format' line");
  if (!hasMagic)
    return fail(error, std::string("not a .surfel file: no 'comment ") + kSurfelFileMagic +
                           "' in the PLY header");
  if (!hasVertexElement) return fail(error, "the PLY header has no vertex element");
  for (std::size_t index = 0; index < properties.size() && index < floatCount + kColorPropertyCount; ++index) {
    const std::vector<std::string> words = splitWords(properties[index]);
    const bool expected =
        index >= floatCount ? isUcharType(words[1]) && words[2] == kColorPropertyNames[index - floatCount]
                            : isFloatType(words[1]) && words[2] == kFloatPropertyNames[index];
    if (!expected)
      return fail(error, "unexpected " + quoted(properties[index]) + " (vertex property " +
                             std::to_string(index + 1) + " of the .surfel layout)");
  }
  if (properties.size() != floatCount + kColorPropertyCount)
    return fail(error, "the vertex element has " + std::to_string(properties.size()) +
                           " properties instead of " + std::to_string(floatCount + kColorPropertyCount));
  return true;
}

// Number of bytes from the current position to the end of a seekable stream.
bool remainingBytes(std::istream& in, std::uint64_t& bytes) {
  const std::istream::pos_type here = in.tellg();
  in.seekg(0, std::ios::end);
  const std::istream::pos_type end = in.tellg();
  in.seekg(here);
  if (here == std::istream::pos_type(-1) || end == std::istream::pos_type(-1) || !in)
    return false;
  bytes = static_cast<std::uint64_t>(end - here);
  return true;
}

}  // namespace

bool operator==(const SurfelRecord& a, const SurfelRecord& b) {
  return a.position == b.position && a.normal == b.normal && a.radius == b.radius &&
         a.majorAxis == b.majorAxis && a.minorAxis == b.minorAxis && a.quality == b.quality &&
         a.blendScale == b.blendScale && a.fitOffset == b.fitOffset && a.color == b.color;
}

namespace {

// The header, then a data section of exactly the announced records; `in` is left at the first.
bool readHeaderAndSize(std::istream& in, std::uint64_t& count, std::size_t& floatCount, std::string& error) {
  floatCount = kFloatPropertyCount;
  if (!readHeader(in, count, floatCount, error)) return false;
  const std::size_t bytesPerRecord = recordBytes(floatCount);
  // Checking the size first also keeps a corrupt count from allocating a huge vector.
  std::uint64_t dataBytes = 0;
  if (!remainingBytes(in, dataBytes)) return fail(error, "cannot determine the file size");
  if (count > dataBytes / bytesPerRecord)
    return fail(error, "truncated file: the header announces " + std::to_string(count) +
                           " surfels, the data holds " + std::to_string(dataBytes / bytesPerRecord));
  if (dataBytes != count * bytesPerRecord)
    return fail(error, std::to_string(dataBytes - count * bytesPerRecord) +
                           " unexpected bytes after the last surfel");
  return true;
}

}  // namespace

bool readSurfelCount(const std::string& path, std::uint64_t& count, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail(error, "cannot open " + quotedPath(path) + ": " + std::strerror(errno));
  std::size_t floatCount = 0;
  return readHeaderAndSize(in, count, floatCount, error);
}

bool readSurfels(std::istream& in, std::vector<SurfelRecord>& surfels, std::string& error) {
  surfels.clear();
  std::uint64_t count = 0;
  std::size_t floatCount = 0;
  if (!readHeaderAndSize(in, count, floatCount, error)) return false;
  const std::size_t bytesPerRecord = recordBytes(floatCount);

  surfels.reserve(count);
  std::vector<unsigned char> chunk(bytesPerRecord * std::min<std::uint64_t>(count, kRecordsPerChunk));
  while (surfels.size() < count) {
    const std::size_t records = std::min<std::uint64_t>(count - surfels.size(), kRecordsPerChunk);
    if (!in.read(reinterpret_cast<char*>(chunk.data()), records * bytesPerRecord)) {
      fail(error, "read error after " + std::to_string(surfels.size()) + " surfels");
      surfels.clear();
      return false;
    }
    for (std::size_t r = 0; r < records; ++r) {
      surfels.push_back(decode(&chunk[r * bytesPerRecord], floatCount));
      const std::string reason = nonFiniteGeometry(surfels.back(), surfels.size() - 1);
      if (!reason.empty()) {
        surfels.clear();
        return fail(error, reason);
      }
    }
  }
  return true;
}

bool readSurfelFile(const std::string& path, std::vector<SurfelRecord>& surfels, std::string& error) {
  surfels.clear();
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail(error, "cannot open " + quotedPath(path) + ": " + std::strerror(errno));
  return readSurfels(in, surfels, error);
}

void writeSurfelHeader(std::ostream& out, std::uint64_t count) {
  out << "ply\nformat binary_little_endian 1.0\ncomment " << kSurfelFileMagic << "\n"
      << "element vertex " << count << "\n";
  for (const char* name : kFloatPropertyNames) out << "property float " << name << "\n";
  for (const char* name : kColorPropertyNames) out << "property uchar " << name << "\n";
  out << "end_header\n";
}

bool writeSurfelRecords(std::ostream& out, const std::vector<SurfelRecord>& surfels, std::string& error) {
  if (!checkGeometry(surfels, error)) return false;
  const std::size_t bytesPerRecord = recordBytes(kFloatPropertyCount);
  std::vector<unsigned char> chunk(bytesPerRecord * kRecordsPerChunk);
  for (std::size_t first = 0; first < surfels.size() && out; first += kRecordsPerChunk) {
    const std::size_t records = std::min(surfels.size() - first, kRecordsPerChunk);
    for (std::size_t r = 0; r < records; ++r) encode(surfels[first + r], &chunk[r * bytesPerRecord]);
    out.write(reinterpret_cast<const char*>(chunk.data()), records * bytesPerRecord);
  }
  if (!out.flush()) return fail(error, "write error");
  return true;
}

bool writeSurfels(std::ostream& out, const std::vector<SurfelRecord>& surfels, std::string& error) {
  if (!checkGeometry(surfels, error)) return false;
  writeSurfelHeader(out, surfels.size());
  return writeSurfelRecords(out, surfels, error);
}

bool writeSurfelFile(const std::string& path, const std::vector<SurfelRecord>& surfels,
                     std::string& error) {
  if (!checkGeometry(surfels, error)) return false;
  FileReplacement replacement;
  return replacement.open(path, error) &&
         replacement.write([&](std::ostream& out, std::string& reason) { return writeSurfels(out, surfels, reason); },
                           error);
}

bool hasBlendScales(const std::vector<SurfelRecord>& surfels) {
  return std::any_of(surfels.begin(), surfels.end(), [](const SurfelRecord& s) { return s.blendScale != 1; });
}

bool hasFitOffsets(const std::vector<SurfelRecord>& surfels) {
  return std::any_of(surfels.begin(), surfels.end(), [](const SurfelRecord& s) { return s.fitOffset != 0; });
}

bool hasEllipseFrames(const std::vector<SurfelRecord>& surfels) {
  const auto isZero = [](const Vec3f& v) { return v[0] == 0 && v[1] == 0 && v[2] == 0; };
  return std::any_of(surfels.begin(), surfels.end(), [&](const SurfelRecord& s) {
    return !isZero(s.majorAxis) || !isZero(s.minorAxis);
  });
}

}  // namespace surfel_io
