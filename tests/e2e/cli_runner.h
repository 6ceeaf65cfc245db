#pragma once
/// @file
/// Runs the chasles program as a user would and captures what it prints.

#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include "test_paths.h"

namespace chasles::test {

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string SourcePath(const std::string& relative) {
  return std::string(chasles::test::SourceDir()) + "/" + relative;
}

/// `text` in single quotes for the shell (paths here have no quotes of their own).
inline std::string Quote(const std::string& text) {
  std::string quoted;
  quoted.reserve(text.size() + 2);
  quoted.push_back('\'');
  quoted.append(text);
  quoted.push_back('\'');
  return quoted;
}

/// Runs `chasles ARGS` (ARGS already shell-quoted by the caller).
inline CliResult RunCli(const std::string& args) {
  const std::filesystem::path err_file = std::filesystem::temp_directory_path() /
                                         ("chasles_e2e_err_" + std::to_string(::getpid()) + ".txt");
  const std::string command =
      std::string("'") + chasles::test::CliPath() + "' " + args + " 2>'" + err_file.string() + "'";
  CliResult r;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    r.out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err_file);
  std::stringstream ss;
  ss << in.rdbuf();
  r.err = ss.str();
  std::filesystem::remove(err_file);
  return r;
}

/// A 3x3 matrix from a JSON report ([[row], [row], [row]]).
inline Eigen::Matrix3d ToMat(const nlohmann::json& j) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) m(i, k) = j.at(i).at(k).get<double>();
  }
  return m;
}

/// A 3-vector from a JSON report.
inline Eigen::Vector3d ToVec(const nlohmann::json& j) {
  return Eigen::Vector3d(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>());
}

/// A column's name from its CSV header field: the field without a trailing " [unit]" (the
/// header is name, one space, the SI unit in brackets: "t [s]"; no brackets for a pure number).
inline std::string CsvColumnName(const std::string& field) {
  const size_t open = field.rfind(" [");
  if (field.empty() || field.back() != ']' || open == std::string::npos) return field;
  return field.substr(0, open);
}

/// A CSV file written by `chasles simulate`, as columns by name (units dropped).
inline std::map<std::string, std::vector<double>> ReadCsv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');) names.push_back(CsvColumnName(cell));
  std::map<std::string, std::vector<double>> cols;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    size_t i = 0;
    for (std::string cell; std::getline(row, cell, ','); ++i) {
      cols[names.at(i)].push_back(std::stod(cell));
    }
  }
  return cols;
}

/// Runs `chasles mass FILE EXTRA --format json --units SI` and parses the report.
inline nlohmann::json MassJson(const std::string& example, const std::string& extra = "") {
  const CliResult r =
      RunCli("mass '" + SourcePath(example) + "' --format json --units SI " + extra);
  if (r.exit_code != 0) {
    throw std::runtime_error("chasles mass " + example + " failed (" + std::to_string(r.exit_code) +
                             "): " + r.err);
  }
  return nlohmann::json::parse(r.out);
}

/// The scratch folders a test program made, removed when it ends.
class ScratchFolders {
 public:
  ScratchFolders() = default;
  ScratchFolders(const ScratchFolders&) = delete;
  ScratchFolders& operator=(const ScratchFolders&) = delete;
  ~ScratchFolders() {
    for (const std::filesystem::path& dir : dirs_) {
      std::error_code ec;  // a folder a test removed itself is no error
      std::filesystem::remove_all(dir, ec);
    }
  }
  void Add(const std::filesystem::path& dir) {
    if (std::find(dirs_.begin(), dirs_.end(), dir) == dirs_.end()) dirs_.push_back(dir);
  }

 private:
  std::vector<std::filesystem::path> dirs_;
};

/// A scratch folder for one test program's output files: the system's temporary folder,
/// named by `tag` and the process id so parallel test programs do not share it; removed with
/// its contents when the program ends.
inline std::filesystem::path OutDir(const std::string& tag) {
  static ScratchFolders made;
  const auto dir = std::filesystem::temp_directory_path() /
                   ("chasles_" + tag + "_e2e_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  made.Add(dir);
  return dir;
}

/// Runs `chasles simulate SCENE --format json --out DIR EXTRA` (SCENE a path) and parses the
/// JSON summary; a failed run throws, which fails the test.
inline nlohmann::json SimulateJson(const std::string& scene, const std::filesystem::path& out,
                                   const std::string& extra = "") {
  const CliResult r =
      RunCli("simulate '" + scene + "' --format json --out '" + out.string() + "' " + extra);
  if (r.exit_code != 0) {
    throw std::runtime_error("chasles simulate " + scene + " failed (" +
                             std::to_string(r.exit_code) + "): " + r.err);
  }
  return nlohmann::json::parse(r.out);
}

// Largest |x| of a column.
inline double Scale(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s = std::max(s, std::abs(x));
  return s;
}

// Column `a` equals `sign` times column `b` row by row, to `tol` of the columns' scale.
inline void ExpectSameColumn(const std::vector<double>& a, const std::vector<double>& b,
                             double sign, double tol, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  const double scale = std::max(Scale(a), Scale(b));
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i], sign * b[i], tol * scale) << what << " at row " << i;
  }
}

}  // namespace chasles::test
