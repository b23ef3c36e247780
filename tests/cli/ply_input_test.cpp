// Reading oriented point sets from hostile and valid PLY files (tools/gsresample/ply_input.h).
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <tools/gsresample/ply_input.h>

using vcg::gaussphere::OrientedPointMesh;

namespace {

const char kPointProperties[] = "property float x\nproperty float y\nproperty float z\n"
                                "property float nx\nproperty float ny\nproperty float nz\n";

std::string Header(const std::string &format, const std::string &vertexCount, const std::string &extra = "")
{
    return "ply\nformat " + format + " 1.0\nelement vertex " + vertexCount + "\n" + kPointProperties + extra +
           "end_header\n";
}

std::string AsciiRows(int count)
{
    std::string rows;
    for (int i = 0; i < count; ++i) rows += std::to_string(i) + " " + std::to_string(2 * i) + " 0.5 0 0 1\n";
    return rows;
}

class PlyInput : public ::testing::Test
{
protected:
    /// Writes `bytes` to a file of the test's own and returns its path.
    std::string Write(const std::string &bytes)
    {
        const std::string path = ::testing::TempDir() + "gsresample_ply_input_" + std::to_string(::getpid()) + "_" +
                                 std::to_string(files_.size()) + ".ply";
        std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
        files_.push_back(path);
        return path;
    }
    void TearDown() override
    {
        for (const std::string &path : files_) std::remove(path.c_str());
    }

    /// The file is refused with a reason holding `reason`, on one short printable line.
    void ExpectRefused(const std::string &bytes, const std::string &reason)
    {
        OrientedPointMesh mesh;
        std::string error;
        EXPECT_FALSE(gsresample::ReadOrientedPoints(Write(bytes), mesh, error));
        EXPECT_NE(error.find(reason), std::string::npos) << "error: " << error;
        EXPECT_LE(error.size(), 200u) << error;
        for (char c : error) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << "non-printable in: " << error;
    }

    /// The file is read, with `vertices` points.
    void ExpectRead(const std::string &bytes, int vertices)
    {
        OrientedPointMesh mesh;
        std::string error;
        ASSERT_TRUE(gsresample::ReadOrientedPoints(Write(bytes), mesh, error)) << error;
        EXPECT_EQ(mesh.vn, vertices);
    }

    std::vector<std::string> files_;
};

void AppendFloat(std::string &out, float value, bool bigEndian)
{
    unsigned char bytes[4];
    std::memcpy(bytes, &value, 4);
    if (bigEndian) std::swap(bytes[0], bytes[3]), std::swap(bytes[1], bytes[2]);
    out.append(reinterpret_cast<const char *>(bytes), 4);
}

} // namespace

TEST_F(PlyInput, NegativeCountIsRefused)
{
    ExpectRefused(Header("ascii", "-1") + AsciiRows(3), "count of element 'vertex' is not a non-negative integer: '-1'");
    ExpectRefused(Header("binary_little_endian", "-5"), "not a non-negative integer");
}

TEST_F(PlyInput, CountsBeyondIntAreRefused)
{
    ExpectRefused(Header("ascii", "4294967295") + AsciiRows(3), "exceeds 2147483647");
    ExpectRefused(Header("binary_little_endian", "99999999999999999999999"), "exceeds 2147483647");
}

TEST_F(PlyInput, CountsLargerThanTheFileAreRefused)
{
    ExpectRefused(Header("binary_little_endian", "2147483647") + std::string(240, '\0'),
                  "2147483647 vertex record(s) of at least 24 bytes, but only 240 bytes follow");
    ExpectRefused(Header("binary_big_endian", "11") + std::string(240, '\0'), "only 240 bytes follow");
    ExpectRefused(Header("ascii", "2147483647") + AsciiRows(3), "but only");
    ExpectRefused(Header("ascii", "1000") + AsciiRows(3), "1000 vertex record(s)");
    // The faces after the vertices count too.
    ExpectRefused(Header("binary_little_endian", "2", "element face 1000000\nproperty list uchar int vertex_indices\n") +
                      std::string(48 + 100, '\0'),
                  "1000000 face record(s)");
    // A face takes at least its count and three corners, in ASCII "3 0 1 2".
    ExpectRefused(Header("ascii", "3", "element face 20\nproperty list uchar int vertex_indices\n") + AsciiRows(3) +
                      std::string(40, '0'),
                  "20 face record(s) of at least 8 bytes");
    ExpectRefused(Header("binary_little_endian", "2", "element face 10\nproperty list uchar int vertex_indices\n") +
                      std::string(48 + 129, '\0'),
                  "10 face record(s) of at least 13 bytes");
}

TEST_F(PlyInput, ListPropertyOnVerticesIsRefused)
{
    std::string body;
    const int32_t longList = 100000;
    for (int v = 0; v < 3; ++v) {
        body += std::string(24, '\0');
        body.append(reinterpret_cast<const char *>(&longList), 4);
        body += std::string(4 * longList, '\0');
    }
    ExpectRefused(Header("binary_little_endian", "3", "property list int float junk\n") + body,
                  "the vertex element has a list property 'junk'");
}

TEST_F(PlyInput, FaceListsVcglibCannotHoldAreRefused)
{
    ExpectRefused(Header("ascii", "3", "element face 1\nproperty list int int vertex_indices\n") + AsciiRows(3) + "3 0 1 2\n",
                  "face list 'vertex_indices' counted by 'int'");
    ExpectRefused(Header("ascii", "3", "element face 1\nproperty list uchar int vertex_indices\nproperty list uchar float color\n") +
                      AsciiRows(3) + "3 0 1 2 0\n",
                  "face list property 'color' is not supported");
    ExpectRefused(Header("ascii", "3", "element tristrips 1\nproperty list int int vertex_indices\n") + AsciiRows(3) + "3 0 1 2\n",
                  "element 'tristrips' is not supported");
}

TEST_F(PlyInput, ListsVcglibSkipsThroughAFixedBufferAreRefusedInBinaryFiles)
{
    // vcglib skips an unread binary list through 512 bytes, its count read as one byte: 185 ints
    // would be written past that buffer.
    const std::string vertices(3 * 24, '\0');
    const std::string longList = std::string(1, char(185)) + std::string(740, 'A');
    ExpectRefused(Header("binary_little_endian", "3", "element extra 1\nproperty list uchar int data\n") + vertices + longList,
                  "list property 'data' of element 'extra' ('uchar' counts, 'int' items) is not supported in binary files");
    ExpectRefused(Header("binary_little_endian", "3", "element face 0\nproperty list uint uchar tags\n") + vertices,
                  "list property 'tags' of element 'face' ('uint' counts, 'uchar' items)");
}

TEST_F(PlyInput, CornerListsVcglibDoesNotReadAreCheckedAsSkippedOnes)
{
    const std::string vertices(3 * 24, '\0');
    // vcglib reads no float corners: it skips them through its 512 bytes (255 floats: 1020).
    ExpectRefused(Header("binary_little_endian", "3", "element face 1\nproperty list uchar float vertex_indices\n") +
                      vertices + std::string(1, char(255)) + std::string(1020, '\0'),
                  "list property 'vertex_indices' of element 'face' ('uchar' counts, 'float' items)");
    // Of two corner lists vcglib reads one and skips the other.
    ExpectRefused(Header("binary_little_endian", "3",
                         "element face 0\nproperty list uchar int vertex_indices\nproperty list uchar int vertex_index\n") +
                      vertices,
                  "declares both 'vertex_indices' and 'vertex_index'");
}

TEST_F(PlyInput, AsciiFacesOfMoreCornersThanVcglibHoldsAreRefused)
{
    // In ASCII vcglib reads a list's count as an int, whatever its declared type: the count
    // must be in its type's range.
    std::string face = "600";
    for (int i = 0; i < 600; ++i) face += " 0";
    ExpectRefused(Header("ascii", "3", "element face 1\nproperty list uchar int vertex_indices\n") + AsciiRows(3) + face + "\n",
                  "line 16 (face 0), property vertex_indices, list count: '600' is out of range for uchar (0 to 255)");
    // fscanf would read "3000-1" as the count 3000, then -1.
    std::string glued = "3000-1";
    for (int i = 0; i < 2999; ++i) glued += " 0";
    ExpectRefused(Header("ascii", "3", "element face 1\nproperty list uchar int vertex_indices\n") + AsciiRows(3) + glued + "\n",
                  "line 16 (face 0), property vertex_indices, list count: '3000-1' is not an integer");
    ExpectRead(Header("ascii", "3", "element face 1\nproperty list uchar int vertex_indices\n") + AsciiRows(3) + "3 0 1 2\n", 3);
}

TEST_F(PlyInput, FaceCornersThatAreNoVertexAreRefused)
{
    // vcglib indexes its vertices with the corners unchecked.
    ExpectRefused(Header("ascii", "3", "element face 1\nproperty list uchar int vertex_indices\n") + AsciiRows(3) +
                      "4 0 1 2 100000000\n",
                  "line 16 (face 0), property vertex_indices, item 3: names vertex 100000000 of 3");
    std::string binary(3 * 24, '\0');
    const std::int32_t corners[3] = {0, 1, -5};
    binary += std::string(1, char(3));
    binary.append(reinterpret_cast<const char *>(corners), sizeof corners);
    ExpectRefused(Header("binary_little_endian", "3", "element face 1\nproperty list uchar int vertex_indices\n") + binary,
                  "face record 0 names vertex -5 of 3");
}

TEST_F(PlyInput, FacesOfFewerThanThreeCornersAreRefused)
{
    // vcglib would make a triangle of them, its missing corners unset (valgrind: uninitialised
    // values indexing the vertices).
    const std::string faces = "element face 2\nproperty list uchar int vertex_indices\n";
    ExpectRefused(Header("ascii", "3", faces) + AsciiRows(3) + "3 0 1 2\n2 0 1\n",
                  "line 17 (face 1), property vertex_indices: 2 corner(s); a face needs at least 3");
    ExpectRefused(Header("ascii", "3", faces) + AsciiRows(3) + "0\n3 0 1 2\n",
                  "line 16 (face 0), property vertex_indices: 0 corner(s); a face needs at least 3");
    // A polygon of 10 corners first, so that the body is as long as two triangles take.
    std::string binary(3 * 24, '\0');
    const std::int32_t corners[10] = {0, 1, 2, 0, 1, 2, 0, 1, 2, 0};
    binary += std::string(1, char(10));
    binary.append(reinterpret_cast<const char *>(corners), sizeof corners);
    binary += std::string(1, char(1));
    binary.append(reinterpret_cast<const char *>(corners), sizeof(std::int32_t));
    ExpectRefused(Header("binary_little_endian", "3", faces) + binary, "face record 1 has 1 corner(s); a face needs at least 3");
    // Polygons are read, as triangle fans.
    ExpectRead(Header("ascii", "4", faces) + AsciiRows(4) + "3 0 1 2\n4 0 1 2 3\n", 4);
}

TEST_F(PlyInput, ElementsAndTypesVcglibAssertsOnAreRefused)
{
    ExpectRefused(Header("ascii", "3", "element edge 1\nproperty int vertex1\nproperty int vertex2\n") + AsciiRows(3) + "0 1\n",
                  "element 'edge' is not supported");
    ExpectRefused("ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty double x\nproperty double y\n"
                  "property double z\nproperty float nx\nproperty float ny\nproperty float nz\nend_header\n" +
                      std::string(36, '\0'),
                  "doubles in big-endian files are not supported");
}

TEST_F(PlyInput, TextureCommentsLongerThanVcglibHoldsAreRefused)
{
    const std::string vertices(3 * 24, '\0');
    ExpectRefused("ply\nformat binary_little_endian 1.0\ncomment TextureFile " + std::string(300, 'a') +
                      ".png\nelement vertex 3\n" + kPointProperties + "end_header\n" + vertices,
                  "TextureFile comment of 316 characters");
    ExpectRefused("ply\nformat binary_little_endian 1.0\nobj_info TextureFile " + std::string(300, 'a') +
                      "\nelement vertex 3\n" + kPointProperties + "end_header\n" + vertices,
                  "TextureFile comment");
    ExpectRead("ply\nformat ascii 1.0\ncomment TextureFile bunny.png\nelement vertex 3\n" + std::string(kPointProperties) +
                   "end_header\n" + AsciiRows(3),
               3);
}

TEST_F(PlyInput, ListsVcglibSkipsSafelyAreRead)
{
    // One-byte counts of items of at most two bytes fit the buffer; ASCII lists are skipped item by item.
    std::string vertices;
    const float rows[3][6] = {{0, 0, 0, 0, 0, 1}, {1, 0, 0, 0, 0, 1}, {0, 1, 0, 0, 0, 1}};
    vertices.append(reinterpret_cast<const char *>(rows), sizeof rows);
    ExpectRead(Header("binary_little_endian", "3", "element extra 1\nproperty list uchar short data\n") + vertices +
                   std::string(1, char(255)) + std::string(510, 'A'),
               3);
    ExpectRead(Header("ascii", "3", "element extra 1\nproperty list uchar int data\n") + AsciiRows(3) + "3 7 8 9\n", 3);
}

TEST_F(PlyInput, MissingPropertiesAreRefused)
{
    ExpectRefused("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
                  "0 0 0\n1 0 0\n0 1 0\n",
                  "no per-vertex normals (nx ny nz)");
    ExpectRefused("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float z\nproperty float nx\n"
                  "property float ny\nproperty float nz\nend_header\n0 0 0 0 1\n",
                  "no 'y' property");
    ExpectRefused("ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n",
                  "no vertex element");
    std::string byteNormal = Header("ascii", "1");
    byteNormal.replace(byteNormal.find("float nx"), 5, "uchar");
    ExpectRefused(byteNormal + "0 0 0 0 0 1\n", "float or all be double");
}

TEST_F(PlyInput, TruncatedBodyIsRefused)
{
    // Long enough for the counts, short of the last row.
    ExpectRefused(Header("ascii", "3") + "0.000000001 0.000000001 0.000000001 0 0 1\n1 0 0 0 0 1\n0 1",
                  "line 13 (vertex 2): 2 values where the vertex has 6");
    ExpectRefused(Header("binary_little_endian", "3") + std::string(3 * 24 - 1, '\0'), "but only 71 bytes follow");
}

TEST_F(PlyInput, HeaderWithoutEndIsRefused)
{
    ExpectRefused("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n", "the file ends before end_header");
    std::string endless = "ply\nformat ascii 1.0\n";
    while (endless.size() < 70000) endless += "comment filler filler filler filler\n";
    ExpectRefused(endless, "no end_header within the first 65536 bytes");
    ExpectRefused("", "the file is empty");
}

TEST_F(PlyInput, MegabyteHeaderLineIsRefused)
{
    ExpectRefused("ply\nformat ascii 1.0\ncomment " + std::string(1 << 20, 'a') + "\n" + Header("ascii", "3").substr(21) +
                      AsciiRows(3),
                  "header line 3: longer than 500 bytes");
    ExpectRefused("ply\nformat ascii 1.0\nelement vertex " + std::string(1 << 20, '9') + "\n", "longer than 500 bytes");
}

TEST_F(PlyInput, MalformedHeadersAreRefusedWithQuotedEscapedText)
{
    ExpectRefused("PK\x03\x04" + std::string(1000, 'z'), "not a PLY file: it starts with 'PK\\x03\\x04zzz");
    ExpectRefused("ply\nformat binary_middle_endian 1.0\nend_header\n", "unknown format 'binary_middle_endian'");
    ExpectRefused("ply\nformat ascii 2.0\nend_header\n", "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
    ExpectRefused("ply\nformat ascii 1.0\nelement vertex 3\nproperty floaty x\nend_header\n", "unknown type 'floaty'");
    ExpectRefused("ply\nformat ascii 1.0\nproperty float x\nend_header\n", "a property before any element");
    ExpectRefused("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float x\nend_header\n0 0\n",
                  "a second property 'x'");
    ExpectRefused(Header("ascii", "3", "element vertex 3\n" + std::string(kPointProperties)) + AsciiRows(6),
                  "a second element 'vertex'");
    ExpectRefused("ply\nformat ascii 1.0\nelement vert\x01" "ex 3\nend_header\n", "non-printable byte: 'element vert\\x01ex 3'");
    ExpectRefused("ply\nformat ascii 1.0\nbogus " + std::string(400, 'b') + "\nend_header\n", "unexpected 'bogus bbbb");
    ExpectRefused("ply\nformat ascii 1.0\nelement empty 5\n" + std::string(kPointProperties) + "end_header\n",
                  "no vertex element");
    ExpectRefused("ply\nformat ascii 1.0\nelement vertex 1\n" + std::string(kPointProperties) + "element empty 5\nend_header\n"
                  "0 0 0 0 0 1\n",
                  "element 'empty' has records but no properties");
}

TEST_F(PlyInput, MissingFileIsRefused)
{
    OrientedPointMesh mesh;
    std::string error;
    EXPECT_FALSE(gsresample::ReadOrientedPoints(::testing::TempDir() + "no_such_file.ply", mesh, error));
    EXPECT_NE(error.find("cannot open the file: No such file or directory"), std::string::npos) << error;
    EXPECT_FALSE(gsresample::ReadOrientedPoints(::testing::TempDir(), mesh, error));
    EXPECT_EQ(error, "not a regular file");
}

TEST_F(PlyInput, AsciiLoads)
{
    OrientedPointMesh mesh;
    std::string error;
    ASSERT_TRUE(gsresample::ReadOrientedPoints(Write("ply\r\nformat ascii 1.0\r\ncomment made by a test\r\n" +
                                                     Header("ascii", "4").substr(21) + AsciiRows(4)),
                                               mesh, error))
        << error;
    ASSERT_EQ(mesh.vn, 4);
    EXPECT_EQ(mesh.vert[3].P(), vcg::Point3f(3, 6, 0.5f));
    EXPECT_EQ(mesh.vert[3].N(), vcg::Point3f(0, 0, 1));
}

TEST_F(PlyInput, BinaryBigEndianLoads)
{
    std::string body;
    for (int i = 0; i < 5; ++i)
        for (float value : {float(i), -1.5f * i, 0.25f, 0.f, 1.f, 0.f}) AppendFloat(body, value, true);
    OrientedPointMesh mesh;
    std::string error;
    ASSERT_TRUE(gsresample::ReadOrientedPoints(Write(Header("binary_big_endian", "5") + body), mesh, error)) << error;
    ASSERT_EQ(mesh.vn, 5);
    EXPECT_EQ(mesh.vert[4].P(), vcg::Point3f(4, -6, 0.25f));
    EXPECT_EQ(mesh.vert[4].N(), vcg::Point3f(0, 1, 0));
}

TEST_F(PlyInput, BinaryLittleEndianWithFacesAndExtraPropertiesLoads)
{
    std::string body;
    for (int i = 0; i < 3; ++i) {
        for (float value : {float(i), 0.f, 0.f, 0.f, 0.f, -1.f}) AppendFloat(body, value, false);
        body += char(7); // quality-like extra uchar
    }
    body += std::string("\x03\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00", 13);
    OrientedPointMesh mesh;
    std::string error;
    ASSERT_TRUE(gsresample::ReadOrientedPoints(
        Write(Header("binary_little_endian", "3", "property uchar extra\nelement face 1\nproperty list uchar int vertex_indices\n") +
              body),
        mesh, error))
        << error;
    ASSERT_EQ(mesh.vn, 3);
    EXPECT_EQ(mesh.vert[2].P(), vcg::Point3f(2, 0, 0));
    EXPECT_EQ(mesh.vert[2].N(), vcg::Point3f(0, 0, -1));
}

// The ASCII body is checked record by record before vcglib's reader, which would shift every
// later value after a malformed one (CheckAsciiBody). Header("ascii", ...) takes lines 1-10.

TEST_F(PlyInput, AsciiRecordsOfTheWrongLengthAreRefusedWithTheirLine)
{
    ExpectRefused(Header("ascii", "3") + "0 0 0 0 0 1\n1 0 0 0 0 1 7\n0 1 0 0 0 1\n",
                  "line 12 (vertex 1): 7 values where the vertex has 6");
    ExpectRefused(Header("ascii", "3") + "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 1.00\n",
                  "line 13 (vertex 2): 5 values where the vertex has 6");
    // A record split over two lines: each is refused.
    ExpectRefused(Header("ascii", "3") + "0 0 0\n0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n",
                  "line 11 (vertex 0): 3 values where the vertex has 6");
    ExpectRefused(Header("ascii", "3") + "0 0 0 0 0 1 1 0 0 0 0 1\n0.5 1 0 0 0 1\n",
                  "line 11 (vertex 0): 12 values where the vertex has 6");
    // Lines of a record with lists: the list's count says how many items follow.
    const std::string faces = "element face 1\nproperty list uchar int vertex_indices\n";
    ExpectRefused(Header("ascii", "3", faces) + AsciiRows(3) + "3 0 1 2 0\n",
                  "line 16 (face 0): 5 values where this record has 4 (its list counts included)");
    ExpectRefused(Header("ascii", "3", faces) + AsciiRows(3) + "3 0 1\n",
                  "line 16 (face 0), property vertex_indices, item 2: missing (the line has 3 values, the list count is 3)");
    ExpectRefused(Header("ascii", "3", faces + "property uchar tag\n") + AsciiRows(3) + "3 0 1 2\n",
                  "line 17 (face 0), property tag: missing (the line has 4 values)");
    ExpectRefused(Header("ascii", "3", faces) + AsciiRows(3) + "\n",
                  "the file ends at line 16, after 0 of 1 face records");
}

TEST_F(PlyInput, AsciiValuesThatAreNotWholeNumbersAreRefused)
{
    const std::string before = Header("ascii", "3") + "0 0 0 0 0 1\n";
    ExpectRefused(before + "1.0.0 0 0 0 0 1\n0 1 0 0 0 1\n", "line 12 (vertex 1), property x: '1.0.0' is not a number");
    ExpectRefused(before + "1 0 1e 0 0 1\n0 1 0 0 0 1\n", "line 12 (vertex 1), property z: '1e' is not a number");
    for (const char *token : {"abc", "nan(0x123)", "0x", "--1", "1,5", ".", "e5", "1e+", "0x1p", "infinit", "1.5f", "1_0"})
        ExpectRefused(before + "1 0 0 0 0 1\n0 1 0 0 " + token + " 1\n",
                      std::string("line 13 (vertex 2), property ny: '") + token + "' is not a number");
    // Control bytes are quoted escaped, long tokens cut.
    ExpectRefused(before + "1 0 0 0 0 1\n0 1 0 0 0 1\x0b\n", "property nz: '1\\x0b' is not a number");
    ExpectRefused(before + "1 0 0 0 0 1\n0 1 0 0 0 " + std::string(1 << 20, '7') + "x\n",
                  "property nz: '77777777777777777777777777777777...' is not a number");
    // Long enough for the counts (CheckBodySize), one record short.
    ExpectRefused(before + "1.0000000000000000000000 0 0 0 0 1\n", "the file ends at line 12, after 2 of 3 vertex records");
    // Integer properties take decimal integers in their type's range.
    const std::string extra = "property uchar red\nproperty int quality\n";
    ExpectRefused(Header("ascii", "1", extra) + "0 0 0 0 0 1 1.5 0\n", "line 13 (vertex 0), property red: '1.5' is not an integer");
    ExpectRefused(Header("ascii", "1", extra) + "0 0 0 0 0 1 256 0\n", "property red: '256' is out of range for uchar (0 to 255)");
    ExpectRefused(Header("ascii", "1", extra) + "0 0 0 0 0 1 -1 0\n", "property red: '-1' is out of range for uchar (0 to 255)");
    ExpectRefused(Header("ascii", "1", extra) + "0 0 0 0 0 1 0 2147483648\n",
                  "property quality: '2147483648' is out of range for int (-2147483648 to 2147483647)");
    ExpectRefused(Header("ascii", "1", extra) + "0 0 0 0 0 1 0 99999999999999999999999\n",
                  "property quality: '99999999999999999999999' is out of range for int");
    ExpectRefused(Header("ascii", "1", extra) + "0 0 0 0 0 1 0 0x10\n", "property quality: '0x10' is not an integer");
    ExpectRefused(Header("ascii", "3", "element extra 1\nproperty list char float data\n") + AsciiRows(3) + "-2 1 2\n",
                  "line 16 (extra 0), property data, list count: '-2' is negative");
    ExpectRefused(Header("ascii", "3", "element extra 1\nproperty list uchar short data\n") + AsciiRows(3) + "2 1 40000\n",
                  "line 16 (extra 0), property data, item 1: '40000' is out of range for short");
}

TEST_F(PlyInput, AsciiContentAfterTheLastRecordIsRefused)
{
    ExpectRefused(Header("ascii", "3") + AsciiRows(3) + "\n  \njunk junk\n", "line 16: 'junk junk' after the last record");
    ExpectRefused(Header("ascii", "3") + AsciiRows(4), "line 14: '3 6 0.5 0 0 1' after the last record");
    ExpectRefused(Header("ascii", "3", "element face 1\nproperty list uchar int vertex_indices\n") + AsciiRows(3) +
                      "3 0 1 2\n3 0 1 2",
                  "line 17: '3 0 1 2' after the last record");
    // A line is held whole, up to 16 MiB.
    ExpectRefused(Header("ascii", "3") + AsciiRows(2) + "0 1 0 0 0 1" + std::string(17 << 20, ' ') + "\n",
                  "line 13 (vertex 2): longer than 16777216 bytes");
}

TEST_F(PlyInput, AsciiLayoutsOfValidFilesAreRead)
{
    const std::string faces = "element face 2\nproperty list uchar int vertex_indices\nproperty uchar tag\n";
    // CRLF line ends, tabs and runs of blanks, comments, blank lines between and after the
    // records, and no line end after the last one.
    ExpectRead("ply\r\nformat ascii 1.0\r\ncomment a\tcomment\r\n" + Header("ascii", "3", faces).substr(21) +
                   "\t0 0 0  0 0 1\r\n\r\n 1\t0 0 0 0 1 \t\r\n0 1 0 0 0 1\r\n3 0 1 2 7\r\n   \r\n4\t0 1 2 0\t0\r\n\r\n\t\n \n",
               3);
    ExpectRead(Header("ascii", "3", faces) + AsciiRows(3) + "3 0 1 2 0\n3 2 1 0 255", 3);
    // Lists vcglib skips, empty lists, and integer properties at their types' limits.
    ExpectRead(Header("ascii", "2", "property char a\nproperty ushort b\nproperty uint c\nelement extra 2\n"
                                    "property list uint double data\n") +
                   "0 0 0 0 0 1 -128 65535 4294967295\n1 0 0 0 0 1 127 0 +0\n0\n3 1e300 -0 0x1p-3\n",
               2);
    ExpectRead(Header("ascii", "0"), 0);
}

TEST_F(PlyInput, AsciiNumbersReadAsBeforeTheCheck)
{
    // Every spelling fscanf reads whole: exponents, signs, points at either end, hexadecimal,
    // nan and infinities in any case, overflow to infinity (the resampler skips such points).
    const std::string body = "1e2 -2.5E-1 +.5 5. 0x1.8p1 0X10\n"
                             "nan -NaN INF -inf Infinity -INFINITY\n"
                             "1e999 -1e999 0000.125 -0 1 1E+0\n";
    OrientedPointMesh ascii;
    std::string error;
    ASSERT_TRUE(gsresample::ReadOrientedPoints(Write(Header("ascii", "3") + body), ascii, error)) << error;
    ASSERT_EQ(ascii.vn, 3);
    EXPECT_EQ(ascii.vert[0].P(), vcg::Point3f(100, -0.25f, 0.5f));
    EXPECT_EQ(ascii.vert[0].N(), vcg::Point3f(5, 3, 16));
    EXPECT_TRUE(std::isnan(ascii.vert[1].P()[0]) && std::isnan(ascii.vert[1].P()[1]));
    EXPECT_EQ(ascii.vert[1].P()[2], INFINITY);
    EXPECT_EQ(ascii.vert[1].N(), vcg::Point3f(-INFINITY, INFINITY, -INFINITY));
    EXPECT_EQ(ascii.vert[2].P(), vcg::Point3f(INFINITY, -INFINITY, 0.125f));
    EXPECT_EQ(ascii.vert[2].N(), vcg::Point3f(0, 1, 1));
    // Ordinary values read as the same file in binary.
    std::string binary;
    const float values[] = {0.1f, -3.25e-7f, 12345.678f, 0.f, -0.70710677f, 0.70710677f};
    std::string row;
    for (float v : values) {
        AppendFloat(binary, v, false);
        char text[32];
        std::snprintf(text, sizeof text, "%.9g ", v);
        row += text;
    }
    OrientedPointMesh fromAscii, fromBinary;
    ASSERT_TRUE(gsresample::ReadOrientedPoints(Write(Header("ascii", "1") + row + "\n"), fromAscii, error)) << error;
    ASSERT_TRUE(gsresample::ReadOrientedPoints(Write(Header("binary_little_endian", "1") + binary), fromBinary, error));
    EXPECT_EQ(fromAscii.vert[0].P(), fromBinary.vert[0].P());
    EXPECT_EQ(fromAscii.vert[0].N(), fromBinary.vert[0].N());
}
