// The 3-D wind tunnel (`plumekit localize tunnel`, `evaluate tunnel`; run/tunnel_run.hpp): seed
// 004's 3-D STE, surge-spiral and 2-D surge-cast, with the command's options as keywords.
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "core/animation.hpp"
#include "core/error.hpp"
#include "core/seed.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "run/replay.hpp"
#include "run/replay_render.hpp"
#include "run/tunnel_report.hpp"
#include "run/tunnel_run.hpp"

namespace plumekit::python {

namespace {

Vec3 to_point3(const std::vector<double>& v, const char* what) {
  if (v.size() != 3)
    throw InputError(std::string(what) + ": expected a point (x, y, z) in metres, got " +
                     std::to_string(v.size()) + " numbers");
  return {v[0], v[1], v[2]};
}

// The command's flags, in the library's fields.
run::TunnelOptions tunnel_options(const std::string& method, const std::vector<double>& tunnel,
                                  double wind_speed, double release_rate, double threshold,
                                  double time_limit, double noise, double sigma_rel) {
  run::TunnelOptions o;
  o.method = run::parse_tunnel_method(method);
  const Vec3 size = to_point3(tunnel, "tunnel");
  o.tunnel.length = size.x, o.tunnel.width = size.y, o.tunnel.height = size.z;
  o.tunnel.speed = wind_speed;
  o.world.filament.release_rate = release_rate;
  o.search.threshold = threshold;
  o.time_limit_s = time_limit;
  o.world.noise = noise;
  o.ste.likelihood.sigma_rel = sigma_rel;
  o.validate();
  return o;
}

}  // namespace

void bind_tunnel(py::module_& m) {
  m.def(
      "localize_tunnel",
      [](const std::string& method, const std::optional<std::vector<double>>& source,
         const std::optional<std::vector<double>>& start, std::uint64_t seed,
         const std::vector<double>& tunnel, double wind_speed, double release_rate,
         double threshold, double time_limit, double noise, double sigma_rel,
         const py::object& animate) {
        const run::TunnelOptions o = tunnel_options(method, tunnel, wind_speed, release_rate,
                                                    threshold, time_limit, noise, sigma_rel);
        std::optional<Vec3> src, from;
        if (source) src = to_point3(*source, "source");
        if (start) from = to_point3(*start, "start");
        const std::string animation = animate.is_none() ? "" : py::str(animate).cast<std::string>();
        if (!animation.empty()) check_animation_target(animation, "animate");
        nlohmann::ordered_json j;
        {
          ReleasedGil release;
          std::optional<run::Replay> replay;
          const run::TunnelRun r =
              run::localize_tunnel(o, src, from, seed, 0, animation.empty() ? nullptr : &replay);
          j = run::tunnel_run_json(r, true);
          if (replay) {
            std::string text;  // the command's line; Python takes the dict
            run::report_animation(run::animate_replay(*replay, animation, "animate"), j, text);
          }
        }
        return from_json(j);
      },
      py::arg("method") = "ste-3d", py::arg("source") = py::none(), py::arg("start") = py::none(),
      py::arg("seed") = kDefaultSeed, py::arg("tunnel") = std::vector<double>{10.0, 4.0, 2.0},
      py::arg("wind_speed") = 0.9, py::arg("release_rate") = 1000.0, py::arg("threshold") = 0.7,
      py::arg("time_limit") = 720.0, py::arg("noise") = 0.0, py::arg("sigma_rel") = 0.5,
      py::arg("animate") = py::none(),
      "One run in seed 004's 3-D wind tunnel (`plumekit localize tunnel`): method 'ste-3d', "
      "'surge-spiral' or 'surge-cast-2d'; points (x, y, z) in metres, x downwind, z up; random "
      "when None (the same seed, the same run). Returns run.json's content: 'estimate', "
      "'error_m', 'error_xyz_m', 'stopped_by', 'steps', ...; animate='run.mp4' (or .png) draws "
      "its replay there, seen from above and from the side (docs/replay.md)");
  m.def(
      "evaluate_tunnel",
      [](const std::string& method, int runs, std::uint64_t seed, int threads,
         const std::vector<double>& tunnel, double wind_speed, double release_rate,
         double threshold, double time_limit, double noise, double sigma_rel) {
        const run::TunnelOptions o = tunnel_options(method, tunnel, wind_speed, release_rate,
                                                    threshold, time_limit, noise, sigma_rel);
        nlohmann::ordered_json j;
        {
          ReleasedGil release;
          j = run::tunnel_summary(run::evaluate_tunnel(o, runs, seed, threads));
        }
        return from_json(j);
      },
      py::arg("method") = "ste-3d", py::arg("runs") = 10, py::arg("seed") = kDefaultSeed,
      py::arg("threads") = 0, py::arg("tunnel") = std::vector<double>{10.0, 4.0, 2.0},
      py::arg("wind_speed") = 0.9, py::arg("release_rate") = 1000.0, py::arg("threshold") = 0.7,
      py::arg("time_limit") = 720.0, py::arg("noise") = 0.0, py::arg("sigma_rel") = 0.5,
      "`runs` runs of one method over random sources and starts (`plumekit evaluate tunnel`); "
      "returns summary.json's medians and rates.");
}

}  // namespace plumekit::python
