// Source term estimation (ste/): one run, an evaluation, and a mission a user drives step by step
// with their own readings.
#include <filesystem>
#include <memory>
#include <optional>

#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "core/animation.hpp"
#include "core/error.hpp"
#include "core/seed.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/wind.hpp"
#include "run/evaluate_job.hpp"
#include "run/evaluation.hpp"
#include "run/localize_job.hpp"
#include "run/replay.hpp"
#include "run/replay_render.hpp"
#include "run/report.hpp"
#include "run/scenario.hpp"
#include "ste/mission.hpp"
#include "surrogate/plume_network.hpp"
#include "surrogate/shipped_models.hpp"

namespace plumekit::python {

namespace {

using run::Scenario;
using run::SteOptions;

// The CLI's defaults the library leaves to its caller: the shipped CNN.
run::SteOptions ste_options(const py::object& base, const py::kwargs& kw, const std::string& what) {
  run::SteOptions o = options_from<run::SteOptions>(base, kw, what);
  if (o.model == run::PlumeModelKind::Surrogate)
    o.model_path =
        surrogate::resolve_model(o.model_path.empty() ? "hybrid" : o.model_path, data_dir())
            .string();
  return o;
}

std::shared_ptr<run::Scenario> make_scenario(const Map& map, const run::SteOptions& o) {
  ReleasedGil release;
  try {
    return std::make_shared<run::Scenario>(map, o);
  } catch (const surrogate::MapSizeError& e) {
    throw InputError(with_any_map_advice(e.what(), "model_path") + " or plume_model=\"physics\"");
  }
}

py::dict posterior_dict(const Map& map, const ste::Posterior& p) {
  py::dict out;
  out["estimate"] = from_point(map.to_frame(p.expected_source()));
  out["map"] = from_point(map.to_frame(p.map));
  out["expected"] = p.expected;
  out["entropy"] = p.entropy;
  out["max_entropy"] = p.max_entropy;
  out["seen_mass"] = p.seen_mass;
  out["marginal"] = grid_array(p.marginal.values, p.marginal.shape);
  return out;
}

// The run `localize` makes (run::localize_once: its seeds, so that the same seed gives the same
// run), summarised as run.json is without the command's keys.
// With `animate` (a path), the mission's replay is drawn there too (`localize --animate`).
py::object run_once(const run::Scenario& sc, const py::handle& source, const py::object& start,
                    std::uint64_t seed, const py::object& animate) {
  const Map& map = sc.map();
  // Python objects are read before the GIL is released.
  const Vec2 s = map.from_frame(to_point(source, "source"));
  const std::optional<Vec2> requested =
      start.is_none() ? std::nullopt
                      : std::optional<Vec2>(map.from_frame(to_point(start, "start")));
  const std::string animation = animate.is_none() ? "" : py::str(animate).cast<std::string>();
  if (!animation.empty()) check_animation_target(animation, "animate");
  nlohmann::ordered_json j;
  {
    ReleasedGil release;
    const std::unique_ptr<run::ReplayRecorder> recorder =
        animation.empty() ? nullptr : run::replay_recorder_for(sc);
    const run::LocalizeRun r = run::localize_once(sc, s, requested, seed, recorder.get());
    j = run::run_report(sc, r.source, r.result).json;
    if (recorder) {
      const run::Replay replay =
          recorder->finish(r.result, r.source, run::replay_title(sc, r.source, seed));
      const AnimationWriter::Written w = run::animate_replay(replay, animation, "animate");
      std::string text;  // the command's line; Python takes the dict
      run::report_animation(w, j, text);
    }
  }
  return from_json(j);
}

// `plumekit replay RUN_DIR --out FILE`.
py::object replay_run(const std::string& run_dir, const std::string& out, double fps,
                      const py::object& size) {
  run::AnimateOptions o;
  o.fps = fps;
  if (!size.is_none()) {
    const py::tuple t = size.cast<py::tuple>();
    if (t.size() != 2) throw InputError("size: expected (width, height) in pixels");
    o.size = {t[0].cast<int>(), t[1].cast<int>()};
    if (o.size.width < 640 || o.size.height < 360 || o.size.width % 2 || o.size.height % 2)
      throw InputError("size: each side even, at least (640, 360)");
  }
  check_animation_target(out, "out");
  nlohmann::ordered_json j;
  {
    ReleasedGil release;
    const run::Replay replay = run::read_replay(run_dir);
    const AnimationWriter::Written w = run::animate_replay(replay, out, "out", o);
    j = {{"title", replay.title},
         {"file", w.file.string()},
         {"format", w.format},
         {"frames", w.frames}};
    if (!w.note.empty()) j["note"] = w.note;
  }
  return from_json(j);
}

// A sample's point (map frame) in arena coordinates. A point outside the arena or inside an
// obstacle is refused as the CLI refuses such a source or start (point_fault's wording).
Vec2 sample_point(const Map& map, const py::handle& p, const std::string& field) {
  const Vec2 a = map.from_frame(to_point(p, field.c_str()));
  if (const std::string fault = point_fault(map, a); !fault.empty())
    throw OptionError(field, fault);
  return a;
}

// Readings taken on the way, [(point, time_s, reading), ...] in the map's frame.
std::vector<ste::PassingReading> passing_readings(const Map& map, const py::list& readings) {
  std::vector<ste::PassingReading> out;
  for (const py::handle& r : readings) {
    const py::tuple t = r.cast<py::tuple>();
    if (t.size() != 3) throw InputError("on_the_way: each reading is (point, time_s, reading)");
    out.push_back({map.from_frame(to_point(t[0], "on_the_way point")), t[1].cast<double>(),
                   t[2].cast<double>()});
  }
  return out;
}

// A mission on a scenario, kept alive together.
struct PyMission {
  std::shared_ptr<const run::Scenario> scenario;
  std::unique_ptr<ste::Estimator> estimator;
  std::unique_ptr<ste::Mission> mission;
};

void bind_mission(py::module_& m) {
  py::class_<PyMission>(
      m, "Mission",
      "STE driven by the caller: add(p, reading) after each stop, next(robot) for where to go. "
      "Points in the map frame; a reading is the mean over a stop, in the plume model's units. "
      "One thread at a time.")
      .def(
          "add",
          [](PyMission& pm, const py::handle& p, double reading, const py::list& shared,
             const py::list& on_the_way) {
            const Map& map = pm.scenario->map();
            const Vec2 a = sample_point(map, p, "p");
            std::vector<ste::Mission::Sample> others;
            for (const py::handle& s : shared) {
              const py::tuple t = s.cast<py::tuple>();
              if (t.size() != 2) throw InputError("shared: each sample is (point, reading)");
              others.push_back({sample_point(map, t[0], "shared point"), t[1].cast<double>()});
            }
            const std::vector<ste::PartialSample> partial = ste::partial_samples(
                passing_readings(map, on_the_way), pm.scenario->options().passing_options());
            const ste::Posterior* post = nullptr;
            {
              ReleasedGil release;
              post = &pm.mission->add(a, reading, others, partial);
            }
            return posterior_dict(map, *post);
          },
          py::arg("p"), py::arg("reading"), py::arg("shared") = py::list(),
          py::arg("on_the_way") = py::list(),
          "A sample; returns the posterior: 'estimate' (the expected source), 'map', "
          "'entropy', 'max_entropy', 'seen_mass', 'expected' (every parameter) and 'marginal' "
          "[ny, nx] over the arena. `shared`: teammates' samples since the last, [(point, "
          "reading), ...], added first; they do not count against this robot's max_samples. A "
          "point "
          "outside the arena or inside an obstacle raises OptionError (a ValueError), as the "
          "command line refuses such a source. `on_the_way`: the readings taken while moving "
          "here, [(point, time_s, reading), ...] oldest first; averaged over the scenario's "
          "passing_window_s into partial samples (docs/design/ste.md, 'Readings on the way'), "
          "which do not count as samples")
      .def(
          "next",
          [](const PyMission& pm, const py::handle& robot, const py::list& teammates) {
            const Map& map = pm.scenario->map();
            const Vec2 a = map.from_frame(to_point(robot, "robot"));
            std::vector<Vec2> goals;
            for (const py::handle& g : teammates)
              goals.push_back(map.from_frame(to_point(g, "teammate goal")));
            planner::PlanResult r;
            {
              ReleasedGil release;
              r = pm.mission->next(a, goals);
            }
            py::dict out;
            py::list path;
            for (const Vec2& q : r.path)
              path.append(from_point(map.to_frame(q)));
            out["goal"] = from_point(map.to_frame(r.goal));
            out["path"] = path;
            out["length"] = r.length;
            return out;
          },
          py::arg("robot"), py::arg("teammate_goals") = py::list(),
          "Where to sample next from `robot`: 'goal', the planner's 'path' there and its "
          "'length'. `teammate_goals`: where teammates are about to sample; planned as if they "
          "had, reading what the belief predicts (a collaborative team's virtual samples). "
          "InputError once the mission has stopped.")
      .def_property_readonly("samples", [](const PyMission& pm) { return pm.mission->samples(); })
      .def_property_readonly("stopped", [](const PyMission& pm) { return pm.mission->stopped(); })
      .def_property_readonly(
          "stopped_by", [](const PyMission& pm) { return pm.mission->stopped_by(); },
          "'entropy', 'max_samples', or '' while it goes on")
      .def_property_readonly(
          "posterior",
          [](const PyMission& pm) {
            if (pm.mission->samples() == 0)
              throw InputError("the mission has no sample yet: there is no posterior");
            return posterior_dict(pm.scenario->map(), pm.mission->posterior());
          },
          "The posterior after the last sample");
}

void bind_scenario(py::module_& m) {
  py::class_<run::Scenario, std::shared_ptr<run::Scenario>>(
      m, "Scenario",
      "What STE needs for one map, built once: the wind, the plume model, the planner. Keyword "
      "arguments set SteOptions fields.")
      .def(py::init([](const Map& map, const py::object& options, const py::kwargs& kw) {
             return make_scenario(map, ste_options(options, kw, "Scenario"));
           }),
           py::arg("map"), py::arg("options") = py::none())
      .def_property_readonly("map", [](const run::Scenario& sc) { return sc.map(); })
      .def_property_readonly(
          "options", [](const run::Scenario& sc) { return sc.options(); },
          "The SteOptions it was built with (a copy)")
      .def_property_readonly(
          "wind",
          [](const run::Scenario& sc) {
            auto w = std::make_shared<Wind>();
            w->map = std::make_shared<const Map>(sc.map());
            w->field = sc.wind();
            return w;
          },
          "The scenario's wind (a copy)")
      .def("run", &run_once, py::arg("source"), py::arg("start") = py::none(),
           py::arg("seed") = kDefaultSeed, py::arg("animate") = py::none(),
           "One simulated localization (`plumekit localize --json`'s summary as a dict); "
           "animate='run.mp4' (or .png) draws its replay there (docs/replay.md)")
      .def(
          "mission",
          [](std::shared_ptr<run::Scenario> sc, std::uint64_t seed) {
            auto pm = std::make_unique<PyMission>();
            pm->scenario = sc;
            pm->estimator = sc->make_estimator(world::run_seed(seed, 0, 0, 0));
            pm->mission = std::make_unique<ste::Mission>(*pm->estimator, sc->planner(),
                                                         sc->navigator(), sc->options().stop);
            return pm;
          },
          py::arg("seed") = kDefaultSeed,
          "A Mission on this scenario, for readings the caller brings (`seed` drives MH)");
}

py::object evaluate_maps(const py::object& maps, int runs, std::uint64_t seed, int seeds,
                         int threads, int source_count, const py::object& progress,
                         const py::object& options, const py::kwargs& kw) {
  std::vector<Map> list;
  std::filesystem::path dir;
  if (py::isinstance<py::str>(maps) || py::hasattr(maps, "__fspath__")) {
    dir = py::str(maps).cast<std::string>();
    list = run::read_map_folder(dir).maps;
  } else {
    list = maps.cast<std::vector<Map>>();
  }
  // method=[...] (a list): several methods in one plume per run (docs/design/evaluation.md,
  // "Several methods in one world"), a summary each.
  std::vector<std::string> kinds;
  py::dict rest;
  for (const auto& item : kw) {
    const std::string key = py::str(item.first);
    if (key == "method" && py::isinstance<py::list>(item.second)) {
      std::string names;
      for (const py::handle& name : item.second)
        names += (names.empty() ? "" : ",") + py::str(name).cast<std::string>();
      kinds = run::parse_method_list(names);
    } else {
      rest[item.first] = item.second;
    }
  }
  run::EvaluationOptions eo;
  eo.ste = ste_options(options, py::reinterpret_borrow<py::kwargs>(rest), "evaluate");
  eo.runs = runs;
  eo.seed = seed;
  eo.seeds = seeds;
  eo.threads = threads;
  eo.source_count = source_count;
  std::function<void(int, int)> report;
  if (!progress.is_none())
    report = [&progress](int done, int total) {
      py::gil_scoped_acquire acquire;
      progress(done, total);
    };
  const bool several = !kinds.empty();
  if (!several) kinds = {eo.ste.method.name};
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  {
    ReleasedGil release;
    const std::vector<run::EvaluationResult> results =
        run::evaluate_methods(list, eo, kinds, report);
    for (std::size_t m = 0; m < kinds.size(); ++m) {
      nlohmann::ordered_json one = run::method_report(results[m], eo, kinds[m], dir, "").json;
      one["timings"] = run::evaluation_timings(results[m]);
      if (!several)
        j = one;
      else
        j[kinds[m]] = one;
    }
  }
  return from_json(j);
}

}  // namespace

void bind_ste(py::module_& m) {
  bind_mission(m);
  bind_scenario(m);
  m.def(
      "localize",
      [](const Map& map, const py::handle& source, const py::object& start, std::uint64_t seed,
         const py::object& options, const py::object& animate, const py::kwargs& kw) {
        const auto sc = make_scenario(map, ste_options(options, kw, "localize"));
        return run_once(*sc, source, start, seed, animate);
      },
      py::arg("map"), py::arg("source"), py::arg("start") = py::none(),
      py::arg("seed") = kDefaultSeed, py::arg("options") = py::none(),
      py::arg("animate") = py::none(),
      "A simulated robot localizes the source (`plumekit localize`; the same seed gives the same "
      "run). Returns its summary dict: 'estimate', 'error_m', 'samples', 'steps', ...; "
      "animate='run.mp4' (or .png) draws the mission's replay there ('animation' in the dict)");
  m.def("replay", &replay_run, py::arg("run_dir"), py::arg("out"), py::arg("fps") = 10.0,
        py::arg("size") = py::none(),
        "Draws a run's recorded replay again (`plumekit replay RUN_DIR --out FILE`): the folder "
        "of `plumekit localize --out DIR --animate FILE`; out is FILE.mp4 or FILE.png. Returns "
        "{'title', 'file', 'format', 'frames', ('note')}.");
  m.def("evaluate", &evaluate_maps, py::arg("maps"), py::arg("runs") = 3,
        py::arg("seed") = kDefaultSeed, py::arg("seeds") = 1, py::arg("threads") = 0,
        py::arg("source_count") = 0, py::arg("progress") = py::none(),
        py::arg("options") = py::none(),
        "Every source of every map (or the first `source_count`), `runs` times each (`plumekit "
        "evaluate`): `maps` is a list of Map or a folder of map files. Returns summary.json's "
        "content, with the measured times under 'timings'. `progress(done, total)` is called "
        "after each run. With method=[names], every method samples one plume per run and the "
        "result is a dict of their summaries by name.");
  m.def(
      "methods",
      [] {
        py::list out;
        for (const methods::MethodSpec& s : methods::method_registry())
          out.append(py::dict(py::arg("name") = s.name, py::arg("description") = s.description,
                              py::arg("source") = s.source,
                              py::arg("uses_plume_model") = s.traits.uses_plume_model,
                              py::arg("ends") = methods::to_string(s.traits.ends)));
        return out;
      },
      "The localization methods (the registry, methods/registry.hpp), in --method's order: a "
      "dict each with 'name', 'description', 'source', 'uses_plume_model', 'ends'.");
  m.def(
      "data_dir", [] { return data_dir(); },
      "The shipped data folder ($PLUMEKIT_DATA, else the source tree's data/)");
}

std::string data_dir() {
  if (const char* env = std::getenv("PLUMEKIT_DATA"); env && *env) return env;
  return PLUMEKIT_DATA_DIR;
}

}  // namespace plumekit::python
