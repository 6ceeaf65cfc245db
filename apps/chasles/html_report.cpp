#include "html_report.h"

#include <cstdio>
#include <string_view>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/report/json_report.h"
#include "report_bundle.h"

namespace chasles::cli {

namespace {

/// `text` with every "</" written "<\/": inside a <script> element the sequence "</script"
/// would end it, and "<\/" means "</" both in JSON strings and in JavaScript strings, regular
/// expressions and comments.
std::string EscapeScript(std::string_view text) {
  std::string out;
  out.reserve(text.size() + 64);
  for (size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') out += '\\';
  }
  return out;
}

std::string HtmlEscape(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

bool HaveHtmlReport() {
  return kReportScriptSize > 0;
}

void RequireHtmlReport(const std::string& option) {
  if (HaveHtmlReport()) return;
  throw InputError(fmt::format(
      "{}: this build of chasles has no browser report (it was built without node and the "
      "packages of report/: run scripts/setup.sh and build again; docs/report.md)",
      option));
}

std::string HtmlReport(const nlohmann::json& data) {
  RequireHtmlReport("--html");
  const std::string json = DumpJson(data, "the report data");
  const std::string title = data.value("title", std::string()).empty()
                                ? data.value("scene", std::string("chasles report"))
                                : data.value("title", std::string());
  std::string out;
  out.reserve(json.size() + kReportScriptSize + kReportStyleSize + 1024);
  out += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  out += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  out += "<meta name=\"generator\" content=\"chasles\">\n";
  out += fmt::format("<title>{} - chasles report</title>\n", HtmlEscape(title));
  out += "<style>\n";
  out += std::string_view(kReportStyle, kReportStyleSize);
  out += "\n</style>\n</head>\n<body>\n";
  out += "<script type=\"application/json\" id=\"chasles-data\">";
  out += EscapeScript(json);
  out += "</script>\n<script>\n";
  out += EscapeScript(std::string_view(kReportScript, kReportScriptSize));
  out += "\n</script>\n</body>\n</html>\n";
  return out;
}

void SayWroteHtmlReport(const std::string& path) {
  if (!path.empty()) std::fprintf(stderr, "Wrote %s (the browser report)\n", path.c_str());
}

}  // namespace chasles::cli
