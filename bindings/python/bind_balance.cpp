// Rotor balancing: chasles.balance(scene, body, planes, radius, ...) (`chasles balance`,
// docs/modes.md "Rotors"): the numbers, and the program's text and JSON reports.

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "bindings.h"
#include "chasles/report/balance_json.h"
#include "chasles/report/balance_text.h"
#include "chasles/report/json_report.h"
#include "chasles/scene/balance.h"

namespace chasles::python {

namespace {

/// Rows of 3-vectors as a (rows x 3) numpy array.
py::array_t<double> Rows(const std::vector<Vec3>& rows) {
  py::array_t<double> out({static_cast<py::ssize_t>(rows.size()), py::ssize_t{3}});
  auto a = out.mutable_unchecked<2>();
  for (size_t i = 0; i < rows.size(); ++i) {
    for (int j = 0; j < 3; ++j) a(static_cast<py::ssize_t>(i), j) = rows[i][j];
  }
  return out;
}

py::object OrNone(double v) {
  return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none());
}

py::list Corrections(const RotorBalance& b) {
  py::list out;
  const char* names[2] = {"A", "B"};
  const double z[2] = {b.axis.z_A, b.axis.z_B};
  for (size_t k = 0; k < 2; ++k) {
    const BalanceCorrection& c = b.balance.corrections[k];
    py::dict d;
    d["plane"] = names[k];
    d["position"] = z[k];
    d["mass"] = c.mass;
    d["radius"] = c.radius;
    d["angle"] = c.angle;
    d["point"] = py::cast(c.p_W);
    out.append(d);
  }
  return out;
}

py::object Whirl(const RotorBalance& b) {
  if (!b.whirl) return py::none();
  py::list points, critical;
  std::vector<double> speeds;
  for (const WhirlPoint& p : b.whirl->points) {
    speeds.push_back(p.speed);
    const auto n = static_cast<py::ssize_t>(p.modes.size());
    py::array_t<std::complex<double>> eigenvalues(n);
    py::array_t<double> frequency(n), damping(n);
    py::list directions;
    for (py::ssize_t i = 0; i < n; ++i) {
      const WhirlMode& m = p.modes[static_cast<size_t>(i)];
      eigenvalues.mutable_at(i) = m.eigenvalue;
      frequency.mutable_at(i) = m.frequency_hz;
      damping.mutable_at(i) = m.damping_ratio;
      directions.append(WhirlDirectionName(m.direction));
    }
    py::dict point;
    point["speed"] = p.speed;
    point["eigenvalues"] = eigenvalues;
    point["frequency_hz"] = frequency;
    point["damping_ratio"] = damping;
    point["directions"] = directions;
    points.append(point);
  }
  for (const WhirlCriticalSpeed& c : b.whirl->critical_speeds) {
    py::list directions;
    for (const WhirlDirection d : c.directions) directions.append(WhirlDirectionName(d));
    critical.append(py::make_tuple(c.speed, directions));
  }
  py::dict out;
  out["speeds"] = py::array_t<double>(static_cast<py::ssize_t>(speeds.size()), speeds.data());
  out["points"] = points;
  out["critical_speeds"] = critical;
  return out;
}

}  // namespace

void BindBalance(py::module_& m) {
  py::class_<BalanceOptions>(m, "_BalanceOptions")
      .def(py::init<>())
      .def_readwrite("body", &BalanceOptions::body)
      .def_readwrite("axis", &BalanceOptions::axis)
      .def_readwrite("through", &BalanceOptions::through)
      .def_readwrite("planes", &BalanceOptions::planes)
      .def_readwrite("radius", &BalanceOptions::radius)
      .def_readwrite("speed", &BalanceOptions::speed)
      .def_readwrite("grade", &BalanceOptions::grade)
      .def_readwrite("whirl", &BalanceOptions::whirl)
      .def_readwrite("source", &BalanceOptions::source)
      .def_readwrite("option_prefix", &BalanceOptions::option_prefix);
  py::class_<RotorBalance>(
      m, "Balance",
      "A rotor's balance (`chasles balance`, docs/modes.md \"Rotors\"), SI: the static and "
      "couple unbalance, the two correction masses, what is left after them, the bearing "
      "forces at the speed, the ISO 21940-11 permissible residual unbalance and the whirl rows "
      "on elastic bearings. Attributes that need the speed or the grade are None without "
      "them. text() and json() are what the program prints.")
      .def_readonly("body", &RotorBalance::body, "The rotor's name")
      .def_property_readonly(
          "mass", [](const RotorBalance& b) { return b.balance.mass; }, "[kg]")
      .def_property_readonly(
          "static_unbalance",
          [](const RotorBalance& b) { return b.balance.static_unbalance_W.norm(); },
          "|U| = m e [kg·m]")
      .def_property_readonly(
          "static_unbalance_vector",
          [](const RotorBalance& b) { return Vec3(b.balance.static_unbalance_W); },
          "U in W, normal to the axis [kg·m]")
      .def_property_readonly(
          "couple_unbalance",
          [](const RotorBalance& b) { return b.balance.couple_unbalance_W.norm(); },
          "|C| [kg·m²]: the products of inertia about the axis through the centre of mass")
      .def_property_readonly(
          "couple_unbalance_vector",
          [](const RotorBalance& b) { return Vec3(b.balance.couple_unbalance_W); },
          "C in W, normal to the axis [kg·m²]")
      .def_property_readonly(
          "reference_directions",
          [](const RotorBalance& b) {
            return Rows({b.balance.e1_W, b.balance.e2_W});
          },
          "Rows e1 and e2 = a × e1 in W: the corrections' angles turn from e1 towards e2")
      .def_property_readonly("corrections", &Corrections,
                             "One dict per plane (A, B): 'plane', 'position' along the axis "
                             "[m], 'mass' [kg], 'radius' [m], 'angle' [rad], 'point' in W [m]")
      .def_property_readonly(
          "residual_static", [](const RotorBalance& b) { return b.balance.residual_static; },
          "|U| left after the corrections [kg·m] (round-off)")
      .def_property_readonly(
          "residual_couple", [](const RotorBalance& b) { return b.balance.residual_couple; },
          "|D| left after the corrections [kg·m²] (round-off)")
      .def_property_readonly(
          "speed", [](const RotorBalance& b) { return OrNone(b.balance.speed); },
          "The spin [rad/s]; None without one")
      .def_property_readonly(
          "bearing_forces_before",
          [](const RotorBalance& b) -> py::object {
            if (!std::isfinite(b.balance.speed)) return py::none();
            const auto& f = b.balance.bearing_forces_W;
            return Rows({f[0], f[1]});
          },
          "Rows A and B: the bearing forces on the rotor at the speed, in W at the present "
          "angle, before the correction [N]; None without a speed")
      .def_property_readonly(
          "bearing_forces_after",
          [](const RotorBalance& b) -> py::object {
            if (!std::isfinite(b.balance.speed)) return py::none();
            const auto& f = b.balance.bearing_forces_after_W;
            return Rows({f[0], f[1]});
          },
          "The same after the correction [N] (round-off); None without a speed")
      .def_property_readonly(
          "grade", [](const RotorBalance& b) { return OrNone(b.balance.grade); },
          "The balance grade G [mm/s]; None without one")
      .def_property_readonly(
          "permissible", [](const RotorBalance& b) { return OrNone(b.balance.permissible); },
          "ISO 21940-11 permissible residual unbalance U_per = m G/ω [kg·m]; None without a "
          "grade")
      .def_property_readonly(
          "permissible_per_plane",
          [](const RotorBalance& b) -> py::object {
            if (!std::isfinite(b.balance.permissible)) return py::none();
            return py::make_tuple(b.balance.permissible_per_plane[0],
                                  b.balance.permissible_per_plane[1]);
          },
          "(A, B): U_per shared between the planes [kg·m]; None without a grade")
      .def_property_readonly(
          "permissible_met",
          [](const RotorBalance& b) -> py::object {
            if (!std::isfinite(b.balance.permissible)) return py::none();
            return py::bool_(b.balance.static_unbalance_W.norm() <= b.balance.permissible);
          },
          "Whether the static unbalance is within U_per; None without a grade")
      .def_property_readonly("whirl", &Whirl,
                             "None unless a bearing element holds the rotor; else a dict: "
                             "'speeds' [rad/s], 'points' (per spin 'speed', 'eigenvalues' "
                             "(complex, 1/s), 'frequency_hz', 'damping_ratio', 'directions' "
                             "('forward', 'backward' or 'none')) and 'critical_speeds' "
                             "((speed, [directions]), ...)")
      .def("text", &RotorBalanceText, "The report `chasles balance` prints (text)")
      .def(
          "json",
          [](const RotorBalance& b) { return DumpJson(RotorBalanceJson(b), "the balance report"); },
          "The report `chasles balance --format json` prints (text)");
  m.def(
      "_balance",
      [](const PyScene& s, const BalanceOptions& options) {
        py::gil_scoped_release release;
        RotorBalance b = AnalyseRotorBalance(MakeBalanceDefinition(s.scene, options));
        // As the program refuses to print a report with a number out of range.
        CheckFiniteJson(RotorBalanceJson(b), "the balance report");
        return b;
      },
      py::arg("scene"), py::arg("options"));
}

}  // namespace chasles::python
