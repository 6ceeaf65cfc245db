// Drawing a plot with PLplot into memory, its errors turned into InputErrors (plot_render.h).

#include "plot_render.h"

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string_view>

#include <fmt/format.h>
#include <plplot.h>

#include "chasles/error.h"
#include "chasles/files/input_file.h"

namespace chasles::cli {

namespace {

// Series colours (cmap0 entries 2...): distinct on white, as in common plotting palettes.
constexpr int kPalette[][3] = {{31, 119, 180},  {214, 39, 40}, {44, 160, 44},   {255, 127, 14},
                               {148, 103, 189}, {140, 86, 75}, {227, 119, 194}, {127, 127, 127},
                               {188, 189, 34},  {23, 190, 207}};
constexpr int kColours = sizeof(kPalette) / sizeof(kPalette[0]);

/// PLplot reads '#' as the start of an escape sequence; "##" is a literal '#'.
std::string PlText(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '#' ? std::string("##") : std::string(1, c);
  return out;
}

/// The axis range of values, widened when they are all equal (PLplot needs a span), with 3 %
/// margins; every bound finite (a span of values near the largest double is kept in range).
void Range(const std::vector<const std::vector<double>*>& values, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (const auto* v : values) {
    for (double x : *v) {
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
  constexpr double kBig = std::numeric_limits<double>::max();
  if (!(hi > lo)) {
    const double pad = lo == 0.0 ? 1.0 : 0.5 * std::abs(lo);
    lo = std::max(-kBig, lo - pad);
    hi = std::min(kBig, hi + pad);
    return;
  }
  // 0.03 hi - 0.03 lo cannot overflow where hi - lo can.
  const double m = 0.03 * hi - 0.03 * lo;
  lo = std::max(-kBig, lo - m);
  hi = std::min(kBig, hi + m);
}

/// The plot's bytes as PLplot writes them, through a stdio stream (fopencookie) with a cap.
struct Sink {
  std::string bytes;
  bool too_large = false;
  bool closed = false;
};

ssize_t SinkWrite(void* cookie, const char* data, size_t size) {
  auto* s = static_cast<Sink*>(cookie);
  if (s->too_large || s->bytes.size() + size > kMaxPlotBytes) {
    s->too_large = true;
    return -1;
  }
  try {
    s->bytes.append(data, size);
  } catch (const std::bad_alloc&) {
    s->too_large = true;
    return -1;
  }
  return static_cast<ssize_t>(size);
}

int SinkClose(void* cookie) {
  static_cast<Sink*>(cookie)->closed = true;
  return 0;
}

/// Everything PLplot reads, made before PLplot is called: a fatal PLplot error jumps back to
/// DrawGuarded, so no object with a destructor may live in the frames it jumps over.
struct Drawing {
  const PlotSpec* spec = nullptr;
  std::string device, xlabel, ylabel, title;
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  PLINT n = 0;
  std::vector<PLINT> opt, colours, styles, zero, text_colours, symbol_numbers;
  std::vector<PLFLT> widths, scales;
  std::vector<std::string> text;
  std::vector<const char*> text_p, symbols;
};

Drawing Prepare(const PlotSpec& spec) {
  Drawing d;
  d.spec = &spec;
  d.device = spec.png ? "pngcairo" : "svg";
  d.xlabel = PlText(spec.xlabel);
  d.ylabel = PlText(spec.ylabel);
  d.title = PlText(spec.title);
  std::vector<const std::vector<double>*> xs, ys;
  for (const PlotSeries& s : spec.series) {
    xs.push_back(&s.x);
    ys.push_back(&s.y);
  }
  Range(xs, d.x0, d.x1);
  Range(ys, d.y0, d.y1);
  // The legend: one line sample and label per series.
  d.n = static_cast<PLINT>(spec.series.size());
  const auto n = static_cast<size_t>(d.n);
  d.opt.assign(n, PL_LEGEND_LINE);
  d.styles.assign(n, 1);
  d.zero.assign(n, 0);
  d.text_colours.assign(n, 1);
  d.symbol_numbers.assign(n, 0);
  d.widths.assign(n, 2.0);
  d.scales.assign(n, 1.0);
  d.symbols.assign(n, "");
  for (PLINT i = 0; i < d.n; ++i) {
    d.colours.push_back(2 + i % kColours);
    d.text.push_back(PlText(spec.series[static_cast<size_t>(i)].label));
  }
  for (const std::string& t : d.text) d.text_p.push_back(t.c_str());
  return d;
}

// PLplot's fatal errors (plexit) call the exit handler and then exit(): the handler jumps back
// into DrawGuarded instead. Its other errors (plabort) print a message and go on drawing: the
// abort handler keeps the first. PLplot is not reentrant, and neither is this.
std::jmp_buf g_jump;
bool g_armed = false;
char g_message[512];

extern "C" int OnPlplotExit(PLCHAR_VECTOR message) {
  std::snprintf(g_message, sizeof g_message, "%s", message ? message : "");
  if (g_armed) {
    g_armed = false;
    std::longjmp(g_jump, 1);
  }
  return 1;
}

extern "C" void OnPlplotAbort(PLCHAR_VECTOR message) {
  if (g_message[0] == '\0')
    std::snprintf(g_message, sizeof g_message, "%s", message ? message : "");
}

/// Draws `d` into `out`; false when PLplot gave up (its message in g_message).
bool DrawGuarded(const Drawing& d, FILE* out) {
  if (setjmp(g_jump) != 0) return false;
  g_armed = true;
  plsexit(OnPlplotExit);
  plsabort(OnPlplotAbort);
  plsdev(d.device.c_str());
  plsfile(out);
  plspage(0.0, 0.0, 960, 640, 0, 0);
  // cmap0: 0 white background, 1 black axes and text, then the series colours.
  plscmap0n(2 + kColours + 1);
  plscol0(0, 255, 255, 255);
  plscol0(1, 0, 0, 0);
  for (int i = 0; i < kColours; ++i) plscol0(2 + i, kPalette[i][0], kPalette[i][1], kPalette[i][2]);
  plscol0a(2 + kColours, 255, 255, 255, 0.85);  // the legend's background
  plinit();
  plcol0(1);
  // Log axes: PLplot draws log10 of the values with its logarithmic axis labels (axis = 30).
  plenv(d.x0, d.x1, d.y0, d.y1, 0, d.spec->log ? 30 : 0);
  pllab(d.xlabel.c_str(), d.ylabel.c_str(), d.title.c_str());
  for (size_t i = 0; i < d.spec->series.size(); ++i) {
    const PlotSeries& s = d.spec->series[i];
    plcol0(2 + static_cast<int>(i % kColours));
    plwidth(2.0);
    plline(static_cast<PLINT>(s.x.size()), s.x.data(), s.y.data());
  }
  plwidth(1.0);
  PLFLT w = 0, h = 0;
  pllegend(&w, &h, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX,
           PL_POSITION_TOP | PL_POSITION_RIGHT | PL_POSITION_INSIDE, 0.02, 0.02, 0.08, 2 + kColours,
           1, 1, 0, 0, d.n, d.opt.data(), 1.0, 0.8, 2.0, 0.0, d.text_colours.data(),
           d.text_p.data(), nullptr, nullptr, nullptr, nullptr, d.colours.data(), d.styles.data(),
           d.widths.data(), d.zero.data(), d.scales.data(), d.symbol_numbers.data(),
           d.symbols.data());
  plend();
  g_armed = false;
  return true;
}

/// After a fatal error PLplot's stream is half made: end it, so a later plot starts afresh.
void ResetGuarded() {
  if (setjmp(g_jump) != 0) return;
  g_armed = true;
  plend();
  g_armed = false;
}

}  // namespace

void CheckPlotText(const std::string& text, const std::string& what) {
  const size_t bad = FindInvalidUtf8(text);
  if (bad != std::string_view::npos) {
    throw InputError(
        fmt::format("{}: the byte {} (0x{:02X}) is not valid UTF-8; a plot's text "
                    "must be UTF-8",
                    what, bad + 1, static_cast<unsigned char>(text[bad])));
  }
  if (text.size() > kMaxPlotTextBytes) {
    throw InputError(
        fmt::format("{}: {} bytes, more than the {} a plot's title, label or legend "
                    "entry may have; give a shorter one",
                    what, text.size(), kMaxPlotTextBytes));
  }
  for (const char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) {
      throw InputError(
          fmt::format("{}: holds the control character 0x{:02X}; a plot's text is "
                      "one line of printable characters",
                      what, static_cast<unsigned char>(c)));
    }
  }
}

std::string RenderPlot(const PlotSpec& spec) {
  const Drawing d = Prepare(spec);
  Sink sink;
  FILE* out = ::fopencookie(&sink, "w", {nullptr, SinkWrite, nullptr, SinkClose});
  if (out == nullptr) throw std::bad_alloc();
  g_message[0] = '\0';
  const bool drawn = DrawGuarded(d, out);
  if (!drawn) ResetGuarded();
  if (!sink.closed) std::fclose(out);  // PLplot closes the file it wrote when it ends
  if (!drawn || g_message[0] != '\0') {
    throw InputError(fmt::format("the plot could not be drawn: PLplot: {}",
                                 g_message[0] ? g_message : "an error without a message"));
  }
  if (sink.too_large) {
    throw InputError(
        fmt::format("the plot would be larger than {} MiB; plot fewer points (a "
                    "shorter or coarser table)",
                    kMaxPlotBytes >> 20));
  }
  return std::move(sink.bytes);
}

}  // namespace chasles::cli
