#pragma once
// `plumekit localize tunnel` and `evaluate tunnel` as one call each (apps/ parses the flags into
// a request and prints the Report): the runs of run/tunnel_run.hpp, their files and pictures in
// the output folder, and the summary.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "core/geometry.hpp"
#include "core/report.hpp"
#include "core/seed.hpp"
#include "core/thread_pool.hpp"
#include "run/evaluate_job.hpp"
#include "run/tunnel_run.hpp"

namespace plumekit::run {

struct TunnelLocalizeRequest {
  TunnelOptions options;
  std::optional<Vec3> source, start;  // none: random (localize_tunnel)
  std::uint64_t seed = kDefaultSeed;
  std::filesystem::path out;  // empty: no files; else run.json and trajectory.png
  // A replay of the mission, seen from above and from the side, as a video (.mp4) or animated
  // PNG (.png); empty: none. With `out`, the run's replay files too, for `plumekit replay`.
  std::filesystem::path animate;
  bool progress = false;  // a progress bar while the replay is drawn
};
// One run: its summary (run.json without the steps), and with an output folder the files.
Report localize_tunnel_job(const TunnelLocalizeRequest& request);

struct TunnelEvaluateRequest {
  TunnelOptions options;             // the method is replaced by each of `methods`
  std::vector<std::string> methods;  // several: each into out/NAME/
  int runs = 10, threads = kDefaultThreads;
  std::uint64_t seed = kDefaultSeed;
  std::filesystem::path out = "out/evaluate-tunnel";
  bool replays = false;  // every run's replay into replays/tunnel-rN/ (slower; the same runs)
};
// Each method's runs.csv, summary.json, boxplot.png, trajectory-median.png, tracks.json and
// report.html (run/tunnel_page.hpp), with several methods OUT/report.html of all, the output
// written whole; returns every method's summary and a line each. `progress` counts the runs of
// all.
Report evaluate_tunnel_job(const TunnelEvaluateRequest& request, const JobProgress& progress = {});

// The run a picture of an evaluation shows: STE's of median error, a tracker's of median time.
std::size_t median_tunnel_run(const std::vector<TunnelRun>& runs);

}  // namespace plumekit::run
