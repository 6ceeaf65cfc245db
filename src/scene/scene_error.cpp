#include "chasles/scene/scene_error.h"

#include <fmt/format.h>

namespace chasles {

namespace {
std::string Compose(const std::string& file, int line, int column, const std::string& key,
                    const std::string& message) {
  std::string where = file;
  if (line > 0) where += fmt::format(":{}", line);
  if (line > 0 && column > 0) where += fmt::format(":{}", column);
  return key.empty() ? fmt::format("{}: {}", where, message)
                     : fmt::format("{}: {}: {}", where, key, message);
}
}  // namespace

SceneError::SceneError(std::string file, int line, int column, std::string key, std::string message)
    : InputError(Compose(file, line, column, key, message)),
      file_(std::move(file)),
      line_(line),
      column_(column),
      key_(std::move(key)),
      message_(std::move(message)) {}

}  // namespace chasles
