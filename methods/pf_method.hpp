#pragma once
// The particle filter (particle_filter.hpp) as a localization method: the filter estimates, an
// exploration strategy (any LocalizationMethod: the seeds' pseudo-gradient tracker, or the
// predefined sweep below) decides where to go. Seed 001 Sec. III, seed 000 Ch. 6.
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/seed.hpp"
#include "methods/method.hpp"
#include "methods/particle_filter.hpp"

namespace plumekit::methods {

// The explorations the seeds tuned (alpha, beta) for.
enum class PfExploration { Sweep, Gradient };

// `base` with the seeds' best (alpha, beta) for an exploration (seed 001 Sec. V.B): (0.4, 0.9)
// for the predefined sweep, (0.2, 0.8) for the pseudo-gradient tracker.
ParticleFilterOptions pf_options_for(PfExploration exploration, ParticleFilterOptions base = {});

struct SweepPatternOptions {
  double step = 1.0;     // m between lines and between the stops on a line (the seeds' 1 m)
  int max_steps = 2000;  // stops before stopped_by() says "max_samples"

  // OptionError naming the field ("sweep.step", ...).
  void validate() const;
};

// The predefined sweep of seed 000 Sec. 6.2.1 (start (32, 0) in the 32 x 8 m tunnel with the wind
// along +x, 1 m steps), generalised: a boustrophedon of lines across the first observation's wind,
// `step` apart, from the downwind end of the search rectangle to its upwind end, with stops `step`
// apart along each line. Stops outside the rectangle or in an obstacle are left out. The first
// line starts at its end nearer to the robot's first position; each next line starts where the
// last ended. A calm first wind sweeps as for a wind along +x (plumekit's arenas blow along +x).
// It ends ("swept") once the robot has stood at the last stop; a stop closer than half a step to
// the robot when it is due (the start, or a goal the runner could not reach) is passed over.
class PredefinedSweep : public LocalizationMethod {
 public:
  PredefinedSweep(const SearchArea& area, const SweepPatternOptions& options = {});
  std::string name() const override { return "predefined-sweep"; }
  void observe(const Observation& o) override;
  Move next(Vec2 robot) override;
  std::optional<Vec2> estimate() const override { return std::nullopt; }
  std::string stopped_by() const override;
  // The stops in order; empty before the first observation.
  const std::vector<Vec2>& pattern() const { return pattern_; }

 private:
  void build(Vec2 start, Vec2 wind);

  SearchArea area_;
  SweepPatternOptions options_;
  std::vector<Vec2> pattern_;
  std::size_t next_ = 0;
  int stops_ = 0;
  bool built_ = false;
  bool awaiting_ = false;  // a stop was handed out and not yet observed
};

// The sweep's stops for a wind `wind` in the rectangle of `area` (see PredefinedSweep).
std::vector<Vec2> sweep_pattern(const SearchArea& area, Vec2 start, Vec2 wind, double step);

struct PfMethodOptions {
  ParticleFilterOptions filter;
  // Declaration (seed 001: "the estimate remains within a small region for a defined number of
  // iterations"; no values given): the run declares when the last `declare_iterations` MNEs all
  // lie within `declare_radius` of the newest one, counting from the first detection on (before
  // it the particles hold no evidence of gas). 0, the default, never declares: the run ends when
  // the explorer stops or at max_steps, and the MNE then is scored, as in all the seeds' results.
  // Li et al.'s 20 within 0.5 m declares too early here: the MNE moves only when the particles
  // are resampled (every 5-10 stops in a sweep), so it "stays" while the robot is still downwind
  // of the source, before anything penalised the particles upwind of it.
  double declare_radius = 0.5;  // m
  int declare_iterations = 0;
  int max_steps = 2000;  // stops before stopped_by() says "max_samples"
  std::uint64_t seed = kDefaultSeed;

  // OptionError naming the field ("pf.declare_radius", ...); validates `filter` too.
  void validate() const;
};

class ParticleFilterMethod : public LocalizationMethod {
 public:
  // `explorer` decides where to go (it never sees the filter). `name` empty: "pf-" and the
  // explorer's name.
  ParticleFilterMethod(const SearchArea& area, std::unique_ptr<LocalizationMethod> explorer,
                       const PfMethodOptions& options = {}, std::string name = "");
  std::string name() const override { return name_; }
  // Updates the filter, then lets the explorer observe. InputError for a non-finite reading.
  void observe(const Observation& o) override;
  Move next(Vec2 robot) override { return explorer_->next(robot); }
  // The MNE, from the first observation on.
  std::optional<Vec2> estimate() const override;
  // "declared", else the explorer's reason when it stopped, else "max_samples" at max_steps.
  std::string stopped_by() const override;

  const ParticleFilter& filter() const { return filter_; }
  // The final weights binned on 0.1 m cells: the run picture's "posterior".
  std::optional<Grid<double>> belief_map(const Map& map) const override;
  const LocalizationMethod& explorer() const { return *explorer_; }
  int steps() const { return steps_; }

 private:
  PfMethodOptions options_;
  ParticleFilter filter_;
  std::unique_ptr<LocalizationMethod> explorer_;
  std::string name_;
  std::deque<Vec2> recent_;  // the latest MNEs since the first detection
  bool detected_ = false;
  bool declared_ = false;
  int steps_ = 0;
};

// The PF with the predefined sweep, named "pf-sweep". The filter's default (alpha, beta) are
// the seeds' best for it; a PF with the pseudo-gradient tracker takes
// pf_options_for(PfExploration::Gradient) and the tracker as its explorer ("pf-gradient").
std::unique_ptr<LocalizationMethod> make_pf_sweep(const SearchArea& area,
                                                  const PfMethodOptions& options = {},
                                                  const SweepPatternOptions& sweep = {});

}  // namespace plumekit::methods
