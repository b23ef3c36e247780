#include "strict_parse.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <io_surfel/printable_text.h>

namespace gsresample {

std::string Quoted(const std::string &text) { return "'" + surfel_io::printableText(text, kQuotedTextChars) + "'"; }

namespace {

// strtol and strtod skip leading blanks and stop at an embedded NUL: the text must start with
// a sign or a digit (or '.') and be consumed entirely.
bool StartsLikeNumber(const std::string &text)
{
    if (text.empty()) return false;
    const unsigned char c = static_cast<unsigned char>(text[0]);
    return std::isdigit(c) || c == '+' || c == '-' || c == '.';
}

std::string NumberText(double x)
{
    if (std::isinf(x)) return x > 0 ? "infinity" : "-infinity";
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

} // namespace

bool ParseInt(const std::string &text, int min, int max, int &value, std::string &error)
{
    const std::string range = "an integer between " + std::to_string(min) + " and " + std::to_string(max);
    if (!StartsLikeNumber(text) || text[0] == '.') {
        error = "expected " + range + ", got " + Quoted(text);
        return false;
    }
    errno = 0;
    char *end = nullptr;
    const long long parsed = std::strtoll(text.c_str(), &end, 10);
    if (end != text.c_str() + text.size() || end == text.c_str()) {
        error = "expected " + range + ", got " + Quoted(text);
        return false;
    }
    if (errno == ERANGE || parsed < min || parsed > max) {
        error = "expected " + range + ", got " + Quoted(text) + " (out of range)";
        return false;
    }
    value = int(parsed);
    return true;
}

bool ParseDouble(const std::string &text, double min, double max, double &value, std::string &error)
{
    std::string range;
    if (std::isinf(max)) range = "a number of at least " + NumberText(min);
    else if (std::isinf(min)) range = "a number of at most " + NumberText(max);
    else range = "a number between " + NumberText(min) + " and " + NumberText(max);
    if (std::isinf(min) && std::isinf(max)) range = "a finite number";
    if (!StartsLikeNumber(text)) {
        error = "expected " + range + ", got " + Quoted(text);
        return false;
    }
    errno = 0;
    char *end = nullptr;
    const double parsed = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || end == text.c_str()) {
        error = "expected " + range + ", got " + Quoted(text);
        return false;
    }
    if (errno == ERANGE || !std::isfinite(parsed) || parsed < min || parsed > max) {
        error = "expected " + range + ", got " + Quoted(text) + " (out of range)";
        return false;
    }
    value = parsed;
    return true;
}

bool ParseChoice(const std::string &text, const std::vector<std::string> &choices, int &index, std::string &error)
{
    for (std::size_t i = 0; i < choices.size(); ++i) {
        if (text == choices[i]) {
            index = int(i);
            return true;
        }
    }
    std::string accepted;
    for (std::size_t i = 0; i < choices.size(); ++i) accepted += (i ? "|" : "") + choices[i];
    error = "expected one of " + accepted + ", got " + Quoted(text);
    return false;
}

} // namespace gsresample
