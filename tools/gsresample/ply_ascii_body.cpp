// The strict check of an ASCII PLY body (CheckAsciiBody in ply_input.h): vcglib's reader takes
// whitespace-separated tokens with fscanf, so a record of one value too many or too few, or a
// token fscanf reads only in part ("1.0.0", "1e"), shifts every later value without an error.
// Here the body is streamed line by line (one record a line, as PLY ASCII writes it) and each
// token is checked against its property's type before vcglib reads the file.
#include "ply_input.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <io_surfel/printable_text.h>

namespace gsresample {
namespace {

constexpr std::size_t kChunkBytes = std::size_t(1) << 20;
// A line is held whole: a face of 255 corners takes a few kilobytes.
constexpr std::size_t kMaxLineBytes = std::size_t(16) << 20;
// Quoted body text in messages: 32 characters of it and the "..." of a cut.
constexpr std::size_t kQuoteChars = 35;

std::string Quote(const char *begin, const char *end)
{
    const std::size_t length = std::min<std::size_t>(std::size_t(end - begin), 64);
    return "'" + surfel_io::printableText(std::string(begin, length), kQuoteChars) + "'";
}

std::string Name(const std::string &name) { return surfel_io::printableText(name, kQuoteChars); }

/// The lines of a file from its position on, read chunk by chunk into a buffer that holds the
/// current line whole.
class LineReader
{
public:
    LineReader(std::FILE *file, std::uint64_t firstLine) : file_(file), buffer_(kChunkBytes), line_(firstLine - 1) {}

    /// The next line without its line end ("\n" or "\r\n"; the last line may have none, or "\r"). False at
    /// the end of the file, or with `error` set on a read error or a line beyond kMaxLineBytes.
    bool Next(const char *&begin, const char *&end, std::string &error)
    {
        std::size_t searched = pos_;
        for (;;) {
            char *data = buffer_.data();
            const void *newline = std::memchr(data + searched, '\n', end_ - searched);
            if (newline || (eof_ && pos_ < end_)) {
                begin = data + pos_;
                end = newline ? static_cast<const char *>(newline) : data + end_;
                pos_ = newline ? std::size_t(end - data) + 1 : end_;
                if (end > begin && end[-1] == '\r') --end;
                ++line_;
                return true;
            }
            if (eof_) return false;
            searched = end_ - pos_;
            if (!Refill(error)) return false;
        }
    }
    /// The number of the line Next gave last (or of the next one, after a failed Next).
    std::uint64_t Line() const { return line_; }

private:
    /// Moves the unread bytes to the front and reads more after them.
    bool Refill(std::string &error)
    {
        std::memmove(buffer_.data(), buffer_.data() + pos_, end_ - pos_);
        end_ -= pos_;
        pos_ = 0;
        if (end_ == buffer_.size()) {
            if (buffer_.size() >= kMaxLineBytes) {
                ++line_;
                error = "longer than " + std::to_string(kMaxLineBytes) + " bytes";
                return false;
            }
            buffer_.resize(buffer_.size() * 2);
        }
        const std::size_t read = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
        end_ += read;
        if (read == 0) {
            if (std::ferror(file_)) {
                error = "read error after line " + std::to_string(line_);
                return false;
            }
            eof_ = true;
        }
        return true;
    }

    std::FILE *file_;
    std::vector<char> buffer_;
    std::size_t pos_ = 0, end_ = 0;
    bool eof_ = false;
    std::uint64_t line_;
};

/// The blank-separated tokens of a line (blanks: spaces and tabs).
struct Tokens
{
    const char *next, *end;

    bool Next(const char *&begin, const char *&tokenEnd)
    {
        while (next != end && (*next == ' ' || *next == '\t')) ++next;
        if (next == end) return false;
        begin = next;
        while (next != end && *next != ' ' && *next != '\t') ++next;
        tokenEnd = next;
        return true;
    }
    std::size_t CountRest()
    {
        std::size_t count = 0;
        const char *b, *e;
        while (Next(b, e)) ++count;
        return count;
    }
};

bool IsBlank(const char *begin, const char *end)
{
    Tokens tokens{begin, end};
    const char *b, *e;
    return !tokens.Next(b, e);
}

bool IsDigit(char c) { return c >= '0' && c <= '9'; }
bool IsHexDigit(char c) { return IsDigit(c) || ((c | 0x20) >= 'a' && (c | 0x20) <= 'f'); }

/// `text` equals the lower-case `word`, in any case.
bool IsWord(const char *begin, const char *end, const char *word)
{
    const std::size_t length = std::strlen(word);
    if (std::size_t(end - begin) != length) return false;
    for (std::size_t i = 0; i < length; ++i)
        if ((begin[i] | 0x20) != word[i]) return false;
    return true;
}

/// Digits (hexadecimal ones when `hex`) with an optional point among them, at least one digit;
/// `p` moves past them.
bool Mantissa(const char *&p, const char *end, bool hex)
{
    bool digits = false;
    while (p != end && (hex ? IsHexDigit(*p) : IsDigit(*p))) ++p, digits = true;
    if (p != end && *p == '.') ++p;
    while (p != end && (hex ? IsHexDigit(*p) : IsDigit(*p))) ++p, digits = true;
    return digits;
}

/// A whole number as fscanf's %f reads it whole (and strtod): decimal with an optional
/// exponent, hexadecimal (0x1.8p3), or nan, inf, infinity in any case, each optionally signed.
/// Out of range is no error: 1e999 reads as infinity, as an explicit inf does. fscanf reads
/// "nan(...)" only up to the parenthesis, so it is refused.
bool IsFloatToken(const char *p, const char *end)
{
    if (p != end && (*p == '+' || *p == '-')) ++p;
    if (p == end) return false;
    if ((*p | 0x20) == 'i' || (*p | 0x20) == 'n')
        return IsWord(p, end, "nan") || IsWord(p, end, "inf") || IsWord(p, end, "infinity");
    const bool hex = end - p > 2 && p[0] == '0' && (p[1] | 0x20) == 'x';
    if (hex) p += 2;
    if (!Mantissa(p, end, hex)) return false;
    if (p == end) return true;
    if ((*p | 0x20) != (hex ? 'p' : 'e')) return false;
    ++p;
    if (p != end && (*p == '+' || *p == '-')) ++p;
    const char *exponent = p;
    while (p != end && IsDigit(*p)) ++p;
    return p != exponent && p == end;
}

/// A decimal integer, optionally signed; false when it is none or beyond 19 significant digits.
bool ParseIntegerToken(const char *p, const char *end, long long &value)
{
    bool negative = false;
    if (p != end && (*p == '+' || *p == '-')) negative = *p++ == '-';
    if (p == end) return false;
    while (end - p > 1 && *p == '0') ++p;
    if (end - p > 18) {
        for (; p != end; ++p)
            if (!IsDigit(*p)) return false;
        value = negative ? -1000000000000000000LL : 1000000000000000000LL; // out of any PLY type's range
        return true;
    }
    long long magnitude = 0;
    for (; p != end; ++p) {
        if (!IsDigit(*p)) return false;
        magnitude = magnitude * 10 + (*p - '0');
    }
    value = negative ? -magnitude : magnitude;
    return true;
}

/// What a property's value (or a list's count or item) must be.
struct ValueType
{
    const char *name = "float"; // the canonical name
    bool floating = true;
    long long min = 0, max = 0;
};

ValueType MakeValueType(const std::string &type)
{
    struct Range
    {
        const char *name;
        long long min, max;
    };
    static const Range kRanges[] = {{"char", -128, 127},      {"uchar", 0, 255},           {"short", -32768, 32767},
                                    {"ushort", 0, 65535},     {"int", -2147483648LL, 2147483647LL},
                                    {"uint", 0, 4294967295LL}};
    ValueType value;
    const std::string canonical = CanonicalType(type);
    for (const Range &r : kRanges) {
        if (canonical == r.name) {
            value.name = r.name;
            value.floating = false;
            value.min = r.min;
            value.max = r.max;
        }
    }
    if (canonical == "double") value.name = "double";
    return value;
}

/// A property of an element as its records are checked.
struct PropertyCheck
{
    std::string name;
    bool isList = false;
    bool corners = false; // a face corner list vcglib reads: items name vertices
    ValueType count, item;
};

struct ElementCheck
{
    const HeaderElement *element;
    std::vector<PropertyCheck> properties;
    bool fixedSize = true; // no lists: a record has one value a property
};

std::vector<ElementCheck> MakeElementChecks(const PlyHeader &header)
{
    std::vector<ElementCheck> checks;
    for (const HeaderElement &e : header.elements) {
        ElementCheck check{&e, {}, true};
        for (const HeaderProperty &p : e.properties) {
            PropertyCheck property;
            property.name = p.name;
            property.isList = p.isList;
            property.corners = IsReadCornerList(e, p);
            if (p.isList) property.count = MakeValueType(p.countType);
            property.item = MakeValueType(p.type);
            check.fixedSize = check.fixedSize && !p.isList;
            check.properties.push_back(property);
        }
        checks.push_back(check);
    }
    return checks;
}

/// Checks the records of the body, one a line, against the header.
class RecordChecker
{
public:
    explicit RecordChecker(const PlyHeader &header) : elements_(MakeElementChecks(header))
    {
        for (const HeaderElement &e : header.elements)
            if (e.name == "vertex") vertices_ = e.count;
    }

    bool CheckAll(LineReader &lines, std::string &error);

private:
    bool Record(const char *begin, const char *end, std::string &error) const;
    bool Value(const ValueType &type, const char *begin, const char *end, long long &integer, std::string &problem) const;
    bool List(const PropertyCheck &property, Tokens &tokens, std::size_t &values, std::string &error) const;
    /// "line L (ELEMENT R)" of the record being checked, and ", property P" of one of its properties.
    std::string Where() const
    {
        return "line " + std::to_string(line_) + " (" + Name(element_->element->name) + " " + std::to_string(record_) + ")";
    }
    std::string Where(const PropertyCheck &property) const { return Where() + ", property " + Name(property.name); }

    std::vector<ElementCheck> elements_;
    std::uint64_t vertices_ = 0;
    // The record being checked.
    const ElementCheck *element_ = nullptr;
    std::uint64_t line_ = 0, record_ = 0;
};

/// Whether [begin, end) is a value of `type`; `problem` says why not, `integer` receives an
/// integer's value.
bool RecordChecker::Value(const ValueType &type, const char *begin, const char *end, long long &integer,
                          std::string &problem) const
{
    if (type.floating) {
        if (IsFloatToken(begin, end)) return true;
        problem = Quote(begin, end) + " is not a number";
        return false;
    }
    if (!ParseIntegerToken(begin, end, integer)) {
        problem = Quote(begin, end) + " is not an integer";
        return false;
    }
    if (integer < type.min || integer > type.max) {
        problem = Quote(begin, end) + " is out of range for " + type.name + " (" + std::to_string(type.min) + " to " +
                  std::to_string(type.max) + ")";
        return false;
    }
    return true;
}

/// A list property's count and items from `tokens`; `values` counts the tokens taken.
bool RecordChecker::List(const PropertyCheck &property, Tokens &tokens, std::size_t &values, std::string &error) const
{
    const char *b, *e;
    long long count = 0, item = 0;
    std::string problem;
    if (!tokens.Next(b, e)) {
        error = Where(property) + ": missing (the line has " + std::to_string(values) + " values)";
        return false;
    }
    ++values;
    if (!Value(property.count, b, e, count, problem) || count < 0) {
        error = Where(property) + ", list count: " + (problem.empty() ? Quote(b, e) + " is negative" : problem);
        return false;
    }
    if (property.corners && count < 3) { // vcglib would make a triangle of unset corners
        error = Where(property) + ": " + std::to_string(count) + " corner(s); a face needs at least 3";
        return false;
    }
    for (long long i = 0; i < count; ++i) {
        if (!tokens.Next(b, e)) {
            error = Where(property) + ", item " + std::to_string(i) + ": missing (the line has " + std::to_string(values) + " values, the list count is " +
                    std::to_string(count) + ")";
            return false;
        }
        ++values;
        if (!Value(property.item, b, e, item, problem)) {
            error = Where(property) + ", item " + std::to_string(i) + ": " + problem;
            return false;
        }
        if (property.corners && (item < 0 || std::uint64_t(item) >= vertices_)) {
            error = Where(property) + ", item " + std::to_string(i) + ": names vertex " + std::to_string(item) + " of " + std::to_string(vertices_);
            return false;
        }
    }
    return true;
}

bool RecordChecker::Record(const char *begin, const char *end, std::string &error) const
{
    const ElementCheck &element = *element_;
    Tokens tokens{begin, end};
    const std::size_t declared = element.properties.size();
    std::size_t values = 0;
    const char *b, *e;
    long long integer = 0;
    std::string problem;
    for (const PropertyCheck &property : element.properties) {
        if (property.isList) {
            if (!List(property, tokens, values, error)) return false;
            continue;
        }
        if (!tokens.Next(b, e)) {
            if (element.fixedSize)
                error = Where() + ": " + std::to_string(values) + " values where the " + Name(element.element->name) +
                        " has " + std::to_string(declared);
            else
                error = Where(property) + ": missing (the line has " +
                        std::to_string(values) + " values)";
            return false;
        }
        ++values;
        if (!Value(property.item, b, e, integer, problem)) {
            error = Where(property) + ": " + problem;
            return false;
        }
    }
    const std::size_t extra = tokens.CountRest();
    if (extra == 0) return true;
    if (element.fixedSize)
        error = Where() + ": " + std::to_string(values + extra) + " values where the " + Name(element.element->name) +
                " has " + std::to_string(declared);
    else
        error = Where() + ": " + std::to_string(values + extra) + " values where this record has " +
                std::to_string(values) + " (its list counts included)";
    return false;
}

bool RecordChecker::CheckAll(LineReader &lines, std::string &error)
{
    const char *begin = nullptr, *end = nullptr;
    for (const ElementCheck &element : elements_) {
        element_ = &element;
        for (record_ = 0; record_ < element.element->count; ++record_) {
            // Blank lines between records are passed over: they shift no value.
            bool found = false;
            while ((found = lines.Next(begin, end, error)) && IsBlank(begin, end)) {}
            line_ = lines.Line();
            if (!found) {
                if (error.empty())
                    error = "the file ends at line " + std::to_string(line_) + ", after " + std::to_string(record_) +
                            " of " + std::to_string(element.element->count) + " " + Name(element.element->name) +
                            " records";
                else error = Where() + ": " + error;
                return false;
            }
            if (!Record(begin, end, error)) return false;
        }
    }
    // Blank lines may end the file; anything else after the last record is refused.
    while (lines.Next(begin, end, error)) {
        if (!IsBlank(begin, end)) {
            error = "line " + std::to_string(lines.Line()) + ": " + Quote(begin, end) + " after the last record";
            return false;
        }
    }
    if (!error.empty()) error = "line " + std::to_string(lines.Line()) + ": " + error;
    return error.empty();
}

} // namespace

bool CheckAsciiBody(const std::string &path, const PlyHeader &header, std::string &error)
{
    std::unique_ptr<std::FILE, int (*)(std::FILE *)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) {
        error = std::string("cannot open the file: ") + std::strerror(errno);
        return false;
    }
    // The body's first line number: the header's lines are counted.
    std::vector<char> headerBytes(std::size_t(header.bodyOffset));
    if (std::fread(headerBytes.data(), 1, headerBytes.size(), file.get()) != headerBytes.size()) {
        error = "cannot read the header";
        return false;
    }
    const std::uint64_t headerLines = std::uint64_t(std::count(headerBytes.begin(), headerBytes.end(), '\n'));
    LineReader lines(file.get(), headerLines + 1);
    RecordChecker checker(header);
    return checker.CheckAll(lines, error);
}

} // namespace gsresample
