// Sweeps of a scene's parameters over a grid (chasles/scene/sweep.h).

#include "chasles/scene/sweep.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "chasles/error.h"
#include "chasles/scene/column_units.h"
#include "chasles/scene/expression.h"
#include "chasles/scene/mass_report.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/units.h"
#include "chasles/suggest.h"
#include "scene/internal/study_columns.h"

namespace chasles {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// `text` with the white space around ( ) , - and at the ends removed, and each other run of
/// it made one space: "event( leaves wall, 2 )" reads "event(leaves wall,2)".
std::string Normalized(const std::string& text) {
  const auto special = [](char c) { return c == '(' || c == ')' || c == ',' || c == '-'; };
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    if (!std::isspace(static_cast<unsigned char>(text[i]))) {
      out += text[i];
      continue;
    }
    size_t j = i;
    while (j < text.size() && std::isspace(static_cast<unsigned char>(text[j]))) ++j;
    if (!out.empty() && j < text.size() && !special(out.back()) && !special(text[j])) out += ' ';
    i = j - 1;
  }
  return out;
}

/// The scene's parameter names, in file order.
std::vector<std::string> ParameterNames(const Scene& scene) {
  std::vector<std::string> names;
  for (const auto& [n, q] : scene.parameters) names.push_back(n);
  return names;
}

/// The parameters of point k: the loaded scene's values (what its run used).
std::vector<double> SceneValues(const SweepGrid& grid, const Scene& scene) {
  std::vector<double> v;
  for (const SweepSpec& s : grid.specs) {
    for (const auto& [n, q] : scene.parameters) {
      if (n == s.name) v.push_back(q.value);
    }
  }
  return v;
}

/// One `event(NAME)` or `event(NAME,k)` term (no whitespace).
bool ParseEventTerm(const std::string& t, std::string* name, int* k) {
  if (t.rfind("event(", 0) != 0 || t.back() != ')') return false;
  const std::string inner = t.substr(6, t.size() - 7);
  if (inner.empty() || inner.find_first_of("()") != std::string::npos) return false;
  const auto comma = inner.find(',');
  *name = inner.substr(0, comma);
  *k = 1;
  if (comma != std::string::npos) {
    const std::string count = inner.substr(comma + 1);
    if (count.empty() || count.size() > 9 ||
        !std::all_of(count.begin(), count.end(), [](char c) { return std::isdigit(c); })) {
      return false;
    }
    *k = std::stoi(count);
  }
  return !name->empty() && *k >= 1;
}

}  // namespace

SceneOptions SweepGrid::PointOptions(const SceneOptions& base,
                                     const std::vector<double>& values) const {
  const std::int64_t k = parameters.PointOf(values);
  if (k < 0) throw std::logic_error("SweepGrid::PointOptions: the values are not a grid point");
  SceneOptions o = base;
  const std::vector<int> i = parameters.Indices(k);
  for (size_t j = 0; j < specs.size(); ++j) {
    const SweepSpec& s = specs[j];
    o.parameter_overrides.emplace_back(
        s.name,
        fmt::format("({}) + (({}) - ({})) * {} / {}", s.start, s.stop, s.start, i[j], s.count - 1));
  }
  return o;
}

SweepGrid MakeSweepGrid(const Scene& scene, const std::vector<SweepSpec>& specs,
                        std::int64_t max_points) {
  const std::vector<std::string> known = ParameterNames(scene);
  const SymbolResolver resolver = [&scene](std::string_view name) -> std::optional<Symbol> {
    for (const auto& [n, q] : scene.parameters) {
      if (n == name) return Symbol::Constant(q);
    }
    return std::nullopt;
  };
  SweepGrid grid;
  std::int64_t size = 1;
  for (const SweepSpec& s : specs) {
    const auto fail = [&s](const std::string& why) {
      throw SceneError(s.source, 0, 0, s.key, why);
    };
    const auto p = std::find(known.begin(), known.end(), s.name);
    if (p == known.end()) {
      fail(fmt::format("the scene has no parameter '{}'{}; parameters: {}", s.name,
                       DidYouMean(s.name, known), fmt::join(known, ", ")));
    }
    for (const SweepSpec& other : grid.specs) {
      if (other.name == s.name) fail(fmt::format("parameter '{}' is swept twice", s.name));
    }
    if (s.count < 2) fail(fmt::format("COUNT must be a whole number >= 2, got {}", s.count));
    const Quantity& q = scene.parameters[static_cast<size_t>(p - known.begin())].second;
    double ends[2];
    const std::string* texts[2] = {&s.start, &s.stop};
    for (int e = 0; e < 2; ++e) {
      Quantity v;
      try {
        v = EvaluateQuantity(*texts[e], resolver, [&known] { return known; });
      } catch (const InputError& x) {
        fail(fmt::format("{} '{}' of '{}': {}", e ? "STOP" : "START", *texts[e], s.name, x.what()));
      }
      if (!(v.dim == q.dim)) {
        fail(fmt::format("{} '{}' has dimension {}, but parameter '{}' has {}",
                         e ? "STOP" : "START", *texts[e], v.dim.Formula(), s.name,
                         q.dim.Formula()));
      }
      ends[e] = v.value;
    }
    if (size > max_points / s.count) {
      fail(
          fmt::format("the grid has more points than the limit of {} runs; raise the limit with "
                      "--max-runs N (max_runs= from Python)",
                      max_points));
    }
    size *= s.count;
    grid.specs.push_back(s);
    grid.parameters.names.push_back(s.name);
    grid.parameters.units.push_back(SweepParameterUnit(s, q.dim));
    grid.parameters.start.push_back(ends[0]);
    grid.parameters.stop.push_back(ends[1]);
    grid.parameters.counts.push_back(s.count);
  }
  if (size > max_points) {
    throw SceneError(specs.front().source, 0, 0, specs.front().key,
                     fmt::format("the grid's {} points are more than the limit of {} runs; raise "
                                 "the limit with --max-runs N (max_runs= from Python)",
                                 size, max_points));
  }
  return grid;
}

SweepQuantity ParseSweepQuantity(const std::string& text, const std::string& source,
                                 const std::string& key) {
  SweepQuantity q;
  q.text = Normalized(text);
  const auto fail = [&]() {
    throw SceneError(source, 0, 0, key,
                     fmt::format("expected final(COLUMN), max(COLUMN), min(COLUMN), event(NAME), "
                                 "event(NAME, k), event(NAME2) - event(NAME1) or t_end, got '{}'",
                                 text));
  };
  const std::string& t = q.text;
  if (t == "t_end") return q;
  for (const auto& [prefix, kind] : {std::pair{"final(", SweepQuantity::Kind::kFinal},
                                     std::pair{"max(", SweepQuantity::Kind::kMax},
                                     std::pair{"min(", SweepQuantity::Kind::kMin}}) {
    const std::string p = prefix;
    if (t.rfind(p, 0) == 0) {
      if (t.back() != ')' || t.size() == p.size() + 1) fail();
      q.column = t.substr(p.size(), t.size() - p.size() - 1);
      if (q.column.find_first_of("(),") != std::string::npos) fail();
      q.kind = kind;
      return q;
    }
  }
  // A difference of two event times: split at the '-' outside the parentheses.
  int depth = 0;
  size_t minus = std::string::npos;
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] == '(') ++depth;
    if (t[i] == ')') --depth;
    if (t[i] == '-' && depth == 0) {
      if (minus != std::string::npos) fail();
      minus = i;
    }
  }
  if (minus == std::string::npos) {
    if (!ParseEventTerm(t, &q.event, &q.k)) fail();
    q.kind = SweepQuantity::Kind::kEvent;
    return q;
  }
  if (!ParseEventTerm(t.substr(0, minus), &q.event, &q.k) ||
      !ParseEventTerm(t.substr(minus + 1), &q.event2, &q.k2)) {
    fail();
  }
  q.kind = SweepQuantity::Kind::kEventDifference;
  return q;
}

SceneStudySweep MakeStudySweep(const std::function<Scene(const SceneOptions&)>& load,
                               const SceneOptions& options, const std::vector<SweepSpec>& specs,
                               const std::vector<SweepQuantity>& quantities,
                               const StudySweepOptions& sweep_options, std::int64_t max_points) {
  if (specs.empty()) throw InputError("a sweep needs at least one --sweep");
  if (quantities.empty()) {
    throw SceneError(specs.front().source, 0, 0, "--quantity",
                     "a sweep of simulate needs at least one --quantity, e.g. --quantity "
                     "'final(ball_x)' or --quantity 'event(bottom)'");
  }
  // Everything a point cannot change is checked once, on the scene as written: the grid, the
  // columns and the events the quantities name.
  const Scene base = load(options);
  SceneStudySweep sweep;
  sweep.grid = MakeSweepGrid(base, specs, max_points);
  std::vector<std::string> columns =
      sweep_options.columns.empty() ? base.dynamics.columns : sweep_options.columns;
  std::vector<std::string> event_names;
  for (const SceneEvent& e : base.dynamics.events) event_names.push_back(e.name);
  for (const SweepQuantity& q : quantities) {
    const auto fail = [&](const std::string& why) {
      throw SceneError(specs.front().source, 0, 0, "--quantity", why);
    };
    if (!q.column.empty()) {
      std::string why;
      const std::vector<std::string> expanded = scene_internal::ExpandColumn(base, q.column, &why);
      if (expanded.empty()) fail(fmt::format("'{}': {}", q.text, why));
      if (expanded.size() != 1 || expanded.front() != q.column) {
        fail(fmt::format("'{}': '{}' is a group of columns; name one of them: {}", q.text, q.column,
                         fmt::join(expanded, ", ")));
      }
      columns.push_back(q.column);
      sweep.units.push_back(StudyColumnUnit(base, q.column));
      continue;
    }
    sweep.units.push_back("s");
    for (const std::string* e : {&q.event, &q.event2}) {
      if (e->empty()) continue;
      if (std::find(event_names.begin(), event_names.end(), *e) == event_names.end()) {
        fail(fmt::format(
            "'{}': the scene has no event '{}'{}; events: {}", q.text, *e,
            DidYouMean(*e, event_names),
            event_names.empty() ? "none" : fmt::format("{}", fmt::join(event_names, ", "))));
      }
    }
  }
  // --columns names no point can change: refused here, not at every row.
  SelectColumns(base, columns);
  StudyOptions study = sweep_options.study;
  study.progress = nullptr;
  sweep.point = [load, options, grid = sweep.grid, columns, study,
                 on_run = sweep_options.on_run](const std::vector<double>& values) {
    const auto scene = std::make_shared<Scene>(load(grid.PointOptions(options, values)));
    StudySweepPoint point;
    point.values = SceneValues(grid, *scene);
    try {
      scene->dynamics.columns = SelectColumns(*scene, columns);
      point.definition = MakeStudyDefinition(*scene, study);
    } catch (const InputError& e) {
      point.error = e.what();  // the row keeps the values the scene was read with
      return point;
    }
    if (on_run) {
      point.on_run = [on_run, k = grid.parameters.PointOf(values), scene](const StudyResult& r) {
        on_run(k, *scene, r);
      };
    }
    return point;
  };
  return sweep;
}

std::vector<std::string> MassSweepQuantityNames() {
  return {"mass",
          "volume",
          "surface_area",
          "center_of_mass_x",
          "center_of_mass_y",
          "center_of_mass_z",
          "Ixx",
          "Iyy",
          "Izz",
          "Ixy",
          "Ixz",
          "Iyz",
          "I1",
          "I2",
          "I3",
          "k1",
          "k2",
          "k3",
          "kx",
          "ky",
          "kz"};
}

namespace {

/// Quantity `name` of a body's entry of the mass JSON report (SI units), with its SI unit.
std::pair<double, std::string> MassQuantity(const nlohmann::json& b, const std::string& name) {
  const auto number = [](const nlohmann::json& v) {
    return v.is_number() ? v.get<double>() : kNaN;
  };
  const auto axis = [](char c) { return c == 'x' ? 0 : c == 'y' ? 1 : 2; };
  if (name == "mass") return {number(b.at("mass")), "kg"};
  if (name == "volume") return {number(b.at("volume")), "m^3"};
  if (name == "surface_area") return {number(b.at("surface_area")), "m^2"};
  if (name.rfind("center_of_mass_", 0) == 0) {
    return {number(b.at("center_of_mass").at(axis(name.back()))), "m"};
  }
  if (name.size() == 3 && name[0] == 'I' && std::isalpha(static_cast<unsigned char>(name[1]))) {
    // The central inertia matrix as the report prints it (its "inertia_convention").
    return {number(b.at("inertia_about_center_of_mass").at(axis(name[1])).at(axis(name[2]))),
            "kg*m^2"};
  }
  const int n = name.back() - '1';
  if (name[0] == 'I') return {number(b.at("principal_moments").at(n)), "kg*m^2"};
  if (std::isdigit(static_cast<unsigned char>(name.back()))) {
    return {number(b.at("radii_of_gyration").at("principal_axes").at(n)), "m"};
  }
  return {number(b.at("radii_of_gyration").at("body_axes").at(axis(name.back()))), "m"};
}

}  // namespace

SweepTable MassSweep(const std::function<Scene(const SceneOptions&)>& load,
                     const SceneOptions& options, const std::vector<SweepSpec>& specs,
                     const std::vector<std::string>& quantities, int jobs,
                     const std::function<void(std::int64_t, std::int64_t)>& progress,
                     std::int64_t max_points, const SweepShare& share) {
  if (specs.empty()) throw InputError("a sweep needs at least one --sweep");
  const auto fail = [&](const std::string& why) {
    throw SceneError(specs.front().source, 0, 0, "--quantity", why);
  };
  if (quantities.empty()) {
    fail(fmt::format("a sweep of mass needs at least one --quantity, one of: {}",
                     fmt::join(MassSweepQuantityNames(), ", ")));
  }
  const Scene base = load(options);
  const SweepGrid grid = MakeSweepGrid(base, specs, max_points);
  std::vector<std::string> bodies;
  for (const SceneBody& b : base.bodies) bodies.push_back(b.name);
  const std::vector<std::string> known = MassSweepQuantityNames();
  // Each quantity as (body index, name in the report).
  std::vector<std::pair<size_t, std::string>> what;
  std::vector<std::string> units;
  const nlohmann::json base_report = MassReportJson(base, UnitSystem::Parse("SI"));
  for (const std::string& text : quantities) {
    const std::string q = Normalized(text);
    const auto dot = q.rfind('.');
    std::string body = dot == std::string::npos ? "" : q.substr(0, dot);
    const std::string name = dot == std::string::npos ? q : q.substr(dot + 1);
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      fail(fmt::format("'{}': unknown quantity '{}'{}; quantities: {}", text, name,
                       DidYouMean(name, known), fmt::join(known, ", ")));
    }
    if (body.empty() && bodies.size() != 1) {
      fail(fmt::format("'{}': the scene has {} bodies; name one as BODY.{} (bodies: {})", text,
                       bodies.size(), name, fmt::join(bodies, ", ")));
    }
    if (body.empty()) body = bodies.front();
    const auto b = std::find(bodies.begin(), bodies.end(), body);
    if (b == bodies.end()) {
      fail(fmt::format("'{}': the scene has no body '{}'{}; bodies: {}", text, body,
                       DidYouMean(body, bodies), fmt::join(bodies, ", ")));
    }
    const auto i = static_cast<size_t>(b - bodies.begin());
    what.emplace_back(i, name);
    units.push_back(MassQuantity(base_report.at("bodies").at(i), name).second);
  }
  std::vector<std::string> names;
  for (const std::string& q : quantities) names.push_back(Normalized(q));
  const SweepFunction point = [&](const std::vector<double>& values) {
    SweepRow row;
    row.values = values;
    try {
      const Scene scene = load(grid.PointOptions(options, values));
      row.values = SceneValues(grid, scene);
      const nlohmann::json report = MassReportJson(scene, UnitSystem::Parse("SI"));
      // A quantity the report does not give leaves its own cell empty, with the reason.
      std::vector<std::string> missing;
      for (size_t j = 0; j < what.size(); ++j) {
        const double v = MassQuantity(report.at("bodies").at(what[j].first), what[j].second).first;
        if (!std::isfinite(v)) {
          const nlohmann::json& b = report.at("bodies").at(what[j].first);
          const std::string note = b.value(what[j].second + "_note", std::string());
          missing.push_back(
              fmt::format("{}: not given{}", quantities[j], note.empty() ? "" : " (" + note + ")"));
        }
        row.values.push_back(std::isfinite(v) ? v : kNaN);
      }
      row.error = fmt::format("{}", fmt::join(missing, "; "));
    } catch (const InputError& e) {
      row.values.resize(grid.specs.size());
      row.values.resize(grid.specs.size() + quantities.size(), kNaN);
      row.error = OneLine(e.what());
    }
    return row;
  };
  return RunSweep(grid.parameters, names, units, point, {jobs, progress, share});
}

}  // namespace chasles
