#pragma once
// Adaptive sampling with an artificial potential field (seed 000 ch. 8, after Asadi; digest
// ../shared/notes/seed-000-neumann-thesis.md §1.14): at each stop the Kernel DM+V(/W) maps of the
// readings so far give an APF that attracts the robot to high mean, high variance and low
// confidence; n_sp suggestions are picked greedily from it, each repelling the next, and a
// locality constraint picks the one to fly to (SPPAM).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "core/grid.hpp"
#include "map/map.hpp"
#include "methods/kernel_dmv.hpp"
#include "methods/method.hpp"

namespace plumekit::methods {

// How the goal is chosen from the suggestions (seed 000 §8.2.1).
enum class Locality {
  None,           // adaptive SP: the first (highest-APF) suggestion
  Closest,        // A: the suggestion closest to the robot (eq. 8.8)
  MostSuggested,  // B: the suggestion with the highest S / d, S the counter matrix
};
const char* to_string(Locality l);
// "none", "closest" (or "a"), "most-suggested" (or "b"); OptionError on apf.locality otherwise.
Locality parse_locality(const std::string& name);

struct ApfOptions {
  // Importance factors of the mean, variance and confidence terms (eq. 8.4); they sum to 1
  // (eq. 8.5). The seed's best: (0.1, 0.1, 0.8).
  double beta_m = 0.1, beta_v = 0.1, beta_c = 0.8;
  int suggestions = 10;  // n_sp
  double charge = -1.0;  // q of each picked suggestion's repulsion (eq. 8.7); <= 0
  double sigma_d = 1.0;  // m, the repulsion's length: q exp(-d / sigma_d)
  Locality locality = Locality::Closest;
  double counter_radius = 0.5;  // m, locality B: neighbours counted (and reset) with a cell
  // m: cells closer than this to the robot are never suggested (the drone's minimum step).
  double min_step = 1.0;
  int max_steps = 206;  // stops before stopped_by() says "max_samples" (the seed's 206)
  // Stop ("confident") once the confidence exceeds this in every free cell; 0 never stops so.
  double confidence_stop = 0.9;
  // Divide the mean and variance maps by their largest value over the free cells before weighting
  // them, so that they lie in [0, 1] like the confidence (the seed's maps were of normalised
  // concentrations; plumekit's readings run to thousands).
  bool normalise = true;
  // The maps (ch. 8's simulations: 0.1 m cells, sigma 0.4 m, sigma_Omega 1, minimum reading as
  // background; gamma 0.2 s, the seed's outdoor value, for plumekit's ~1 m/s winds).
  GdmOptions gdm = default_gdm();
  // Which of source_estimates()'s six names estimate() reports.
  std::string estimator = "90% area mean x variance";

  static GdmOptions default_gdm();
  // OptionError naming the field ("apf.beta_c", ...) and its range.
  void validate() const;
};

// The default weights as --apf-weights takes them: "0.1,0.1,0.8".
std::string default_weights();

// beta_m r' + beta_v v' - beta_c alpha per cell (eqs. 8.1-8.4), r' and v' the mean and variance,
// normalised when options.normalise; NaN in obstacle cells.
Grid<double> apf_field(const GdmMaps& maps, const ApfOptions& options);

struct ApfSuggestion {
  Vec2 position;       // the cell's centre
  int i = 0, j = 0;    // the cell
  double value = 0.0;  // the APF there when it was picked (eq. 8.6, earlier picks' repulsion in)
};

// The n_sp suggestions in pick order: each the free cell of largest APF, at least min_step from
// `robot`, after which beta_c q exp(-d / sigma_d) is added around it (eqs. 8.6-8.7). When no free
// cell is min_step away (an arena smaller than a step), nearer cells are allowed. InputError when
// `maps` do not cover `map`'s arena.
std::vector<ApfSuggestion> apf_suggestions(const GdmMaps& maps, const Map& map,
                                           const ApfOptions& options, Vec2 robot);

// Locality B's matrix S: how often each cell (or a neighbour within the radius) was suggested since
// the robot last stood within the radius of it.
class SuggestionCounter {
 public:
  SuggestionCounter() = default;
  SuggestionCounter(const GridShape& shape, double radius);
  void suggest(Vec2 p);     // +1 on p's cell and every cell whose centre is within the radius of p
  void visit(Vec2 p);       // 0 on the same cells
  int count(Vec2 p) const;  // S at p's cell (0 outside the grid)
  const Grid<int>& counts() const { return counts_; }

 private:
  template <class F>
  void for_each_near(Vec2 p, F&& f);
  Grid<int> counts_;
  double radius_ = 0.0;
};

// The index of the suggestion chosen by locality A (the closest to `robot`) or B (the highest
// S / d, d at least half a cell); ties go to the earlier (higher-APF) pick. The list is not empty.
std::size_t choose_closest(const std::vector<ApfSuggestion>& s, Vec2 robot);
std::size_t choose_most_suggested(const std::vector<ApfSuggestion>& s,
                                  const SuggestionCounter& counter, Vec2 robot);

// SPPAM as a localization method ("apf"): each stop becomes a sample, the maps are rebuilt, and
// next() flies to the suggestion the locality constraint picks.
class ApfMapping : public methods::LocalizationMethod {
 public:
  // OptionError for bad options; `area.map` must outlive the method.
  ApfMapping(const methods::SearchArea& area, const ApfOptions& options);
  std::string name() const override { return "apf"; }
  void observe(const methods::Observation& o) override;
  methods::Move next(Vec2 robot) override;
  // options.estimator's estimate from the latest maps; nullopt before the first sample.
  std::optional<Vec2> estimate() const override;
  // "confident", "max_samples" or "".
  std::string stopped_by() const override;

  // The maps of every sample so far (empty grids before the first).
  const GdmMaps& maps() const { return maps_; }
  const std::vector<Sample>& samples() const { return samples_; }
  // The latest next()'s suggestions, in pick order, and the index it chose.
  const std::vector<ApfSuggestion>& suggestions() const { return suggestions_; }
  std::size_t chosen() const { return chosen_; }
  const SuggestionCounter& counter() const { return counter_; }

 private:
  methods::SearchArea area_;
  ApfOptions options_;
  std::vector<Sample> samples_;
  GdmMaps maps_;
  double min_confidence_ = 0.0;  // over the free cells of maps_
  std::vector<ApfSuggestion> suggestions_;
  std::size_t chosen_ = 0;
  SuggestionCounter counter_;
};

std::unique_ptr<methods::LocalizationMethod> make_apf_mapping(const methods::SearchArea& area,
                                                              const ApfOptions& options);

}  // namespace plumekit::methods
