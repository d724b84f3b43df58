// SteOptions and the options it nests (docs/methods.md, "Options"), field by field.
#include <pybind11/stl.h>

#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/options.hpp"
#include "run/evaluation.hpp"
#include "run/option_tables.hpp"
#include "ste/option_tables.hpp"
#include "world/option_tables.hpp"

namespace plumekit::python {

namespace {

using namespace ste;

void bind_estimation(py::module_& m) {
  py::class_<run::SteLikelihood> l(m, "SteLikelihood",
                                   "The likelihood's errors; None: the plume model's default");
  l.def(py::init<>());
  bind_table(l, run::ste_likelihood_option_table());

  py::class_<BinOptions> b(m, "BinOptions", "Entropy bins, m");
  b.def(py::init<>());
  bind_table(b, bin_option_table());

  py::class_<MhOptions> mh(m, "MhOptions", "Metropolis-Hastings (Gaussian plume model)");
  mh.def(py::init<>());
  bind_table(mh, mh_option_table());

  py::class_<StopOptions> s(m, "StopOptions", "When a localization stops");
  s.def(py::init<>());
  bind_table(s, stop_option_table());

  py::class_<NavigationOptions> n(m, "NavigationOptions", "Where the robot goes next");
  n.def(py::init<>());
  bind_table(n, navigation_option_table());
}

void bind_world(py::module_& m) {
  py::class_<world::WorldOptions> w(m, "WorldOptions", "The simulated robot's world and sensors");
  w.def(py::init<>());
  PK_FIELD(w, world::WorldOptions, filament, "The world's FilamentOptions");
  PK_FIELD(w, world::WorldOptions, sensor, "The robot's GasSensorModel");
  bind_table(w, world::world_option_table());
  bind_deprecated_alias(w, "wind_direction_noise_deg", "wind_direction_noise");
  w.def_property(
      "gas_sensor", [](const world::WorldOptions& o) { return o.sensor.name; },
      [](world::WorldOptions& o, const std::string& name) { set_gas_sensor(o.sensor, name); },
      "The robot's gas sensor preset (gas_sensor())");
}

void bind_models(py::module_& m) {
  py::class_<PhysicsPlumeOptions> p(m, "PhysicsPlumeOptions", "The physics plume model");
  p.def(py::init<>());
  PK_FIELD(p, PhysicsPlumeOptions, advection_diffusion, "Its AdvectionDiffusionOptions");
  bind_table(p, physics_option_table());

  py::class_<GaussianPlumeBounds> g(m, "GaussianPlumeBounds", "The Gaussian plume's prior box");
  g.def(py::init<>());
  bind_table(g, gaussian_option_table());
}

void bind_team(py::module_& m) {
  py::class_<run::TeamOptions> t(m, "TeamOptions",
                                 "A team of robots running STE (seed 004 ch. 13)");
  t.def(py::init<>());
  bind_table(t, run::team_option_table());
}

void bind_ste_options_class(py::module_& m) {
  py::class_<run::SteOptions> o(
      m, "SteOptions",
      "Every option of a localization, with the library's defaults. Nested "
      "options take dicts in keyword arguments: localize(map, source, "
      "plume_model='physics', stop={'max_samples': 30}).");
  o.def(py::init<>());
  o.def_property(
      "method", [](const run::SteOptions& s) { return s.method.name; },
      [](run::SteOptions& s, const std::string& v) { s.method.name = run::find_method(v).name; },
      "'ste' (the default), or one of the seeds' methods: 'sweeping', 'surge-cast', 'zigzag', "
      "'pseudo-gradient', 'pf-gradient', 'pf-sweep', 'apf', 'levy-taxis', 'ste-local' "
      "(docs/methods.md, "
      "docs/design/ste.md)");
  o.def_property(
      "plume_model", [](const run::SteOptions& s) { return std::string(to_string(s.model)); },
      [](run::SteOptions& s, const std::string& v) { s.model = run::parse_plume_model_kind(v); },
      "'surrogate' (the CNN), 'gaussian' or 'physics'");
  // Its own numbers and names from its table; the plume model keeps its keyword plume_model.
  bind_table(o, run::ste_option_table(), {"ste.model"});
  PK_FIELD(o, run::SteOptions, likelihood, "SteLikelihood");
  PK_FIELD(o, run::SteOptions, bins, "BinOptions");
  PK_FIELD(o, run::SteOptions, mh, "MhOptions");
  PK_FIELD(o, run::SteOptions, navigation, "NavigationOptions");
  PK_FIELD(o, run::SteOptions, stop, "StopOptions");
  PK_FIELD(o, run::SteOptions, world, "WorldOptions");
  PK_FIELD(o, run::SteOptions, team, "TeamOptions: robots > 1 runs a team (its result has 'team')");
  PK_FIELD(o, run::SteOptions, flow, "FlowOptions of the map's wind");
  PK_FIELD(o, run::SteOptions, wind_dir, "A `plumekit flow` output to use instead of solving");
  PK_FIELD(o, run::SteOptions, physics, "PhysicsPlumeOptions");
  PK_FIELD(o, run::SteOptions, gaussian, "GaussianPlumeBounds");
}

}  // namespace

void bind_ste_options(py::module_& m) {
  bind_estimation(m);
  bind_world(m);
  bind_models(m);
  bind_team(m);
  bind_ste_options_class(m);
}

}  // namespace plumekit::python
