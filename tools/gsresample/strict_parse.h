// Strict parsing of command-line values: the whole text must be the value (no leading blanks,
// no trailing junk), and it must lie in the stated range. On failure the functions leave
// `value` unchanged and set `error` to one printable line that names the accepted range and
// quotes at most a few dozen characters of the text; callers prefix the option's name.
#ifndef GSRESAMPLE_STRICT_PARSE_H
#define GSRESAMPLE_STRICT_PARSE_H

#include <cstddef>
#include <string>
#include <vector>

namespace gsresample {

/// `text` in single quotes, escaped and cut as these functions quote it in their errors
/// (surfel_io::printableText): within the quotes at most kQuotedTextChars characters, 40 of
/// the text and the "..." of a cut.
constexpr std::size_t kQuotedTextChars = 43;
std::string Quoted(const std::string &text);

/// A decimal integer in [min, max], optionally signed.
bool ParseInt(const std::string &text, int min, int max, int &value, std::string &error);

/// A finite decimal number in [min, max]; min and max may be infinite.
bool ParseDouble(const std::string &text, double min, double max, double &value, std::string &error);

/// One of `choices`, spelled exactly; `index` receives its position.
bool ParseChoice(const std::string &text, const std::vector<std::string> &choices, int &index, std::string &error);

} // namespace gsresample

#endif
