#include "ply_input.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <new>
#include <vector>

#include <wrap/io_trimesh/import_ply.h>

#include <io_surfel/printable_text.h>
#include <vcg_ext/gaussphere/usable_points.h>

namespace gsresample {
namespace {

constexpr std::size_t kMaxHeaderBytes = 65536;
// vcglib reads header lines with fgets into 512 bytes and would take the rest of a longer
// line for a line of its own.
constexpr std::size_t kMaxHeaderLineBytes = 500;
constexpr std::size_t kMaxErrorChars = 200;
// Quoted header text in messages: 32 characters of it and the "..." of a cut.
constexpr std::size_t kQuoteChars = 35;
// vcglib copies a TextureFile comment, each `<this>` in it replaced by the file's name, into 255
// bytes; comments that could come near that are refused.
constexpr std::size_t kMaxTextureCommentBytes = 200;

struct ScalarType
{
    const char *name, *alias;
    int bytes;
};
constexpr ScalarType kScalarTypes[] = {{"char", "int8", 1},   {"uchar", "uint8", 1},     {"short", "int16", 2},
                                       {"ushort", "uint16", 2}, {"int", "int32", 4},       {"uint", "uint32", 4},
                                       {"float", "float32", 4}, {"double", "float64", 8}};

std::string Quote(const std::string &text) { return "'" + surfel_io::printableText(text, kQuoteChars) + "'"; }

std::vector<std::string> SplitTokens(const std::string &line)
{
    std::vector<std::string> tokens;
    std::size_t start = 0;
    while (start < line.size()) {
        const std::size_t begin = line.find_first_not_of(" \t", start);
        if (begin == std::string::npos) break;
        std::size_t end = line.find_first_of(" \t", begin);
        if (end == std::string::npos) end = line.size();
        tokens.push_back(line.substr(begin, end - begin));
        start = end;
    }
    return tokens;
}

/// An element count: decimal digits only, at most INT_MAX (vcglib keeps counts in an int).
bool ParseCount(const std::string &element, const std::string &text, std::uint64_t &count, std::string &error)
{
    bool digits = !text.empty();
    for (char c : text) digits = digits && c >= '0' && c <= '9';
    if (!digits) {
        error = "the count of element " + Quote(element) + " is not a non-negative integer: " + Quote(text);
        return false;
    }
    std::uint64_t value = 0;
    for (char c : text) {
        value = value * 10 + std::uint64_t(c - '0');
        if (value > std::uint64_t(INT_MAX)) {
            error = "the count of element " + Quote(element) + " exceeds " + std::to_string(INT_MAX) + ": " + Quote(text);
            return false;
        }
    }
    count = value;
    return true;
}

bool ParseProperty(const std::vector<std::string> &tokens, HeaderProperty &property, std::string &error)
{
    if (tokens.size() >= 2 && tokens[1] == "list") {
        if (tokens.size() != 5) {
            error = "a list property needs 'property list COUNT_TYPE ITEM_TYPE NAME'";
            return false;
        }
        property.isList = true;
        property.countType = tokens[2];
        property.type = tokens[3];
        property.name = tokens[4];
        if (TypeSize(property.countType) == 0) {
            error = "unknown type " + Quote(property.countType) + " for the count of list " + Quote(property.name);
            return false;
        }
        if (IsFloatingType(property.countType)) {
            error = "the count of list " + Quote(property.name) + " has a floating-point type";
            return false;
        }
    } else {
        if (tokens.size() != 3) {
            error = "a property needs 'property TYPE NAME'";
            return false;
        }
        property.type = tokens[1];
        property.name = tokens[2];
    }
    if (TypeSize(property.type) == 0) {
        error = "unknown type " + Quote(property.type) + " of property " + Quote(property.name);
        return false;
    }
    return true;
}

/// Reads the first kMaxHeaderBytes of the file into `text` and checks its first line, "ply";
/// `magicBytes` receives that line's length with its line end.
bool ReadHeaderBytes(std::istream &in, std::uint64_t fileSize, std::string &text, std::size_t &magicBytes,
                     std::string &error)
{
    text.assign(std::size_t(std::min<std::uint64_t>(fileSize, kMaxHeaderBytes)), '\0');
    if (!in.read(&text[0], std::streamsize(text.size()))) {
        error = "cannot read the header";
        return false;
    }
    if (text.empty()) {
        error = "the file is empty";
        return false;
    }
    magicBytes = text.compare(0, 4, "ply\n") == 0 ? 4 : text.compare(0, 5, "ply\r\n") == 0 ? 5 : 0;
    if (magicBytes == 0) {
        error = "not a PLY file: it starts with " + Quote(text.substr(0, text.find('\n')));
        return false;
    }
    return true;
}

/// The header line of `text` at `start`, without its line end, as vcglib will read it: at most
/// kMaxHeaderLineBytes, printable ASCII or tabs; `start` moves to the next line. `where` names
/// the line in errors.
bool NextHeaderLine(const std::string &text, std::uint64_t fileSize, const std::string &where, std::size_t &start,
                    std::string &line, std::string &error)
{
    const std::size_t newline = text.find('\n', start);
    const std::size_t end = newline == std::string::npos ? text.size() : newline;
    if (end - start > kMaxHeaderLineBytes) {
        error = where + "longer than " + std::to_string(kMaxHeaderLineBytes) + " bytes";
        return false;
    }
    if (newline == std::string::npos) {
        if (text.size() < fileSize) error = "no end_header within the first " + std::to_string(kMaxHeaderBytes) + " bytes";
        else error = "the file ends before end_header";
        return false;
    }
    line = text.substr(start, end - start);
    start = newline + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    for (char c : line) {
        const unsigned char u = static_cast<unsigned char>(c);
        if (u != '\t' && (u < 0x20 || u >= 0x7f)) {
            error = where + "holds a non-printable byte: " + Quote(line);
            return false;
        }
    }
    return true;
}

/// The `format` line, which must come first (comments aside).
bool ParseFormat(const std::vector<std::string> &tokens, const std::string &line, PlyHeader &header,
                 std::string &error)
{
    if (tokens[0] != "format" || tokens.size() != 3 || tokens[2] != "1.0") {
        error = "expected 'format ascii|binary_little_endian|binary_big_endian 1.0', got " + Quote(line);
        return false;
    }
    if (tokens[1] == "ascii") header.binary = false;
    else if (tokens[1] == "binary_little_endian" || tokens[1] == "binary_big_endian") {
        header.binary = true;
        header.bigEndian = tokens[1] == "binary_big_endian";
    }
    else {
        error = "unknown format " + Quote(tokens[1]);
        return false;
    }
    return true;
}

bool AddElement(const std::vector<std::string> &tokens, const std::string &line, PlyHeader &header,
                std::string &error)
{
    if (tokens.size() != 3) {
        error = "expected 'element NAME COUNT', got " + Quote(line);
        return false;
    }
    for (const HeaderElement &e : header.elements) {
        if (e.name == tokens[1]) {
            error = "a second element " + Quote(tokens[1]);
            return false;
        }
    }
    HeaderElement element;
    element.name = tokens[1];
    if (!ParseCount(element.name, tokens[2], element.count, error)) return false;
    header.elements.push_back(element);
    return true;
}

/// A property of the last element declared.
bool AddProperty(const std::vector<std::string> &tokens, PlyHeader &header, std::string &error)
{
    if (header.elements.empty()) {
        error = "a property before any element";
        return false;
    }
    HeaderProperty property;
    if (!ParseProperty(tokens, property, error)) return false;
    HeaderElement &element = header.elements.back();
    if (element.Find(property.name)) {
        error = "a second property " + Quote(property.name) + " in element " + Quote(element.name);
        return false;
    }
    element.properties.push_back(property);
    return true;
}

/// A header line after the format line, but end_header: obj_info, element or property.
bool ParseDeclaration(const std::vector<std::string> &tokens, const std::string &line, PlyHeader &header,
                      std::string &error)
{
    const std::string &keyword = tokens[0];
    if (keyword == "obj_info") return true;
    if (keyword == "element") return AddElement(tokens, line, header, error);
    if (keyword == "property") return AddProperty(tokens, header, error);
    error = "unexpected " + Quote(line);
    return false;
}

/// Reads the header from the first kMaxHeaderBytes of the file, line by line as vcglib will.
bool ReadHeader(std::istream &in, std::uint64_t fileSize, PlyHeader &header, std::string &error)
{
    std::string text;
    std::size_t start = 0;
    if (!ReadHeaderBytes(in, fileSize, text, start, error)) return false;
    bool formatSeen = false;
    for (int lineNumber = 2;; ++lineNumber) {
        const std::string where = "header line " + std::to_string(lineNumber) + ": ";
        std::string line;
        if (!NextHeaderLine(text, fileSize, where, start, line, error)) return false;
        const std::vector<std::string> tokens = SplitTokens(line);
        if (tokens.empty()) {
            error = where + "empty";
            return false;
        }
        // vcglib keeps the text after `comment` and `obj_info` (and one separator) as a comment.
        if (tokens[0] == "comment" || tokens[0] == "obj_info") {
            const std::size_t keyword = line.find(tokens[0]) + tokens[0].size() + 1;
            header.comments.push_back(keyword < line.size() ? line.substr(keyword) : std::string());
            if (tokens[0] == "comment") continue;
        }
        bool parsed;
        if (!formatSeen) {
            parsed = formatSeen = ParseFormat(tokens, line, header, error);
        } else if (tokens[0] == "end_header" && tokens.size() == 1) {
            header.bodyOffset = start;
            return true;
        } else {
            parsed = ParseDeclaration(tokens, line, header, error);
        }
        if (!parsed) {
            error = where + error;
            return false;
        }
    }
}

/// A list ImporterPLY skips in a binary file goes through a 512-byte buffer, its count read as one
/// byte whatever its declared type: safe for one-byte counts of items of at most 2 bytes.
bool CheckSkippedList(const PlyHeader &header, const HeaderElement &element, const HeaderProperty &property,
                      std::string &error)
{
    if (!header.binary || IsReadCornerList(element, property) ||
        (TypeSize(property.countType) == 1 && TypeSize(property.type) <= 2))
        return true;
    error = "list property " + Quote(property.name) + " of element " + Quote(element.name) + " (" +
            Quote(property.countType) + " counts, " + Quote(property.type) +
            " items) is not supported in binary files: remove it, or save the file as ASCII";
    return false;
}

/// What this reader needs and what vcglib's ImporterPLY handles safely: it reads lists into
/// fixed-size buffers (face corners into 512 ints, face colours into 32 floats, range grid
/// points into 5 ints), tristrips into a buffer sized by each record's count, and skips the
/// lists it does not read through a fixed buffer (CheckSkippedList).
bool CheckElements(const PlyHeader &header, std::string &error)
{
    const HeaderElement *vertex = nullptr;
    for (const HeaderElement &e : header.elements) {
        if (e.name == "vertex") vertex = &e;
        if (e.count > 0 && e.properties.empty()) {
            error = "element " + Quote(e.name) + " has records but no properties";
            return false;
        }
        // vcglib asserts on edges of a mesh without them, and on big-endian doubles it stores.
        if (e.name == "tristrips" || e.name == "range_grid" || e.name == "edge") {
            error = "element " + Quote(e.name) + " is not supported";
            return false;
        }
        for (const HeaderProperty &p : e.properties) {
            if (p.isList && e.name != "vertex" && !CheckSkippedList(header, e, p, error)) return false;
            if (header.bigEndian && (e.name == "vertex" || e.name == "face") && TypeSize(p.type) == 8) {
                error = "property " + Quote(p.name) + " of element " + Quote(e.name) +
                        ": doubles in big-endian files are not supported; save the file as little-endian";
                return false;
            }
        }
        if (e.name != "face") continue;
        if (e.Find("vertex_indices") && e.Find("vertex_index")) {
            error = "the face element declares both 'vertex_indices' and 'vertex_index'";
            return false;
        }
        for (const HeaderProperty &p : e.properties) {
            if (!p.isList) continue;
            if (IsReadCornerList(e, p)) {
                if (TypeSize(p.countType) != 1) {
                    error = "face list " + Quote(p.name) + " counted by " + Quote(p.countType) +
                            ": only char or uchar counts (at most 255 corners) are supported";
                    return false;
                }
            } else if (p.name == "color" || p.name == "texcoord") {
                error = "face list property " + Quote(p.name) + " is not supported";
                return false;
            }
        }
    }
    if (!vertex) {
        error = "the file has no vertex element";
        return false;
    }
    for (const HeaderProperty &p : vertex->properties) {
        if (p.isList) {
            error = "the vertex element has a list property " + Quote(p.name) + "; lists on vertices are not supported";
            return false;
        }
    }
    for (const char *name : {"x", "y", "z"}) {
        const HeaderProperty *p = vertex->Find(name);
        if (!p) {
            error = std::string("the vertex element has no '") + name + "' property (x y z nx ny nz are needed)";
            return false;
        }
        if (!IsFloatingType(p->type)) {
            error = std::string("vertex property '") + name + "' is " + Quote(p->type) + "; float or double is needed";
            return false;
        }
    }
    const HeaderProperty *nx = vertex->Find("nx"), *ny = vertex->Find("ny"), *nz = vertex->Find("nz");
    if (!nx || !ny || !nz) {
        error = "no per-vertex normals (nx ny nz); compute them first, e.g. with MeshLab's Compute normals for point sets";
        return false;
    }
    const int normalSize = TypeSize(nx->type);
    if (!IsFloatingType(nx->type) || TypeSize(ny->type) != normalSize || TypeSize(nz->type) != normalSize ||
        !IsFloatingType(ny->type) || !IsFloatingType(nz->type)) {
        error = "the normals nx ny nz must all be float or all be double";
        return false;
    }
    return true;
}

/// Values a record of `element` holds at least for `property`: one for a scalar, the count
/// for a list, and for a face's corner list also three corners (vcglib allocates a face for
/// each record and makes a triangle of it).
int MinimumValues(const HeaderElement &element, const HeaderProperty &property)
{
    return IsReadCornerList(element, property) ? 4 : 1;
}

/// The body must hold at least the smallest records the counts announce: a binary record
/// takes its values' bytes, an ASCII record one character and a separator per value. This
/// keeps vcglib from allocating for records that are not there.
bool CheckBodySize(const PlyHeader &header, std::uint64_t fileSize, std::string &error)
{
    const std::uint64_t available = fileSize - header.bodyOffset;
    const bool binary = header.binary;
    std::uint64_t needed = 0;
    for (const HeaderElement &e : header.elements) {
        std::uint64_t recordBytes = 0;
        for (const HeaderProperty &p : e.properties) {
            const int values = MinimumValues(e, p);
            if (!binary) recordBytes += 2 * std::uint64_t(values);
            else if (p.isList) recordBytes += std::uint64_t(TypeSize(p.countType) + (values - 1) * TypeSize(p.type));
            else recordBytes += std::uint64_t(TypeSize(p.type));
        }
        const std::uint64_t elementBytes = e.count * recordBytes;
        needed += elementBytes;
        // An ASCII file may end without a separator after its last value.
        const std::uint64_t neededNow = binary || needed == 0 ? needed : needed - 1;
        if (neededNow > available) {
            error = "the header announces " + std::to_string(e.count) + " " + surfel_io::printableText(e.name, kQuoteChars) +
                    " record(s) of at least " + std::to_string(recordBytes) + " bytes, but only " +
                    std::to_string(available) + " bytes follow the header" +
                    (needed > elementBytes ? " and the elements before it" : "");
            return false;
        }
    }
    return true;
}

/// See kMaxTextureCommentBytes.
bool CheckTextureComments(const PlyHeader &header, const std::string &path, std::string &error)
{
    const std::string fileName = path.substr(path.find_last_of('/') + 1);
    for (const std::string &comment : header.comments) {
        if (comment.compare(0, 11, "TextureFile") != 0) continue;
        const std::size_t expansions = std::size_t(std::count(comment.begin(), comment.end(), '<'));
        if (comment.size() + expansions * fileName.size() >= kMaxTextureCommentBytes) {
            error = "a TextureFile comment of " + std::to_string(comment.size()) +
                    " characters (its <this> the file's name) is longer than vcglib's PLY reader holds";
            return false;
        }
    }
    return true;
}

/// Reads a value of a binary body as plylib does, from `file` at its position (CheckFaceCorners).
class BodyReader
{
public:
    BodyReader(std::FILE *file, const PlyHeader &header) : file_(file), header_(header) {}

    /// A scalar plylib stores or skips.
    bool Scalar(const std::string &type) { return Bytes(TypeSize(type), nullptr); }
    /// A list count: one byte (signed for char, as stored).
    bool Count(const std::string &countType, bool stored, long &count)
    {
        unsigned char byte;
        if (!Bytes(1, &byte)) return false;
        count = stored && CanonicalType(countType) == "char" ? long(static_cast<signed char>(byte)) : long(byte);
        return true;
    }
    /// A face corner as plylib stores it in an int (short items through a short).
    bool Corner(const std::string &type, long long &corner)
    {
        unsigned char bytes[4];
        const int size = TypeSize(type);
        if (!Bytes(size, bytes)) return false;
        if (header_.bigEndian) std::reverse(bytes, bytes + size);
        std::int32_t word = 0;
        std::int16_t half = 0;
        if (size == 2) std::memcpy(&half, bytes, 2);
        else std::memcpy(&word, bytes, 4);
        corner = size == 2 ? half : word;
        return true;
    }
    /// Passes over the records of an element without lists in one seek.
    bool SkipFixedRecords(const HeaderElement &element)
    {
        std::uint64_t bytes = 0;
        for (const HeaderProperty &p : element.properties) bytes += std::uint64_t(TypeSize(p.type));
        return ::fseeko(file_, off_t(bytes * element.count), SEEK_CUR) == 0;
    }
    /// An item of a list plylib skips.
    bool SkippedItem(const std::string &type) { return Bytes(TypeSize(type), nullptr); }

private:
    bool Bytes(int size, unsigned char *out)
    {
        unsigned char ignored[8];
        return std::fread(out ? out : ignored, 1, std::size_t(size), file_) == std::size_t(size);
    }
    std::FILE *file_;
    const PlyHeader &header_;
};

/// vcglib reads each face's corners into 512 slots and indexes its vertices with them
/// unchecked. In a binary file (the records of an ASCII one are checked by CheckAsciiBody) the
/// records up to the last element with corners are read here first, each value as plylib reads
/// it: a corner that is not a vertex is refused (a one-byte count holds at most 255 corners).
/// Where plylib's own read would stop, this one stops too and leaves the file to vcglib's error.
bool CheckFaceCorners(const std::string &path, const PlyHeader &header, std::string &error)
{
    std::size_t last = header.elements.size();
    std::uint64_t vertices = 0;
    for (std::size_t e = 0; e < header.elements.size(); ++e) {
        if (header.elements[e].name == "vertex") vertices = header.elements[e].count;
        for (const HeaderProperty &p : header.elements[e].properties)
            if (IsReadCornerList(header.elements[e], p)) last = e;
    }
    if (!header.binary || last == header.elements.size()) return true;
    std::unique_ptr<std::FILE, int (*)(std::FILE *)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file || ::fseeko(file.get(), off_t(header.bodyOffset), SEEK_SET) != 0) return true;
    BodyReader read(file.get(), header);
    for (std::size_t e = 0; e <= last; ++e) {
        const HeaderElement &element = header.elements[e];
        const bool fixedSize = std::none_of(element.properties.begin(), element.properties.end(),
                                            [](const HeaderProperty &p) { return p.isList; });
        // Records without lists hold no corners: their bytes need no reading (the vertices).
        if (fixedSize) {
            if (!read.SkipFixedRecords(element)) return true;
            continue;
        }
        for (std::uint64_t r = 0; r < element.count; ++r) {
            for (const HeaderProperty &p : element.properties) {
                if (!p.isList) {
                    if (!read.Scalar(p.type)) return true;
                    continue;
                }
                const bool corners = IsReadCornerList(element, p);
                long count = 0;
                if (!read.Count(p.countType, corners, count)) return true;
                if (corners && count < 3) { // vcglib would make a triangle of unset corners
                    error = "face record " + std::to_string(r) + " has " + std::to_string(count) +
                            " corner(s); a face needs at least 3";
                    return false;
                }
                for (long i = 0; i < count; ++i) {
                    long long corner = 0;
                    if (!corners) {
                        if (!read.SkippedItem(p.type)) return true;
                    } else if (!read.Corner(p.type, corner)) {
                        return true;
                    } else if (corner < 0 || std::uint64_t(corner) >= vertices) {
                        error = "face record " + std::to_string(r) + " names vertex " + std::to_string(corner) +
                                " of " + std::to_string(vertices);
                        return false;
                    }
                }
            }
        }
    }
    return true;
}

std::string Bounded(const std::string &message) { return surfel_io::printableText(message, kMaxErrorChars); }

} // namespace

std::string CanonicalType(const std::string &type)
{
    for (const ScalarType &t : kScalarTypes)
        if (type == t.name || type == t.alias) return t.name;
    return std::string();
}

/// ImporterPLY reads into its 512 face corners the corner lists its descriptors name
/// (vertex_indices of int, uint or short items, vertex_index of int items; their counts are
/// checked to be one byte apart). Every other list it skips.
bool IsReadCornerList(const HeaderElement &element, const HeaderProperty &property)
{
    if (element.name != "face" || !property.isList) return false;
    const std::string item = CanonicalType(property.type);
    if (property.name == "vertex_indices") return item == "int" || item == "uint" || item == "short";
    return property.name == "vertex_index" && item == "int";
}

int TypeSize(const std::string &type)
{
    for (const ScalarType &t : kScalarTypes)
        if (type == t.name || type == t.alias) return t.bytes;
    return 0;
}

bool IsFloatingType(const std::string &type)
{
    return type == "float" || type == "float32" || type == "double" || type == "float64";
}

bool ReadOrientedPointHeader(const std::string &path, PlyHeader &header, std::string &error)
{
    struct stat info;
    if (::stat(path.c_str(), &info) != 0) {
        error = Bounded(std::string("cannot open the file: ") + std::strerror(errno));
        return false;
    }
    if (!S_ISREG(info.st_mode)) {
        error = "not a regular file";
        return false;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = Bounded(std::string("cannot open the file: ") + std::strerror(errno));
        return false;
    }
    const std::uint64_t fileSize = std::uint64_t(info.st_size);
    if (!ReadHeader(in, fileSize, header, error) || !CheckElements(header, error) ||
        !CheckBodySize(header, fileSize, error) || !CheckTextureComments(header, path, error) ||
        !CheckFaceCorners(path, header, error)) {
        error = Bounded(error);
        return false;
    }
    return true;
}

namespace {

/// vcglib's ImporterPLY on a file whose header and ASCII body were checked; `mask` receives
/// what it read (vcg::tri::io::Mask).
template <class MeshType>
bool ImportChecked(const std::string &path, MeshType &mesh, int &mask, std::string &error)
{
    typedef vcg::tri::io::ImporterPLY<MeshType> Importer;
    mask = 0;
    int status = 0;
    try {
        status = Importer::Open(mesh, path.c_str(), mask);
    } catch (const std::bad_alloc &) {
        error = "not enough memory for the points";
        return false;
    } catch (const std::exception &e) {
        error = Bounded(std::string("vcglib's PLY reader failed: ") + e.what());
        return false;
    }
    if (Importer::ErrorCritical(status)) {
        error = Bounded(std::string("vcglib's PLY reader failed: ") + Importer::ErrorMsg(status));
        return false;
    }
    if (!(mask & vcg::tri::io::Mask::IOM_VERTNORMAL)) {
        error = "vcglib's PLY reader found no per-vertex normals";
        return false;
    }
    return true;
}

bool HasDoubleCoordinates(const PlyHeader &header)
{
    for (const HeaderElement &element : header.elements) {
        if (element.name != "vertex") continue;
        for (const char *axis : {"x", "y", "z"}) {
            const HeaderProperty *p = element.Find(axis);
            if (p && CanonicalType(p->type) == "double") return true;
        }
    }
    return false;
}

/// The centre of the bounding box of the points the resampler can use (usable_points.h), in
/// double; 0 when there is none.
vcg::Point3d CentreOfUsablePoints(const DoublePointMesh &exact)
{
    vcg::Box3d box;
    for (const DoublePointVertex &v : exact.vert)
        if (vcg::gaussphere::ClassifyVertex(v) == vcg::gaussphere::VertexUse::kUsable) box.Add(v.cP());
    return box.IsNull() ? vcg::Point3d(0, 0, 0) : box.Center();
}

/// The double points of `exact` moved by the centre of their box into the float `mesh`, the move
/// in `info`; false with a message when memory runs out.
bool MoveNearOrigin(const DoublePointMesh &exact, vcg::gaussphere::OrientedPointMesh &mesh, InputInfo &info,
                    std::string &error)
{
    info = InputInfo();
    info.doubleCoordinates = true;
    info.origin = CentreOfUsablePoints(exact);
    try {
        mesh.Clear();
        auto vi = vcg::tri::Allocator<vcg::gaussphere::OrientedPointMesh>::AddVertices(mesh, exact.vert.size());
        for (const DoublePointVertex &v : exact.vert) {
            vi->P() = vcg::Point3f::Construct(v.cP() - info.origin);
            vi->N() = vcg::Point3f::Construct(v.cN());
            vi->C() = v.cC();
            ++vi;
        }
    } catch (const std::bad_alloc &) {
        error = "not enough memory for the points";
        return false;
    }
    return true;
}

} // namespace

bool ReadOrientedPoints(const std::string &path, vcg::gaussphere::OrientedPointMesh &mesh, std::string &error,
                        InputInfo *info)
{
    PlyHeader header;
    if (!ReadOrientedPointHeader(path, header, error)) return false;
    if (!header.binary && !CheckAsciiBody(path, header, error)) {
        error = Bounded(error);
        return false;
    }
    int mask = 0;
    if (!info || !HasDoubleCoordinates(header)) {
        if (!ImportChecked(path, mesh, mask, error)) return false;
        if (info) *info = InputInfo();
    } else {
        DoublePointMesh exact;
        if (!ImportChecked(path, exact, mask, error) || !MoveNearOrigin(exact, mesh, *info, error)) return false;
    }
    if (info) info->vertexColours = (mask & vcg::tri::io::Mask::IOM_VERTCOLOR) != 0;
    return true;
}

} // namespace gsresample
