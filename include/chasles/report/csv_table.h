#pragma once
/// @file
/// The CSV tables the program writes (simulate's time series, a sweep's table) and reads back
/// (report, plot). The first line is the header, with no comment line before it: one field per
/// column, the column's name, then, when the column has a unit, one space and the SI unit in
/// brackets ("t [s]", "car_ax [m/s^2]", "theta [rad]"; a pure number such as a quaternion
/// component or a contact mode has no brackets). A field is quoted (a quote doubled) when it
/// holds a comma, a quote or a newline. A reader finds a column by its name: the header field
/// with a trailing " [unit]" removed (CsvHeaderName).

#include <string>
#include <vector>

namespace chasles {

/// How the numbers of a table are written.
enum class CsvPrecision {
  /// The table's usual digits: the shortest text that reads back as the same double for a
  /// run, 12 significant digits for a sweep.
  kDefault,
  /// Every double as printf %.17g: reads back bitwise, whatever the reader.
  kFull,
};

/// Reads "default" or "full" (the --precision option). Throws InputError naming the value.
CsvPrecision ParseCsvPrecision(const std::string& text);

/// The header field of a column: "name [unit]", or "name" when `unit` is empty.
std::string CsvHeaderField(const std::string& name, const std::string& unit);

/// The column name and unit of a header field: "car_ax [m/s^2]" -> {"car_ax", "m/s^2"};
/// "qw" -> {"qw", ""}. Only a trailing " [...]" is a unit.
struct CsvColumnName {
  std::string name, unit;
};
CsvColumnName CsvHeaderName(const std::string& field);

/// The fields of one CSV line (RFC 4180 quoting; a trailing carriage return dropped).
std::vector<std::string> CsvFields(const std::string& line);

/// A table of numbers with its column names and units.
struct CsvTable {
  std::vector<std::string> columns, units;
  std::vector<std::vector<double>> rows;
  /// Per row, why it has no values ("" when it has them); empty when no row can fail (a
  /// sweep's points can). Written as a last column "error"; a failed row's values other than
  /// its parameters are NaN and written as empty fields.
  std::vector<std::string> errors;
};

/// The text of a table: the header (CsvHeaderField of each column; `units` empty: no units),
/// then one line per row. `digits` 0: the shortest text that reads back as the same double;
/// otherwise that many significant digits (%.{digits}g). With `errors`, a last column "error"
/// and a failed row's non-finite values as empty fields. Throws InputError naming the column
/// and row of a value of a row that did not fail that is not finite (`what` names the table,
/// e.g. "the CSV time series").
std::string CsvText(const CsvTable& table, int digits, const std::string& what);

/// Reads a table written by CsvText (`text`, from the file `path` named in errors): the header
/// split into names and units (CsvHeaderName), then rows of numbers. A last column "error" is
/// read into `errors`, and a row with an error reads its empty fields as NaN. Throws
/// InputError naming path:line and the column of a value that is not a number, or a row with
/// a wrong number of values.
CsvTable ReadCsvTable(const std::string& text, const std::string& path);

/// The index of column `name` (the name without its unit). Throws InputError naming `path`,
/// the column and the table's columns when there is none.
size_t CsvColumnIndex(const CsvTable& table, const std::string& name, const std::string& path);

}  // namespace chasles
