#pragma once
/// @file
/// The error a scene file gives: where (file, line, column), which key, and what was expected.

#include <string>

#include "chasles/error.h"

namespace chasles {

/// Bad input in a scene file. what() reads "FILE:LINE:COL: KEY: MESSAGE", the form compilers
/// use, so editors can jump to it. Line and column are 1-based; 0 means unknown.
class SceneError : public InputError {
 public:
  SceneError(std::string file, int line, int column, std::string key, std::string message);

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int column() const { return column_; }
  /// Path of the offending key, e.g. "bodies[0].parts[1].radius"; empty for the whole file.
  const std::string& key() const { return key_; }
  /// The message without the location.
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_;
  int column_;
  std::string key_;
  std::string message_;
};

}  // namespace chasles
