#pragma once
/// @file
/// The page's script (report/src bundled by esbuild: three.js, uPlot and the report's own
/// code, one minified IIFE) and its style (uPlot's CSS and the report's), embedded at build
/// time by cmake/embed_report.cmake; empty (size 0) in a build without the report.

#include <cstddef>

namespace chasles::cli {

extern const char kReportScript[];
extern const std::size_t kReportScriptSize;
extern const char kReportStyle[];
extern const std::size_t kReportStyleSize;

}  // namespace chasles::cli
