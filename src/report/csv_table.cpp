// The CSV tables of the program (chasles/report/csv_table.h).

#include "chasles/report/csv_table.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/report/json_report.h"
#include "report/internal/csv_field.h"

namespace chasles {

CsvPrecision ParseCsvPrecision(const std::string& text) {
  if (text == "default") return CsvPrecision::kDefault;
  if (text == "full") return CsvPrecision::kFull;
  throw InputError(fmt::format(
      "--precision: expected 'default' or 'full' (every double with %.17g), got '{}'", text));
}

std::string CsvHeaderField(const std::string& name, const std::string& unit) {
  return unit.empty() ? name : name + " [" + unit + "]";
}

CsvColumnName CsvHeaderName(const std::string& field) {
  // Name, one space, the unit in brackets: the last " [" opens the unit when the field ends
  // with "]".
  const size_t open = field.rfind(" [");
  if (field.size() < 3 || field.back() != ']' || open == std::string::npos || open == 0) {
    return {field, ""};
  }
  return {field.substr(0, open), field.substr(open + 2, field.size() - open - 3)};
}

std::vector<std::string> CsvFields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        out.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else if (c != '\r') {
      out.back() += c;
    }
  }
  return out;
}

std::string CsvText(const CsvTable& t, int digits, const std::string& what) {
  // Every value of a row that did not fail must be finite; a failed row's values are empty.
  const auto failed = [&](size_t r) { return r < t.errors.size() && !t.errors[r].empty(); };
  std::vector<std::vector<double>> ran;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    if (!failed(r)) ran.push_back(t.rows[r]);
  }
  CheckFiniteTable(t.columns, ran, what);
  std::string out;
  for (size_t i = 0; i < t.columns.size(); ++i) {
    if (i) out += ',';
    const std::string unit = i < t.units.size() ? t.units[i] : "";
    out += internal::CsvField(CsvHeaderField(t.columns[i], unit));
  }
  if (!t.errors.empty()) out += ",error";
  out += '\n';
  for (size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    for (size_t i = 0; i < row.size(); ++i) {
      if (i) out += ',';
      if (!std::isfinite(row[i])) continue;  // only in a failed row (checked above)
      // digits 0: fmt's shortest round-trip text; otherwise %.{digits}g.
      out += digits == 0 ? fmt::format("{}", row[i]) : fmt::format("{:.{}g}", row[i], digits);
    }
    if (!t.errors.empty()) {
      out += ',';
      out += internal::CsvField(r < t.errors.size() ? t.errors[r] : std::string());
    }
    out += '\n';
  }
  return out;
}

CsvTable ReadCsvTable(const std::string& text, const std::string& path) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) throw InputError(fmt::format("{}: empty CSV", path));
  CsvTable t;
  for (const std::string& f : CsvFields(line)) {
    const CsvColumnName n = CsvHeaderName(f);
    t.columns.push_back(n.name);
    t.units.push_back(n.unit);
  }
  // A sweep's last column "error" holds text: why a row has no values.
  const bool has_errors = !t.columns.empty() && t.columns.back() == "error";
  if (has_errors) {
    t.columns.pop_back();
    t.units.pop_back();
  }
  const size_t fields = t.columns.size() + (has_errors ? 1 : 0);
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line == "\r") continue;
    std::vector<std::string> f = CsvFields(line);
    if (f.size() != fields) {
      throw InputError(fmt::format("{}:{}: expected {} values (one per column), got {}", path,
                                   number, fields, f.size()));
    }
    std::string error;
    if (has_errors) {
      error = f.back();
      f.pop_back();
      t.errors.push_back(error);
    }
    std::vector<double> row;
    row.reserve(f.size());
    for (size_t c = 0; c < f.size(); ++c) {
      if (f[c].empty() && !error.empty()) {  // a failed row's missing value
        row.push_back(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      errno = 0;
      char* end = nullptr;
      const double v = std::strtod(f[c].c_str(), &end);
      // A number, finite (an underflow to a subnormal or zero reads as such).
      if (f[c].empty() || *end != '\0' || !std::isfinite(v)) {
        throw InputError(fmt::format("{}:{}: column '{}': expected a number, got '{}'", path,
                                     number, t.columns[c], f[c]));
      }
      row.push_back(v);
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

size_t CsvColumnIndex(const CsvTable& t, const std::string& name, const std::string& path) {
  for (size_t i = 0; i < t.columns.size(); ++i) {
    if (t.columns[i] == name) return i;
  }
  throw InputError(
      fmt::format("{}: no column '{}'; columns: {}", path, name, fmt::join(t.columns, ", ")));
}

}  // namespace chasles
