// Text of any bytes made safe for a one-line message: the .surfel reader and writer, the plugin
// glue and gsresample quote paths, header lines and command-line values with it. Header-only,
// no Qt, no vcg.
#ifndef GAUSSPHERE_IO_SURFEL_PRINTABLE_TEXT_H
#define GAUSSPHERE_IO_SURFEL_PRINTABLE_TEXT_H

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <string>

namespace surfel_io {

// `text` as printable ASCII of at most `maxLength` characters (at least 8): bytes outside
// 0x20-0x7e become \xNN (lower-case hex); a longer result is cut between whole escapes, its cut
// end marked with "...": the end of the text is kept when `keepEnd` (for paths), its start
// otherwise. Printable text within the length comes back unchanged.
inline std::string printableText(const std::string& text, std::size_t maxLength, bool keepEnd = false) {
  maxLength = std::max<std::size_t>(maxLength, 8);
  const auto escaped = [](unsigned char c) {
    if (c >= 0x20 && c <= 0x7e) return std::string(1, char(c));
    char hex[5];
    std::snprintf(hex, sizeof hex, "\\x%02x", c);
    return std::string(hex);
  };
  std::size_t fullLength = 0;
  for (std::size_t i = 0; i < text.size() && fullLength <= maxLength; ++i) fullLength += escaped(text[i]).size();
  const bool cut = fullLength > maxLength;
  const std::size_t budget = cut ? maxLength - 3 : maxLength;
  // Whole escapes only, from the kept end inwards.
  std::string result;
  for (std::size_t n = 0; n < text.size(); ++n) {
    const std::string piece = escaped(text[keepEnd ? text.size() - 1 - n : n]);
    if (result.size() + piece.size() > budget) break;
    result = keepEnd ? piece + result : result + piece;
  }
  if (cut) result = keepEnd ? "..." + result : result + "...";
  return result;
}

// A path quoted in a message, its end (the file name) kept.
inline std::string quotedPath(const std::string& path) { return "'" + printableText(path, 100, true) + "'"; }

}  // namespace surfel_io

#endif
