// SteOptions and the options it nests (docs/methods.md, "Options"), field by field.
#include <pybind11/stl.h>

#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/options.hpp"
#include "run/evaluation.hpp"
#include "run/option_tables.hpp"
#include "ste/option_tables.hpp"

namespace plumekit::python {

namespace {

using namespace ste;

void bind_estimation(py::module_& m) {
  py::class_<run::SteLikelihood> l(m, "SteLikelihood",
                                   "The likelihood's errors; None: the plume model's default");
  l.def(py::init<>());
  PK_FIELD(l, run::SteLikelihood, sigma_m,
           "Model error (None: 200 surrogate, 150 physics, 30 gaussian)");
  PK_FIELD(l, run::SteLikelihood, sigma_d, "Measurement error");
  PK_FIELD(l, run::SteLikelihood, sigma_rel,
           "Model error relative to the prediction (None: 0.15 physics, else 0)");
  PK_FIELD(l, run::SteLikelihood, sigma_std,
           "Model error in the surrogate's predicted stds (None: 2 surrogate)");

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
  PK_FIELD(w, world::WorldOptions, speed, "Travel speed, m/s");
  PK_FIELD(w, world::WorldOptions, sample_s, "Seconds per sample");
  PK_FIELD(w, world::WorldOptions, sample_rate, "Readings per second");
  PK_FIELD(w, world::WorldOptions, noise, "Std of each reading's noise");
  PK_FIELD(w, world::WorldOptions, sensor, "The robot's GasSensorModel");
  PK_FIELD(w, world::WorldOptions, wind_direction_noise_deg, "Anemometer direction error, degrees");
  PK_FIELD(w, world::WorldOptions, wind_noise_from_table35,
           "Direction error from seed 000's table 3.5");
  PK_FIELD(w, world::WorldOptions, position_noise, "Std per axis of the recorded position, m");
  PK_FIELD(w, world::WorldOptions, position_noise_per_fix,
           "position_noise is each reading's fix error; a stop records their mean");
  PK_FIELD(w, world::WorldOptions, odometry_drift,
           "Recorded positions drift by this std per axis per sqrt(m) travelled (ste-local)");
  PK_FIELD(w, world::WorldOptions, rotor_disc,
           "Radius of the disc each gas reading averages over, m (seed 000's rotor: 0.5)");
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
  PK_FIELD(o, run::SteOptions, model_path, "The surrogate's CNN file (empty: the shipped model)");
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
  PK_FIELD(o, run::SteOptions, source_cell, "Candidate source grid, m (None: the model's default)");
  PK_FIELD(o, run::SteOptions, table_cell,
           "The surrogate's table grid, m (None: the source cell, coarser on large maps)");
  PK_FIELD(o, run::SteOptions, margin, "The planner's clearance, m");
  PK_FIELD(o, run::SteOptions, table_cache, "Folder caching surrogate tables (empty: none)");
  PK_FIELD(o, run::SteOptions, threads, "Threads of the surrogate's table build (0: one per core)");
  PK_FIELD(o, run::SteOptions, min_start_distance,
           "Random starts are at least this far from the source, m");
  PK_FIELD(o, run::SteOptions, success_radius,
           "A run ends on coming this close to the source, m (0: never; levy-taxis: 0.5)");
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
