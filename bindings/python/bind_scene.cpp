// Scenes: loading with overrides, mass properties, the instantaneous solve, the run
// (RunStudy) and sweeps; a study of a Model built in Python, and a sweep of a Python function
// of the parameters (no scene file).

#include <cmath>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "bindings.h"
#include "chasles/analysis/study.h"
#include "chasles/analysis/sweep.h"
#include "chasles/report/json_report.h"
#include "chasles/report/mass_text.h"
#include "chasles/report/result_names.h"
#include "chasles/report/simulation_report.h"
#include "chasles/report/simulation_text.h"
#include "chasles/report/solve_json.h"
#include "chasles/report/solve_text.h"
#include "chasles/scene/column_units.h"
#include "chasles/scene/mesh_file.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/solve.h"
#include "chasles/scene/study.h"
#include "chasles/scene/sweep.h"

// A read-only field; without a doc of its own it points at the C++ field, documented in its
// header (chasles/scene/study.h, solve.h, scene.h, analysis/certificate.h).
#define RO(cls, field, doc) \
  .def_readonly(#field, &cls::field, *doc ? doc : "chasles::" #cls "::" #field " (C++ header)")

namespace chasles::python {

namespace {

SceneOptions OptionsFrom(const py::object& set, size_t max_scene_bytes) {
  SceneOptions o;
  o.max_scene_bytes = max_scene_bytes;
  if (set.is_none()) return o;
  for (auto item : set.cast<py::dict>()) {
    o.parameter_overrides.emplace_back(py::str(item.first), py::str(item.second));
  }
  return o;
}

PyScene LoadFile(const std::string& path, const py::object& set, size_t max_bytes) {
  PyScene s;
  s.path = path;
  s.options = OptionsFrom(set, max_bytes);
  py::gil_scoped_release release;
  s.scene = s.Load(s.options);
  return s;
}

PyScene LoadText(const std::string& text, const py::object& set, const std::string& name,
                 size_t max_bytes) {
  PyScene s;
  s.text = text;
  s.name = name;
  s.options = OptionsFrom(set, max_bytes);
  py::gil_scoped_release release;
  s.scene = s.Load(s.options);
  return s;
}

void BindSceneClasses(py::module_& m) {
  py::class_<ScenePart>(m, "ScenePart", "One part of a scene body.") RO(ScenePart, name, "")
      RO(ScenePart, shape, "Shape keyword") RO(ScenePart, subtractive, "A hole or cut-out")
          RO(ScenePart, mass_source, "material name, 'density', 'field' or 'mass'")
              RO(ScenePart, density, "[kg/m^3] or NaN")
                  RO(ScenePart, mass_properties, "In the body frame") RO(ScenePart, notes, "")
                      RO(ScenePart, line, "Line in the scene file");
  py::class_<SceneBody>(m, "SceneBody", "A body of a scene: the sum of its parts.")
      RO(SceneBody, name, "") RO(SceneBody, parts, "")
          RO(SceneBody, mass_properties, "Mass, centre of mass and inertia, in the body frame")
              .def_property_readonly(
                  "points",
                  [](const SceneBody& b) {
                    py::dict d;
                    for (const ScenePoint& p : b.points) d[py::str(p.name)] = py::cast(p.p_BoP_B);
                    return d;
                  },
                  "Named points of the body: name -> position from Bo in B [m]");
  py::class_<PyScene>(m, "Scene",
                      "A scene as read from a scene file (SI). Load with load_scene or "
                      "load_scene_string.")
      .def_property_readonly(
          "file", [](const PyScene& s) { return s.scene.file; },
          "File name as given (or the name given to load_scene_string)")
      .def_property_readonly(
          "title", [](const PyScene& s) { return s.scene.title; }, "Title")
      .def_property_readonly(
          "description", [](const PyScene& s) { return s.scene.description; }, "Description")
      .def_property_readonly(
          "units", [](const PyScene& s) { return s.scene.units; },
          "The scene's unit choice (key `units`)")
      .def_property_readonly(
          "planar", [](const PyScene& s) { return s.scene.planar; },
          "True for a planar scene (x-y plane)")
      .def_property_readonly(
          "bodies", [](const PyScene& s) { return s.scene.bodies; },
          "The bodies (SceneBody), in the file's order")
      .def_property_readonly(
          "warnings", [](const PyScene& s) { return s.scene.warnings; },
          "Things to know that are not errors")
      .def_property_readonly(
          "parameters",
          [](const PyScene& s) {
            py::dict d;
            for (const auto& [n, q] : s.scene.parameters) d[py::str(n)] = q.value;
            return d;
          },
          "name -> SI value, in the file's order")
      .def(
          "mass_properties",
          [](const PyScene& s) {
            py::dict d;
            for (const SceneBody& b : s.scene.bodies) d[py::str(b.name)] = b.mass_properties;
            return d;
          },
          "body name -> MassProperties (what `chasles mass` reports)")
      .def(
          "point",
          [](const PyScene& s, const std::string& text) {
            return ReadPointOption(s.scene, text, "point");
          },
          py::arg("text"),
          "A point written as in the scene ('[0, 0, 0.5 m]'), in the scene's units [m]");
  m.def("load_scene", &LoadFile, py::arg("path"), py::arg("set") = py::none(),
        py::arg("max_scene_bytes") = kDefaultMaxSceneBytes,
        "Reads a scene file. `set` overrides parameters like the command line's --set: "
        "{'theta': '30 deg'} (values are expressions with units; a bare number is a plain number). "
        "Raises SceneError with file, line, column and key.");
  m.def("load_scene_string", &LoadText, py::arg("text"), py::arg("set") = py::none(),
        py::arg("name") = "<string>", py::arg("max_scene_bytes") = kDefaultMaxSceneBytes,
        "Reads a scene from text; `name` stands for the file in errors.");
  m.def(
      "load_mesh_scene",
      [](const std::string& path, const std::string& unit, const std::string& density,
         const std::string& material, const std::string& mass, const std::string& mode,
         const std::string& areal_density, const std::string& thickness) {
        PyScene s;
        s.path = path;
        s.scene = LoadMeshAsScene(path, MeshCommandOptions{unit, mode, density, material, mass,
                                                           areal_density, thickness});
        return s;
      },
      py::arg("path"), py::kw_only(), py::arg("unit"), py::arg("density") = "",
      py::arg("material") = "", py::arg("mass") = "", py::arg("mode") = "",
      py::arg("areal_density") = "", py::arg("thickness") = "",
      "A one-body scene made of a mesh file, options written as on the command line of "
      "`chasles mass part.stl --unit mm --density 7850` ('7850 kg/m^3', 'steel', ...).");
  m.def(
      "study_column_units",
      [](const PyScene& s, const std::vector<std::string>& columns) {
        return StudyColumnUnits(s.scene, columns);
      },
      py::arg("scene"), py::arg("columns"), "SI unit of each run column of the scene.");
}

void BindCertificate(py::module_& m) {
  py::class_<CheckResult>(m, "CheckResult", "One check of a run's or solve's own answer.")
      RO(CheckResult, name, "") RO(CheckResult, description, "") RO(CheckResult, unit, "")
          RO(CheckResult, count, "Values checked (0: did not apply)")
              RO(CheckResult, worst, "The worst value") RO(CheckResult, tolerance, "")
                  RO(CheckResult, where, "") RO(CheckResult, t, "")
                      .def_property_readonly("passed", &CheckResult::passed);
  py::class_<Certificate>(m, "Certificate", "The checks of an answer (analysis/certificate.h).")
      RO(Certificate, checks, "")
          .def_property_readonly("passed", &Certificate::passed)
          .def("failure_messages", &Certificate::FailureMessages, "One sentence per failed check");
}

/// Sweeps of solve, simulate and mass, and their table.
void BindSweeps(py::module_& m) {
  py::class_<SweepTable>(m, "SweepTable", "A sweep's table (SI).") RO(SweepTable, parameter, "") RO(
      SweepTable, columns, "") RO(SweepTable, units, "") RO(SweepTable, warnings, "") RO(SweepTable,
                                                                                         failed, "")
      .def_property_readonly(
          "data", [](const SweepTable& t) { return TableArray(t.rows, t.columns.size()); })
      .def_readonly("parameters", &SweepTable::parameters, "A grid's parameter names")
      .def_readonly(
          "errors", &SweepTable::errors,
          "Per row why a value is missing (NaN): its run failed, or a quantity could not be had "
          "('' when every value is there); empty when no row can fail")
      .def(
          "to_json", [](const SweepTable& t) { return DumpJson(SweepJson(t), "the sweep table"); },
          "The table as `chasles solve --sweep ... --format json` prints it")
      .def(
          "to_csv",
          [](const SweepTable& t, bool full_precision) {
            return SweepCsv(t, full_precision ? CsvPrecision::kFull : CsvPrecision::kDefault);
          },
          py::arg("full_precision") = false,
          "The table as `chasles solve --sweep ...` prints it (full_precision: "
          "--full-precision, every value %.17g)");
  m.def(
      "_sweep",
      [](const PyScene& s, const std::string& name, const std::string& start,
         const std::string& stop, int count) {
        SweepSpec spec;
        spec.name = name;
        spec.start = start;
        spec.stop = stop;
        spec.count = count;
        py::gil_scoped_release release;
        const auto load = [&s](const SceneOptions& o) { return s.Load(o); };
        const std::string unit = SolveSweepUnit(load, s.options, spec);
        return SolveSweep(spec.name, unit, spec.count,
                          [&](int k) { return MakeSolveSweepPoint(load, s.options, spec, k); });
      },
      py::arg("scene"), py::arg("parameter"), py::arg("start"), py::arg("stop"), py::arg("count"));
  m.def(
      "_simulate_sweep",
      [](const PyScene& s, const std::vector<std::string>& sweeps,
         const std::vector<std::string>& quantities, double until, int jobs,
         std::int64_t max_runs) {
        std::vector<SweepSpec> specs;
        for (const std::string& t : sweeps) specs.push_back(ParseSweep(t));
        std::vector<SweepQuantity> qs;
        for (const std::string& q : quantities)
          qs.push_back(ParseSweepQuantity(q, "python", "quantities"));
        StudySweepOptions options;
        if (!std::isnan(until)) options.study.until = until;
        py::gil_scoped_release release;
        const SceneStudySweep sweep =
            MakeStudySweep([&s](const SceneOptions& o) { return s.Load(o); }, s.options, specs, qs,
                           options, max_runs);
        SweepRunOptions run_options;
        run_options.jobs = jobs;
        return SimulateSweep(sweep.grid.parameters, qs, sweep.units, sweep.point, run_options);
      },
      py::arg("scene"), py::arg("sweeps"), py::arg("quantities"), py::arg("until"), py::arg("jobs"),
      py::arg("max_runs"));
  m.def(
      "_mass_sweep",
      [](const PyScene& s, const std::vector<std::string>& sweeps,
         const std::vector<std::string>& quantities, int jobs, std::int64_t max_runs) {
        std::vector<SweepSpec> specs;
        for (const std::string& t : sweeps) specs.push_back(ParseSweep(t));
        py::gil_scoped_release release;
        return MassSweep([&s](const SceneOptions& o) { return s.Load(o); }, s.options, specs,
                         quantities, jobs, {}, max_runs);
      },
      py::arg("scene"), py::arg("sweeps"), py::arg("quantities"), py::arg("jobs"),
      py::arg("max_runs"));
  m.def(
      "_run_sweep",
      [](const std::vector<std::string>& names, const std::vector<std::string>& units,
         const std::vector<double>& start, const std::vector<double>& stop,
         const std::vector<int>& counts, const std::vector<std::string>& quantities,
         const std::vector<std::string>& quantity_units, const py::function& function, int jobs,
         std::int64_t max_points, const py::object& input_error) {
        const ParameterGrid grid{names, units, start, stop, counts};
        CheckParameterGrid(grid, max_points);
        // Each point calls the Python function with the GIL held; its chasles.InputError (a bad
        // value at that point) fails that row alone, any other exception the sweep.
        const SweepFunction point = [&](const std::vector<double>& values) {
          py::gil_scoped_acquire acquire;
          py::object out;
          try {
            out = function(*py::cast(values));
          } catch (py::error_already_set& e) {
            if (e.matches(input_error)) throw InputError(py::str(e.value()).cast<std::string>());
            throw;
          }
          SweepRow row{values, ""};
          const auto got = out.cast<std::vector<double>>();
          if (got.size() != quantities.size()) {
            throw UsageError("the sweep's function returned " + std::to_string(got.size()) +
                             " values for " + std::to_string(quantities.size()) + " quantities");
          }
          row.values.insert(row.values.end(), got.begin(), got.end());
          return row;
        };
        SweepRunOptions options;
        options.jobs = jobs;
        py::gil_scoped_release release;
        return RunSweep(grid, quantities, quantity_units, point, options);
      },
      py::arg("names"), py::arg("units"), py::arg("start"), py::arg("stop"), py::arg("counts"),
      py::arg("quantities"), py::arg("quantity_units"), py::arg("function"), py::arg("jobs"),
      py::arg("max_points"), py::arg("input_error"));
  m.def(
      "parse_sweep",
      [](const std::string& text) {
        const SweepSpec s = ParseSweep(text);
        return py::make_tuple(s.name, s.start, s.stop, s.count);
      },
      py::arg("text"), "NAME=START:STOP:COUNT -> (name, start, stop, count)");
}

void BindSolve(py::module_& m) {
  py::class_<PointMotionReport>(m, "PointMotion",
                                "A named body point at the solved state (in W, SI).")
      RO(PointMotionReport, name, "")
          .def_readonly("position", &PointMotionReport::p_WP, "[m]")
          .def_readonly("velocity", &PointMotionReport::v_WP_W, "v_cm + w x r [m/s]")
          .def_readonly("acceleration", &PointMotionReport::a_WP_W,
                        "a_cm + alpha x r + w x (w x r) [m/s^2]");
  py::class_<BodyMotionReport>(m, "Motion", "Kinetic energy and momenta of a body (or all).")
      RO(BodyMotionReport, name, "") RO(BodyMotionReport, T_trans, "[J]")
          RO(BodyMotionReport, T_rot, "[J]") RO(BodyMotionReport, P, "Linear momentum [kg*m/s]")
              RO(BodyMotionReport, H_cm, "Angular momentum about the centre of mass [kg*m^2/s]") RO(
                  BodyMotionReport, H_O, "Angular momentum about the origin [kg*m^2/s]")
                  .def_readonly("Hdot_cm", &BodyMotionReport::Hdot_cm,
                                "dH/dt about the centre of mass (I alpha + w x I w) [N*m]")
                  .def_readonly("Hdot_O", &BodyMotionReport::Hdot_O, "dH/dt about the origin [N*m]")
                  .def_readonly("angular_velocity", &BodyMotionReport::w_WB_W,
                                "In W [rad/s] (bodies only)")
                  .def_readonly("velocity", &BodyMotionReport::v_WBcm_W,
                                "Of the centre of mass [m/s] (bodies only)")
                  .def_readonly("points", &BodyMotionReport::points,
                                "The body's named points (bodies only)")
                  .def_property_readonly(
                      "T", [](const BodyMotionReport& x) { return x.T_trans + x.T_rot; },
                      "Kinetic energy [J]");
  py::class_<ContactPointReport>(m, "ContactReport", "A contact point at the solved state.")
      RO(ContactPointReport, point, "") RO(ContactPointReport, contact, "") RO(
          ContactPointReport, mu_s, "") RO(ContactPointReport, mu_k, "")
          .def_property_readonly("mode", [](const ContactPointReport& c) { return c.out.mode; })
          .def_property_readonly("regime", &ContactPointReport::Regime,
                                 "'rolls', 'rolling held', 'sticks', 'slides' or 'separated'")
          .def_property_readonly("rolling_held",
                                 [](const ContactPointReport& c) { return c.out.rolling_held; })
          .def_property_readonly(
              "rolling_moment", [](const ContactPointReport& c) { return c.out.rolling_moment_W; },
              "Rolling-resistance moment on the body, in W [N*m]")
          .def_property_readonly("normal_force",
                                 [](const ContactPointReport& c) { return c.out.normal_force; })
          .def_property_readonly("friction",
                                 [](const ContactPointReport& c) { return c.out.friction_force_W; })
          .def_property_readonly("slip_velocity",
                                 [](const ContactPointReport& c) { return c.out.slip_velocity_W; })
          .def_property_readonly("gap", [](const ContactPointReport& c) { return c.out.gap; })
          .def_property_readonly("point_W", [](const ContactPointReport& c) { return c.out.p_WC; })
          .def_property_readonly("normal_W", [](const ContactPointReport& c) { return c.out.n_W; })
          .def_property_readonly("friction_needed", &ContactPointReport::FrictionRatio,
                                 "|f|/N (sticking: compare with mu_s)");
  // dynamic_attr: solve() keeps the scene beside its solution, for text().
  py::class_<SolveReport>(m, "Solution", "What `chasles solve` reports for a scene.",
                          py::dynamic_attr())
      .def_property_readonly("t", [](const SolveReport& s) { return s.solution.t; })
      .def_property_readonly("bodies", [](const SolveReport& s) { return s.solution.bodies; })
      .def_property_readonly("reactions", [](const SolveReport& s) { return s.solution.reactions; })
          RO(SolveReport, mu_s, "mu_s of each reaction (NaN unless rolling with mu_s)")
              RO(SolveReport, motion, "Per body") RO(SolveReport, total, "All bodies")
                  RO(SolveReport, planar, "") RO(SolveReport, contacts, "")
                      RO(SolveReport, certificate, "")
      .def_property_readonly("rank", [](const SolveReport& s) { return s.solution.rank; })
      .def_property_readonly("num_rows", [](const SolveReport& s) { return s.solution.num_rows; })
      .def_property_readonly(
          "warnings",
          [](const SolveReport& s) {
            std::vector<std::string> w = s.solution.warnings;
            for (const std::string& f : s.certificate.FailureMessages()) w.push_back(f);
            return w;
          },
          "Warnings and failed checks")
      .def(
          "to_json",
          [](const SolveReport& s) { return DumpJson(SolveJson(s), "the solve report"); },
          "The JSON report, as `chasles solve --format json` prints it")
      .def("_row", [](const SolveReport& s) {
        std::vector<std::string> names, units;
        std::vector<double> values;
        SolutionTableRow(s, &names, &units, &values);
        return py::make_tuple(names, units, values);
      });
  m.def(
      "_solve_text",
      [](const PyScene& s, const SolveReport& solution, const std::string& units) {
        TextOptions options;
        options.units = units;
        return SolveText(s.scene, solution, options);
      },
      py::arg("scene"), py::arg("solution"), py::arg("units"));
  m.def(
      "_solve",
      [](const PyScene& s) {
        py::gil_scoped_release release;
        return SolveAtState(MakeSolveDefinition(s.scene));
      },
      py::arg("scene"));
  BindSweeps(m);
}

void BindStudyParts(py::module_& m) {
  py::class_<StudyBodyState>(m, "StudyBody", "Motion of one body at an instant.")
      RO(StudyBodyState, name, "") RO(StudyBodyState, mass, "[kg]")
          .def_readonly("position", &StudyBodyState::p_WBcm, "Centre of mass in W [m]")
          .def_readonly("origin", &StudyBodyState::p_WBo, "Frame origin in W [m]")
          .def_property_readonly("quaternion",
                                 [](const StudyBodyState& b) { return QuatArray(b.q_WB); })
          .def_readonly("velocity", &StudyBodyState::v_WBcm_W, "[m/s]")
          .def_readonly("angular_velocity", &StudyBodyState::w_WB_W, "In W [rad/s]")
          .def_readonly("angular_velocity_body", &StudyBodyState::w_WB_B, "In B [rad/s]")
              RO(StudyBodyState, theta, "Planar: angle about z [rad] (NaN otherwise)");
  // A run's reactions are the same records as solve's (StudyReaction is ReactionReport,
  // bound as chasles.Reaction in bind_simulate.cpp).
  py::class_<StudyContactPoint>(m, "StudyContactPoint", "A contact point at an instant.")
      RO(StudyContactPoint, point, "")
          .def_property_readonly(
              "mode", [](const StudyContactPoint& c) { return StudyContactModeName(c.mode); })
              RO(StudyContactPoint, normal_force, "[N]")
          .def_readonly("friction", &StudyContactPoint::friction_force_W, "[N]")
          .def_readonly("slip_velocity", &StudyContactPoint::slip_velocity_W, "[m/s]")
              RO(StudyContactPoint, gap, "[m]") RO(StudyContactPoint, friction_work, "[J]")
                  RO(StudyContactPoint, rolling_work, "[J]")
                      RO(StudyContactPoint, impact_work, "[J]");
  py::class_<StudySnapshot>(m, "Snapshot", "Bodies, reactions and contacts at an instant.") RO(
      StudySnapshot, bodies, "") RO(StudySnapshot, reactions, "") RO(StudySnapshot, contacts, "");
  py::class_<StudyEvent>(m, "Event", "A scene event located during the run.")
      RO(StudyEvent, name, "") RO(StudyEvent, t, "[s]") RO(StudyEvent, stopped, "")
          RO(StudyEvent, snapshot, "");
  py::class_<BodyImpulse>(m, "BodyImpulse",
                          "One impulse on a body at an impulse or impact (values in W).")
      RO(BodyImpulse, source, "'applied', a constraint's name or \"contact '<point>'\"")
          .def_readonly("point", &BodyImpulse::p_WP, "[m]")
          .def_readonly("impulse", &BodyImpulse::J_W, "[N*s]")
          .def_readonly("moment_impulse", &BodyImpulse::M_W, "About the point [N*m*s]");
  py::class_<BodyImpulseBalance>(m, "JumpBody",
                                 "A body's velocity jumps at an impulse or impact and every "
                                 "impulse on it: m dv = sum J, dH = sum (r x J + M).")
      .def_readonly("name", &BodyImpulseBalance::body) RO(BodyImpulseBalance, mass, "[kg]")
      .def_readonly("center_of_mass", &BodyImpulseBalance::p_WBcm, "[m]")
      .def_readonly("velocity_after", &BodyImpulseBalance::v_WBcm_W, "[m/s]")
      .def_readonly("angular_velocity_after", &BodyImpulseBalance::w_WB_W, "In W [rad/s]")
      .def_readonly("velocity_change", &BodyImpulseBalance::dv_WBcm_W, "[m/s]")
      .def_readonly("angular_velocity_change", &BodyImpulseBalance::dw_WB_W, "[rad/s]")
      .def_readonly("angular_momentum_after", &BodyImpulseBalance::H_Bcm_W,
                    "About the centre of mass [kg*m^2/s]")
      .def_readonly("angular_momentum_change", &BodyImpulseBalance::dH_Bcm_W, "[kg*m^2/s]")
          RO(BodyImpulseBalance, impulses, "");
  py::class_<StudyJump>(m, "Jump", "An impulse or impact applied during the run.")
      .def_property_readonly(
          "kind", [](const StudyJump& x) { return StudyJumpKindName(x.kind); },
          "\"impulse\", \"embedding\" or \"pass-through\"") RO(StudyJump, description, "")
          RO(StudyJump, t, "") RO(StudyJump, energy_before, "[J]")
              RO(StudyJump, energy_after, "[J]")
      .def_readonly("velocity_after", &StudyJump::v_after_W)
      .def_readonly("angular_velocity_after", &StudyJump::w_after_W)
          RO(StudyJump, reactions,
             "The supports' impulsive reactions (Reaction records in N*s, N*m*s)")
              RO(StudyJump, bodies, "Every body's velocity jumps and impulses")
                  RO(StudyJump, impacts, "Indices into run.impacts of this instant");
  py::class_<StudyContactEvent>(m, "StudyContactEvent", "A contact mode change.")
      RO(StudyContactEvent, t, "[s]") RO(StudyContactEvent, point, "") RO(StudyContactEvent,
                                                                          contact, "")
          .def_property_readonly(
              "from_mode", [](const StudyContactEvent& e) { return StudyContactModeName(e.from); })
          .def_property_readonly(
              "to_mode", [](const StudyContactEvent& e) { return StudyContactModeName(e.to); })
          .def_property_readonly("reason", [](const StudyContactEvent& e) {
            return ContactEventReasonName(e.reason);
          });
  py::class_<StudyImpact>(m, "StudyImpact", "An impact at a contact point.") RO(StudyImpact, t, "")
      RO(StudyImpact, point, "") RO(StudyImpact, approach_speed, "[m/s]")
          RO(StudyImpact, normal_impulse, "[N*s]") RO(StudyImpact, energy_lost, "[J]")
              RO(StudyImpact, accumulation, "") RO(StudyImpact, rest_time, "")
                  RO(StudyImpact, jam, "")
                      .def_property_readonly(
                          "restitution_law",
                          [](const StudyImpact& x) {
                            return x.restitution_law ? RestitutionLawName(*x.restitution_law) : "";
                          },
                          "\"energetic\", \"newton\" or \"poisson\"");
  py::class_<StudyLedger>(m, "Ledger", "The work-energy ledger at the end of the run.") RO(
      StudyLedger, kinetic_translational, "[J]") RO(StudyLedger, kinetic_rotational, "[J]")
      RO(StudyLedger, potential, "[J]") RO(StudyLedger, energy, "[J]") RO(
          StudyLedger, energy_initial, "[J]") RO(StudyLedger, work_nonconservative, "[J]")
          RO(StudyLedger, work_by_force, "[(name, J)]") RO(StudyLedger, work_by_constraint, "") RO(
              StudyLedger, friction_work, "[J]") RO(StudyLedger, rolling_work, "[J]")
              RO(StudyLedger, impact_work, "[J]") RO(StudyLedger, dissipated, "[J]") RO(
                  StudyLedger, jumps, "[J]") RO(StudyLedger, residual, "E - E0 - W_nc - jumps [J]")
                  RO(StudyLedger, time_stepping_error, "[J]") RO(StudyLedger, energy_scale, "[J]")
                      .def_readonly("linear_momentum", &StudyLedger::linear_momentum_W)
                      .def_readonly("angular_momentum_cm", &StudyLedger::angular_momentum_Scm_W)
                      .def_readonly("angular_momentum_origin", &StudyLedger::angular_momentum_Wo_W);
}

/// A time-stepped stretch's certificate as a dict (TimeSteppingSummary).
py::dict SteppingSummaryDict(const TimeSteppingSummary& c) {
  py::dict d;
  d["steps"] = c.steps;
  d["regime_changes"] = c.regime_changes;
  d["residual_impulse"] = c.max_residual_impulse;
  d["residual_velocity"] = c.max_residual_velocity;
  d["momentum_residual"] = c.max_momentum_residual;
  d["angular_momentum_residual"] = c.max_angular_momentum_residual;
  d["max_penetration"] = c.max_penetration;
  d["velocity_error_estimate"] = c.max_velocity_error;
  d["accumulated_velocity_error_estimate"] = c.accumulated_velocity_error;
  d["scheme_error"] = c.numerical_energy_error;
  return d;
}

// The run's integrator as the JSON names it ("RK4 (fixed step)", "events", ...).
const char* RunIntegratorName(const StudyResult& r) {
  return StudyIntegratorName(r.engine, r.integrator);
}

void BindEngineSegments(py::module_& m) {
  py::class_<StudyEngineSegment>(m, "EngineSegment",
                                 "One stretch of an `integrator: auto` run on one engine, and why "
                                 "that engine took over.") RO(StudyEngineSegment, t_begin, "[s]")
      RO(StudyEngineSegment, t_end, "[s]")
          .def_property_readonly(
              "engine", [](const StudyEngineSegment& g) { return StudyEngineName(g.engine); },
              "'adaptive' (event-driven) or 'stepping'")
          .def_property_readonly(
              "reason", [](const StudyEngineSegment& g) { return EngineSwitchName(g.reason); },
              "'start', 'regime changes' or 'quiet'") RO(StudyEngineSegment, changes, "")
              RO(StudyEngineSegment, span, "[s]") RO(StudyEngineSegment, where, "")
                  RO(StudyEngineSegment, quiet, "[s]") RO(StudyEngineSegment, stays, "")
                      RO(StudyEngineSegment, islands,
                         "an event-driven stretch: the islands it ran apart (1: one system)")
                          RO(StudyEngineSegment, stats, "")
                              RO(StudyEngineSegment, tolerance_met, "")
                                  RO(StudyEngineSegment, projection_depth, "[m]")
                                      RO(StudyEngineSegment, projection_energy, "[J]")
          .def_property_readonly(
              "stepping",
              [](const StudyEngineSegment& g) -> py::object {
                if (g.engine != StudyEngine::kStepping) return py::none();
                return SteppingSummaryDict(g.stepping);
              },
              "A time-stepped segment's certificate (None otherwise)");
}

// A run's path, and the text report of a scene's mass properties.
void BindRunPathAndMassText(py::module_& m) {
  py::class_<RunPathChoice>(m, "RunPath", "The path a run took and why (docs/contact.md).")
      .def_property_readonly(
          "path", [](const RunPathChoice& c) { return RunPathName(c.path); },
          "'smooth', 'free-body batch', 'hybrid', 'islands', 'event-driven spheres', 'time "
          "stepping' or 'auto' (the JSON's run_path.path)")
          RO(RunPathChoice, reason, "Why this path, in words (the JSON's run_path.reason)")
              RO(RunPathChoice, islands, "Islands the bodies form (0 where not looked for)");
  m.def(
      "_mass_text",
      [](const PyScene& s, const std::string& units) {
        MassTextOptions options;
        options.text.units = units;
        return MassText(s.scene, options);
      },
      py::arg("scene"), py::arg("units"));
}

void BindStudy(py::module_& m) {
  BindEngineSegments(m);
  BindRunPathAndMassText(m);
  py::class_<StudyResult>(m, "StudyResult", "The result of a scene's run (RunStudy).")
      RO(StudyResult, columns, "") RO(StudyResult, events, "") RO(StudyResult, jumps, "")
          RO(StudyResult, contact_events, "") RO(StudyResult, impacts, "")
              RO(StudyResult, run_path, "The path the run took and why")
              RO(StudyResult, final_contacts, "") RO(StudyResult, t_end, "")
                  RO(StudyResult, stopped_by_event, "") RO(StudyResult, final_bodies, "")
                      RO(StudyResult, final_reactions, "") RO(StudyResult, ledger, "")
                          .def_property_readonly("integrator", &RunIntegratorName)
                              RO(StudyResult, stats, "")
                              RO(StudyResult, notes, "") RO(StudyResult, segments, "")
                                  RO(StudyResult, engine_by_default,
                                     "integrator: auto because the scene named none (format "
                                     "version 3's default for a scene with contacts)")
                                  RO(StudyResult, warnings, "")
                                      RO(StudyResult, certificate, "")
                                          .def_property_readonly(
                                              "event_driven",
                                              [](const StudyResult& r) -> py::object {
                                                if (!r.event_driven) return py::none();
                                                const StudyEventDriven& e = *r.event_driven;
                                                py::dict energy;
                                                energy["initial"] = e.energy.initial;
                                                energy["final"] = e.energy.final;
                                                energy["friction"] = e.energy.friction;
                                                energy["rolling"] = e.energy.rolling;
                                                energy["impacts"] = e.energy.impacts;
                                                energy["residual"] = e.energy.residual;
                                                py::dict d;
                                                d["collisions"] = e.collisions;
                                                d["impacts"] = e.stats.impacts;
                                                d["phase_events"] = e.stats.phase_events;
                                                d["pressing_groups"] = e.stats.groups;
                                                d["group_runs"] = e.stats.group_windows;
                                                d["energy"] = energy;
                                                return d;
                                              },
                                              "integrator: events: the counts and the run's "
                                              "closed-form energy balance [J] (None otherwise)")
                                          .def_property_readonly("data",
                                                                 [](const StudyResult& r) {
                                                                   return TableArray(
                                                                       r.rows, r.columns.size());
                                                                 })
                                          .def(
                                              "to_csv",
                                              [](const StudyResult& r, bool full_precision) {
                                                return SimulationCsv(
                                                    r, full_precision ? CsvPrecision::kFull
                                                                      : CsvPrecision::kDefault);
                                              },
                                              py::arg("full_precision") = false,
                                              "The CSV file `chasles simulate` writes "
                                              "(full_precision: "
                                              "--full-precision, every value %.17g)");
  m.def(
      "_run_json",
      [](const PyScene& s, const StudyResult& r, const std::string& csv_path) {
        const ReportHeader header{s.scene.file, s.scene.title, s.scene.planar, s.scene.warnings};
        return DumpJson(SimulationJson(r, header, csv_path), "the JSON summary");
      },
      py::arg("scene"), py::arg("result"), py::arg("csv_path"));
  m.def(
      "_run_text",
      [](const PyScene& s, const StudyResult& r, const std::string& units, const std::string& out) {
        const SimulationFiles files = SimulationFilesIn(out, s.scene.file);
        return SimulationText(s.scene, r, TextOptions{units, files.csv, files.json});
      },
      py::arg("scene"), py::arg("result"), py::arg("units"), py::arg("out"));
  m.def(
      "_run_study",
      [](const PyScene& s, double until, std::int64_t max_steps, std::int64_t max_rows,
         double timeout, double min_step) {
        StudyOptions o;
        o.until = until;
        o.max_steps = max_steps;
        o.max_rows = max_rows;
        o.timeout = timeout;
        o.min_step = min_step;
        py::gil_scoped_release release;
        return RunStudy(MakeStudyDefinition(s.scene, o));
      },
      py::arg("scene"), py::arg("until"), py::arg("max_steps"), py::arg("max_rows"),
      py::arg("timeout"), py::arg("min_step"));
  m.def(
      "_run_definition",
      [](const Model& model, const State& initial, const SimulationOptions& options,
         const std::vector<std::tuple<std::string, int, std::string>>& columns,
         std::int64_t max_steps, std::int64_t max_rows, double timeout) {
        // A study of the caller's Model: its bodies are the study's, the run starts on a copy
        // of it (a Python Model may change afterwards), no impact embeds, so no ModelBuilder.
        StudyDefinition def;
        for (int b = 0; b < model.num_bodies(); ++b) {
          def.bodies.push_back({model.body(b).name(), model.body(b).mass_properties()});
        }
        def.model = std::make_shared<const Model>(model);
        def.initial = initial;
        def.options = options;
        def.options.events.clear();
        for (const auto& [name, body, quantity] : columns) {
          StudyColumn c;
          c.name = name;
          c.body = body;
          c.quantity = quantity;
          c.group = body < 0 ? (name == "t" ? "time" : "energy") : "body";
          def.columns.push_back(std::move(c));
        }
        def.limits = {max_steps, max_rows, timeout};
        {
          py::gil_scoped_release release;
          return RunStudy(def);
        }
      },
      py::arg("model"), py::arg("initial"), py::arg("options"), py::arg("columns"),
      py::arg("max_steps"), py::arg("max_rows"), py::arg("timeout"));
}

}  // namespace

void BindScene(py::module_& m) {
  BindCertificate(m);
  BindSceneClasses(m);
  BindSolve(m);
  BindStudyParts(m);
  BindStudy(m);
}

}  // namespace chasles::python
