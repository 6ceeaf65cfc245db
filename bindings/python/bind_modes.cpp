// Small motions: chasles.modes(scene) (`chasles modes`, docs/modes.md) as numpy arrays.

#include <complex>

#include "bindings.h"
#include "chasles/report/modes_text.h"
#include "chasles/scene/modes.h"
#include "chasles/scene/scene_dynamics.h"
#include "chasles/scene/sweep.h"

namespace chasles::python {

namespace {

py::dict ModesDict(const OperatingPointModes& s) {
  const Linearization& lin = s.modes.linearization;
  const auto n = static_cast<py::ssize_t>(s.modes.modes.size());
  const auto d = static_cast<py::ssize_t>(lin.A.rows());
  py::array_t<std::complex<double>> eigenvalues(n), shapes({n, d});
  py::array_t<double> frequency(n), damping(n), growth(n);
  py::array_t<bool> stable(n), rigid(n);
  auto e = eigenvalues.mutable_unchecked<1>();
  auto sh = shapes.mutable_unchecked<2>();
  auto f = frequency.mutable_unchecked<1>();
  auto z = damping.mutable_unchecked<1>();
  auto g = growth.mutable_unchecked<1>();
  auto st = stable.mutable_unchecked<1>();
  auto rg = rigid.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < n; ++i) {
    const Mode& m = s.modes.modes[static_cast<size_t>(i)];
    e(i) = m.eigenvalue, f(i) = m.frequency_hz, z(i) = m.damping_ratio, g(i) = m.growth_rate;
    st(i) = m.stable, rg(i) = m.rigid;
    for (py::ssize_t j = 0; j < d; ++j) sh(i, j) = m.shape[j];
  }
  py::list coordinates, speeds;
  for (const LinearCoordinate& c : lin.coordinates)
    coordinates.append(py::make_tuple(c.name, c.unit));
  for (const LinearCoordinate& c : lin.speeds) speeds.append(py::make_tuple(c.name, c.unit));
  py::dict op;
  op["kind"] = OperatingPointKindName(s.operating_point.kind);
  op["residual"] = s.operating_point.residual;
  op["warnings"] = s.operating_point.warnings;
  py::dict out;
  out["operating_point"] = op;
  out["coordinates"] = coordinates;
  out["speeds"] = speeds;
  out["A"] = py::cast(lin.A);
  out["eigenvalues"] = eigenvalues;
  out["frequency_hz"] = frequency;
  out["damping_ratio"] = damping;
  out["growth_rate"] = growth;
  out["stable_modes"] = stable;
  out["rigid"] = rigid;
  out["shapes"] = shapes;
  out["stable"] = s.modes.stable;
  out["finite_difference_check"] = lin.finite_difference_check;
  return out;
}

}  // namespace

void BindModes(py::module_& m) {
  m.def(
      "modes",
      [](const PyScene& s) {
        OperatingPointModes r;
        {
          py::gil_scoped_release release;
          r = AnalyseOperatingPointModes(MakeModesDefinition(s.scene));
        }
        return ModesDict(r);
      },
      py::arg("scene"),
      "Small motions about the scene's operating point (`chasles modes`): a dict with "
      "'operating_point' (kind, residual), 'coordinates' and 'speeds' (name, unit), 'A' (the "
      "linearisation x' = A x, x = [coordinates; speeds]), and per mode 'eigenvalues' (complex, "
      "1/s), 'frequency_hz', 'damping_ratio', 'growth_rate', 'stable_modes', 'rigid', 'shapes' "
      "(modes x entries of x, complex); 'stable' the verdict.");
  m.def(
      "_modes_text",
      [](const PyScene& s) {
        OperatingPointModes r;
        {
          py::gil_scoped_release release;
          r = AnalyseOperatingPointModes(MakeModesDefinition(s.scene));
        }
        return ModesText(s.scene, r);
      },
      py::arg("scene"));
  m.def(
      "_modes_sweep_text",
      [](const PyScene& s, const std::string& sweep) {
        const SweepSpec spec = ParseSweep(sweep);
        ModesSweep w;
        {
          py::gil_scoped_release release;
          const auto load = [&s](const SceneOptions& o) { return s.Load(o); };
          const SweepGrid grid = MakeSweepGrid(load(s.options), {spec}, kDefaultMaxRows);
          w = SweepModes(grid.parameters, [&](double value) {
            return MakeModesDefinitionAt(load, s.options, spec.name, grid.parameters.units[0],
                                         value);
          });
        }
        return ModesSweepText(w);
      },
      py::arg("scene"), py::arg("sweep"));
}

}  // namespace chasles::python
