#pragma once
/// @file
/// The browser report (docs/report.md): one self-contained HTML file, the report's data
/// (chasles/report/report_data.h) and the page's script and style embedded. The script is
/// bundled at build time from report/ (three.js, uPlot, esbuild); a build without node has no
/// report, and every --html says so.

#include <string>

#include <nlohmann/json.hpp>

namespace chasles::cli {

/// True when this build embeds the page's script.
bool HaveHtmlReport();

/// Throws InputError naming `option` when this build has no report.
void RequireHtmlReport(const std::string& option);

/// The page: `data` as <script type="application/json" id="chasles-data">, the style and the
/// script. Checks the data (no non-finite number) first.
std::string HtmlReport(const nlohmann::json& data);

/// Says on standard error that the page was written ("Wrote PATH (the browser report)"):
/// standard output may be the command's table or JSON.
void SayWroteHtmlReport(const std::string& path);

}  // namespace chasles::cli
