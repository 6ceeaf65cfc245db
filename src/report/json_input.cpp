// A summary read back as JSON, with a cap on its nesting (chasles/report/json_input.h).

#include "chasles/report/json_input.h"

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

nlohmann::json ParseJsonText(const std::string& text, const std::string& path) {
  // The parser itself keeps its nesting on the heap; the cap protects what walks and copies
  // the values afterwards (recursively).
  const nlohmann::json::parser_callback_t depth_cap =
      [&path](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
        if (depth > kMaxJsonDepth) {
          throw InputError(fmt::format(
              "{}: arrays and objects are nested deeper than {} levels; a chasles summary is "
              "nested at most 5 deep (is this the file the program wrote?)",
              path, kMaxJsonDepth));
        }
        return true;
      };
  try {
    return nlohmann::json::parse(text, depth_cap);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(fmt::format("{}: not JSON: {}", path, e.what()));
  } catch (const nlohmann::json::out_of_range& e) {
    // A number past a double's range (1e99999): the parser's error 406, not a parse_error.
    throw InputError(fmt::format("{}: not a chasles summary: {}", path, e.what()));
  }
}

}  // namespace chasles
