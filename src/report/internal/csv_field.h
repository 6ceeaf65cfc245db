#pragma once
// A CSV field as the report layer's CSV writers write it.

#include <string>

namespace chasles::internal {

/// `text` as it is, or quoted (a quote doubled) when it holds a comma, a quote or a newline
/// (RFC 4180), so that a reader splits the line where the writer meant.
inline std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string q = "\"";
  for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace chasles::internal
