// The .surfel reader and writer: exact round trips, the documented header, and refusal
// (false and a reason, never a crash) of every truncated, foreign or garbage input.
#include "part_files.h"
#include "surfel_fixture.h"

#include <surfel_file.h>

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

namespace {

using surfel_io::SurfelRecord;

const char* const kHeader =
    "ply\n"
    "format binary_little_endian 1.0\n"
    "comment gaussphere-surfel 3\n"
    "element vertex 3\n"
    "property float x\nproperty float y\nproperty float z\n"
    "property float nx\nproperty float ny\nproperty float nz\n"
    "property float radius\n"
    "property float major_x\nproperty float major_y\nproperty float major_z\n"
    "property float minor_x\nproperty float minor_y\nproperty float minor_z\n"
    "property float quality\n"
    "property float blend_scale\n"
    "property float fit_offset\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n"
    "end_header\n";

std::string encode(const std::vector<SurfelRecord>& surfels) {
  std::ostringstream out;
  std::string error;
  EXPECT_TRUE(surfel_io::writeSurfels(out, surfels, error)) << error;
  return out.str();
}

bool decode(const std::string& bytes, std::vector<SurfelRecord>& surfels, std::string& error) {
  std::istringstream in(bytes);
  return surfel_io::readSurfels(in, surfels, error);
}

// The bytes of a valid three-surfel file with `from` replaced by `to` in its header.
std::string withHeaderEdit(const std::string& from, const std::string& to) {
  std::string bytes = encode(syntheticSurfels(3));
  const std::size_t at = bytes.find(from);
  EXPECT_LT(at, std::string(kHeader).size()) << from;
  return bytes.replace(at, from.size(), to);
}

// `surfels` (fewer than 10) as a file of an older version: without fit_offset (version 2),
// and without blend_scale too (version 1).
std::string olderVersionBytes(const std::vector<SurfelRecord>& surfels, int version) {
  const std::string current = encode(surfels);
  const std::size_t headerSize = std::string(kHeader).size();
  std::string bytes = current.substr(0, headerSize);
  bytes.replace(bytes.find("gaussphere-surfel 3"), 19, "gaussphere-surfel " + std::to_string(version));
  const char* const newestFloats[] = {"fit_offset", "blend_scale"};
  const std::size_t droppedFloats = 3 - version;
  for (std::size_t f = 0; f < droppedFloats; ++f) {
    const std::string line = std::string("property float ") + newestFloats[f] + "\n";
    bytes.erase(bytes.find(line), line.size());
  }
  for (std::size_t r = 0; r < surfels.size(); ++r) {
    const std::string record = current.substr(headerSize + r * 68, 68);
    bytes += record.substr(0, 64 - 4 * droppedFloats) + record.substr(64, 4);  // floats, colour
  }
  return bytes;
}

// True when `reason` is what the reader and writer promise: one line of at most
// kMaxReasonLength printable ASCII characters.
bool isShortPrintableLine(const std::string& reason) {
  return !reason.empty() && reason.size() <= surfel_io::kMaxReasonLength &&
         std::all_of(reason.begin(), reason.end(), [](char c) { return c >= 0x20 && c <= 0x7e; });
}

// Expects `bytes` to be refused with a reason containing `reason`.
void expectRefused(const std::string& bytes, const std::string& reason) {
  std::vector<SurfelRecord> surfels(1);
  std::string error;
  EXPECT_FALSE(decode(bytes, surfels, error));
  EXPECT_NE(error.find(reason), std::string::npos) << "error: " << error;
  EXPECT_TRUE(isShortPrintableLine(error)) << "error: " << error;
  EXPECT_TRUE(surfels.empty());
}

// The bytes of syntheticSurfels(count) with float property `property` (0 = x, ..., 15 =
// fit_offset) of record `record` set to `value`, which the writer may refuse to write.
std::string withFloat(std::size_t count, std::size_t record, std::size_t property, float value) {
  std::string bytes = encode(syntheticSurfels(count));
  const std::size_t at = bytes.find("end_header\n") + 11 + record * 68 + property * 4;
  std::memcpy(&bytes[at], &value, 4);  // the tests run on little-endian hosts, like the files
  return bytes;
}

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();
const char* const kGeometryProperties[] = {"x", "y", "z", "nx", "ny", "nz", "radius",
                                           "major_x", "major_y", "major_z",
                                           "minor_x", "minor_y", "minor_z"};

TEST(SurfelFile, WritesTheDocumentedHeaderAnd68BytesPerSurfel) {
  const std::string bytes = encode(syntheticSurfels(3));
  ASSERT_EQ(bytes.substr(0, std::string(kHeader).size()), kHeader);
  EXPECT_EQ(bytes.size(), std::string(kHeader).size() + 3 * 68);
}

// Version 2 files (no fit_offset, 64 bytes per surfel) read with a fit offset of 0.
TEST(SurfelFile, ReadsVersion2Files) {
  std::vector<SurfelRecord> expected = syntheticSurfels(4);  // the second and third are fitted
  const std::string v2 = olderVersionBytes(expected, 2);
  const std::size_t headerSize = v2.find("end_header\n") + 11;
  ASSERT_NE(v2.find("comment gaussphere-surfel 2\n"), std::string::npos);
  ASSERT_NE(v2.find("property float blend_scale\nproperty uchar red\n"), std::string::npos);
  ASSERT_EQ(v2.size(), headerSize + 4 * 64);
  std::vector<SurfelRecord> surfels;
  std::string error;
  ASSERT_TRUE(decode(v2, surfels, error)) << error;
  ASSERT_TRUE(surfel_io::hasFitOffsets(expected));
  for (SurfelRecord& s : expected) s.fitOffset = 0;
  EXPECT_EQ(surfels, expected);
  EXPECT_TRUE(surfel_io::hasBlendScales(surfels));
  EXPECT_FALSE(surfel_io::hasFitOffsets(surfels));
  expectRefused(v2 + std::string(4, '\0'), "4 unexpected bytes after the last surfel");
}

// Version 1 files (no blend_scale, 60 bytes per surfel) read with a blend scale of 1.
TEST(SurfelFile, ReadsVersion1Files) {
  std::vector<SurfelRecord> expected = syntheticSurfels(4);  // the fourth has a blend scale of 1/4
  const std::string v1 = olderVersionBytes(expected, 1);
  ASSERT_NE(v1.find("comment gaussphere-surfel 1\n"), std::string::npos);
  ASSERT_NE(v1.find("property float quality\nproperty uchar red\n"), std::string::npos);
  ASSERT_EQ(v1.size(), v1.find("end_header\n") + 11 + 4 * 60);
  std::vector<SurfelRecord> surfels;
  std::string error;
  ASSERT_TRUE(decode(v1, surfels, error)) << error;
  ASSERT_TRUE(surfel_io::hasBlendScales(expected));
  for (SurfelRecord& s : expected) {
    s.blendScale = 1;
    s.fitOffset = 0;
  }
  EXPECT_EQ(surfels, expected);
  EXPECT_FALSE(surfel_io::hasBlendScales(surfels));
  expectRefused(v1 + std::string(4, '\0'), "4 unexpected bytes after the last surfel");
}

TEST(SurfelFile, StoresLittleEndianFloatsAndBytesInPropertyOrder) {
  SurfelRecord s;
  s.position = {{1.0f, 0, 0}};
  s.fitOffset = -2.0f;
  s.color = {{1, 2, 3, 4}};
  const std::string bytes = encode({s});
  const std::string data = bytes.substr(bytes.size() - 68);
  EXPECT_EQ(data.substr(0, 4), std::string("\x00\x00\x80\x3f", 4));  // 1.0f
  EXPECT_EQ(data.substr(56, 4), std::string("\x00\x00\x80\x3f", 4));  // blend scale 1.0f
  EXPECT_EQ(data.substr(60, 4), std::string("\x00\x00\x00\xc0", 4));  // fit offset -2.0f
  EXPECT_EQ(data.substr(64), std::string("\x01\x02\x03\x04", 4));
}

TEST(SurfelFile, RoundTripThroughAFileIsBitExact) {
  std::vector<SurfelRecord> surfels = syntheticSurfels(5000);  // more than one chunk
  SurfelRecord extremes;
  extremes.position = {{-0.0f, FLT_MAX, -FLT_MAX}};
  extremes.normal = {{FLT_MIN / 4, FLT_EPSILON, std::nextafter(1.0f, 2.0f)}};
  extremes.radius = FLT_MIN;
  extremes.quality = 16777216.0f;
  extremes.fitOffset = -FLT_MIN / 2;
  extremes.color = {{0, 255, 128, 0}};
  surfels.push_back(extremes);
  ASSERT_TRUE(surfel_io::hasFitOffsets(surfels));

  const std::string path = testing::TempDir() + "surfel_file_roundtrip.surfel";
  std::string error;
  ASSERT_TRUE(surfel_io::writeSurfelFile(path, surfels, error)) << error;
  std::vector<SurfelRecord> read;
  ASSERT_TRUE(surfel_io::readSurfelFile(path, read, error)) << error;
  EXPECT_EQ(read, surfels);
  EXPECT_EQ(encode(read), encode(surfels));  // also tells -0 from +0
}

TEST(SurfelFile, FileWithoutSurfelsReadsAsEmpty) {
  std::vector<SurfelRecord> surfels(2);
  std::string error;
  ASSERT_TRUE(decode(encode({}), surfels, error)) << error;
  EXPECT_TRUE(surfels.empty());
}

TEST(SurfelFile, RefusesEveryTruncation) {
  const std::string bytes = encode(syntheticSurfels(3));
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    SCOPED_TRACE("first " + std::to_string(size) + " bytes");
    std::vector<SurfelRecord> surfels;
    std::string error;
    EXPECT_FALSE(decode(bytes.substr(0, size), surfels, error));
    EXPECT_FALSE(error.empty());
    EXPECT_TRUE(surfels.empty());
  }
  expectRefused(bytes.substr(0, bytes.size() - 1), "truncated file");
}

TEST(SurfelFile, RefusesDataAfterTheLastSurfel) {
  expectRefused(encode(syntheticSurfels(3)) + "\n", "1 unexpected bytes after the last surfel");
}

TEST(SurfelFile, RefusesGarbage) {
  expectRefused("", "not a PLY file");
  expectRefused(std::string(5000, '\xaa'), "not a PLY file");
  expectRefused("ply\n" + std::string(100000, '\xaa'), "no 'end_header'");
  expectRefused("solid cube\nfacet normal 0 0 1\n", "not a PLY file");
}

TEST(SurfelFile, RefusesHeadersOtherThanTheSurfelLayout) {
  expectRefused(withHeaderEdit("binary_little_endian", "ascii"), "unsupported PLY encoding");
  expectRefused(withHeaderEdit("binary_little_endian", "binary_big_endian"),
                "unsupported PLY encoding");
  expectRefused(withHeaderEdit("format binary_little_endian 1.0\n", ""), "no 'format' line");
  expectRefused(withHeaderEdit("comment gaussphere-surfel 3\n", ""), "not a .surfel file");
  expectRefused(withHeaderEdit("gaussphere-surfel 3", "gaussphere-surfel 4"),
                "unsupported .surfel version");
  // An older version's comment on version 3 data: the layout does not match the version.
  expectRefused(withHeaderEdit("gaussphere-surfel 3", "gaussphere-surfel 2"),
                "unexpected 'property float fit_offset' (vertex property 16");
  expectRefused(withHeaderEdit("gaussphere-surfel 3", "gaussphere-surfel 1"),
                "unexpected 'property float blend_scale' (vertex property 15");
  expectRefused(withHeaderEdit("comment gaussphere-surfel 3\n",
                               "comment gaussphere-surfel 3\ncomment gaussphere-surfel 2\n"),
                "two different .surfel versions");
  expectRefused(withHeaderEdit("end_header", "element face 0\nend_header"),
                "unexpected 'element face 0'");
  expectRefused(withHeaderEdit("element vertex 3\n", ""), "unexpected 'property float x'");
  expectRefused(withHeaderEdit("vertex 3", "vertex three"), "invalid vertex count");
  expectRefused(withHeaderEdit("vertex 3", "vertex -3"), "invalid vertex count");
  expectRefused(withHeaderEdit("float x", "double x"), "unexpected 'property double x'");
  expectRefused(withHeaderEdit("property float y\nproperty float z",
                               "property float z\nproperty float y"),
                "unexpected 'property float z' (vertex property 2");
  expectRefused(withHeaderEdit("uchar alpha", "list uchar int vertex_indices"),
                "unexpected 'property list");
  expectRefused(withHeaderEdit("property uchar alpha\n", ""), "has 19 properties instead of 20");
  expectRefused(withHeaderEdit("end_header", "property uchar extra\nend_header"),
                "has 21 properties instead of 20");
  expectRefused(withHeaderEdit("end_header", "made_up keyword\nend_header"),
                "unknown PLY header line");
}

TEST(SurfelFile, RefusesACountTheDataCannotHoldWithoutAllocatingIt) {
  expectRefused(withHeaderEdit("vertex 3", "vertex 9999999999999999999"), "truncated file");
  expectRefused(withHeaderEdit("vertex 3", "vertex 18446744073709551616"),
                "invalid vertex count");
}

TEST(SurfelFile, AcceptsWhatOtherPlyWritersAdd) {
  std::string bytes = withHeaderEdit("comment gaussphere-surfel 3\n",
                                     "obj_info from a tool\ncomment gaussphere-surfel 3\n"
                                     "comment another comment\n");
  bytes.replace(bytes.find("float x"), 7, "float32 x");
  bytes.replace(bytes.find("uchar red"), 9, "uint8 red");
  const std::size_t headerEnd = bytes.find("end_header\n") + 11;
  std::string crlf;
  for (char c : bytes.substr(0, headerEnd)) crlf += c == '\n' ? "\r\n" : std::string(1, c);
  std::vector<SurfelRecord> surfels;
  std::string error;
  ASSERT_TRUE(decode(crlf + bytes.substr(headerEnd), surfels, error)) << error;
  EXPECT_EQ(surfels, syntheticSurfels(3));
}

TEST(SurfelFile, ReportsFilesThatCannotBeOpened) {
  std::vector<SurfelRecord> surfels;
  std::string error;
  EXPECT_FALSE(surfel_io::readSurfelFile("/nonexistent/in.surfel", surfels, error));
  EXPECT_NE(error.find("cannot open '/nonexistent/in.surfel'"), std::string::npos) << error;
  EXPECT_FALSE(surfel_io::writeSurfelFile("/nonexistent/out.surfel", surfels, error));
  EXPECT_NE(error.find("cannot write '/nonexistent/out.surfel': No such file or directory"), std::string::npos)
      << error;
}

TEST(SurfelFile, FailedSaveLeavesNoPartialFile) {
  const std::string directory = testing::TempDir() + "surfel_file_not_a_file";
  ::mkdir(directory.c_str(), 0700);  // a path a file cannot replace
  std::string error;
  EXPECT_FALSE(surfel_io::writeSurfelFile(directory, syntheticSurfels(3), error));
  EXPECT_NE(error.find("cannot write '" + directory + "': it is a folder"), std::string::npos) << error;
  EXPECT_EQ(partFilesBeside(directory), 0);
}

TEST(SurfelFile, EllipseFramesAreAnyNonZeroAxis) {
  std::vector<SurfelRecord> surfels(3);
  EXPECT_FALSE(surfel_io::hasEllipseFrames(surfels));
  surfels[2].minorAxis[1] = 1e-30f;
  EXPECT_TRUE(surfel_io::hasEllipseFrames(surfels));
  EXPECT_TRUE(surfel_io::hasEllipseFrames(syntheticSurfels(1)));
}

TEST(SurfelFile, FitOffsetsAreAnyNonZeroOffsetAndPartOfTheRecord) {
  std::vector<SurfelRecord> surfels(3);
  EXPECT_FALSE(surfel_io::hasFitOffsets(surfels));
  surfels[2].fitOffset = -1e-30f;
  EXPECT_TRUE(surfel_io::hasFitOffsets(surfels));
  EXPECT_NE(surfels[2], surfels[1]);
  EXPECT_TRUE(surfel_io::hasFitOffsets(syntheticSurfels(2)));
}

// A reason never echoes the 64 KB a header line may hold, nor its control or non-ASCII bytes.
TEST(SurfelFile, ReasonsQuoteAtMostAShortPrintableExcerptOfTheFile) {
  const std::string longLine = "\x1b[2J\r\xff" + std::string(60000, 'A');
  expectRefused(withHeaderEdit("binary_little_endian", longLine), "unsupported PLY encoding 'format \\x1b[2J\\x0d\\xffAAA");
  expectRefused(withHeaderEdit("end_header", longLine + "\nend_header"), "unknown PLY header line '\\x1b[2J");
  expectRefused(withHeaderEdit("gaussphere-surfel 3", "gaussphere-surfel " + longLine),
                "unsupported .surfel version 'gaussphere-surfel \\x1b[2J");
  expectRefused(withHeaderEdit("vertex 3", "vertex 3" + std::string(60000, '7')),
                "invalid vertex count in 'element vertex 37777");
  expectRefused(withHeaderEdit("vertex 3", "vertex 3 " + longLine), "a .surfel file has one vertex element");
  expectRefused(withHeaderEdit("property float y", "property float" + longLine),
                "unexpected 'property float\\x1b[2J");
  expectRefused(withHeaderEdit("property float y", "property float " + longLine), "(vertex property 2 of");

  std::vector<SurfelRecord> surfels;
  std::string error;
  const std::string path = "/nonexistent/" + std::string(3000, 'x') + "\n.surfel";
  EXPECT_FALSE(surfel_io::readSurfelFile(path, surfels, error));
  EXPECT_TRUE(isShortPrintableLine(error)) << error;
  EXPECT_EQ(error.rfind("cannot open '...xxx", 0), 0u) << error;  // the end of the path is kept
  EXPECT_NE(error.find("xxx\\x0a.surfel': "), std::string::npos) << error;
  EXPECT_FALSE(surfel_io::writeSurfelFile(path, syntheticSurfels(1), error));
  EXPECT_TRUE(isShortPrintableLine(error)) << error;
  EXPECT_NE(error.find("xxx\\x0a.surfel': No such file"), std::string::npos) << error;
}

TEST(SurfelFile, PrintableTextEscapesAndCutsWholeEscapes) {
  using surfel_io::printableText;
  EXPECT_EQ(printableText("a\tb\\c\xe9", 100), "a\\x09b\\c\\xe9");
  EXPECT_EQ(printableText(printableText("a\tb", 100), 100), "a\\x09b");
  EXPECT_EQ(printableText("0123456789", 10), "0123456789");
  EXPECT_EQ(printableText("0123456789A", 10), "0123456...");
  EXPECT_EQ(printableText("0123456789A", 10, true), "...456789A");
  EXPECT_EQ(printableText("012345\n789", 10), "012345...");  // "\x0a" does not fit whole
  EXPECT_EQ(printableText("0123\n56789", 10, true), "...56789");
  EXPECT_EQ(printableText(std::string(1000, '\0'), 3), "\\x00...");  // 8 at least, whole escapes
}

// Positions, normals, radii and axes must be finite: the reader names the first record and
// property that are not.
TEST(SurfelFile, RefusesNonFiniteGeometryNamingTheFirstRecordAndProperty) {
  for (std::size_t property = 0; property < 13; ++property) {
    SCOPED_TRACE(kGeometryProperties[property]);
    for (float value : {kNaN, kInf, -kInf}) {
      const std::string name = kGeometryProperties[property];
      const char* const text = std::isnan(value) ? "nan" : value > 0 ? "inf" : "-inf";
      expectRefused(withFloat(5, 3, property, value), "surfel 3 has a non-finite " + name + " (" + text + ")");
    }
  }
  std::string bytes = withFloat(5000, 4500, 2, kNaN);  // in the second chunk of records
  const std::size_t at = bytes.find("end_header\n") + 11 + 4097 * 68 + 5 * 4;  // nz of 4097
  std::memcpy(&bytes[at], &kInf, 4);
  expectRefused(bytes, "surfel 4097 has a non-finite nz (inf)");
}

// Quality, blend scale and fit offset have a reading of any value (docs/surfel_format.md):
// they are kept as they are, bit for bit.
TEST(SurfelFile, KeepsNonFiniteQualityBlendScaleAndFitOffset) {
  std::vector<SurfelRecord> surfels = syntheticSurfels(3);
  surfels[0].quality = kNaN;
  surfels[1].blendScale = kInf;
  surfels[2].fitOffset = -kNaN;
  const std::string bytes = encode(surfels);
  std::vector<SurfelRecord> read;
  std::string error;
  ASSERT_TRUE(decode(bytes, read, error)) << error;
  EXPECT_EQ(encode(read), bytes);
}

// The writer refuses what the reader would, before writing a byte or touching the file.
TEST(SurfelFile, WriterRefusesNonFiniteGeometryAndKeepsThePreviousFile) {
  std::vector<SurfelRecord> surfels = syntheticSurfels(4);
  surfels[3].position[0] = kNaN;
  surfels[2].minorAxis[1] = -kInf;
  std::ostringstream out;
  std::string error;
  EXPECT_FALSE(surfel_io::writeSurfels(out, surfels, error));
  EXPECT_NE(error.find("surfel 2 has a non-finite minor_y (-inf)"), std::string::npos) << error;
  EXPECT_TRUE(isShortPrintableLine(error)) << error;
  EXPECT_TRUE(out.str().empty());

  const std::string path = testing::TempDir() + "surfel_file_non_finite.surfel";
  const std::string previous = encode(syntheticSurfels(2));
  std::ofstream(path, std::ios::binary) << previous;
  EXPECT_FALSE(surfel_io::writeSurfelFile(path, surfels, error));
  EXPECT_NE(error.find("surfel 2 has a non-finite minor_y"), std::string::npos) << error;
  std::ifstream in(path, std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), previous);
  EXPECT_EQ(partFilesBeside(path), 0);
}

// The bytes of a file whose storage fails after the first block of records is read.
class FailingAfterFirstBlock : public std::stringbuf {
 public:
  using std::stringbuf::stringbuf;

 protected:
  std::streamsize xsgetn(char* s, std::streamsize n) override {
    return blockReads_++ == 0 ? std::stringbuf::xsgetn(s, n) : 0;
  }

 private:
  int blockReads_ = 0;  // the header is read byte by byte, the records in blocks
};

TEST(SurfelFile, ReportsHowFarAReadGotBeforeItFailed) {
  FailingAfterFirstBlock bytes(encode(syntheticSurfels(5000)), std::ios::in);
  std::istream in(&bytes);
  std::vector<SurfelRecord> surfels;
  std::string error;
  EXPECT_FALSE(surfel_io::readSurfels(in, surfels, error));
  EXPECT_EQ(error, "read error after 4096 surfels");
  EXPECT_TRUE(surfels.empty());
}

}  // namespace
