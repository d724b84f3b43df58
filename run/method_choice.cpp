#include "run/method_choice.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/option_check.hpp"

namespace plumekit::run {

namespace {

struct Named {
  MethodKind kind;
  const char* name;
};
constexpr Named kMethods[] = {
    {MethodKind::Ste, "ste"},
    {MethodKind::Sweeping, "sweeping"},
    {MethodKind::SurgeCast, "surge-cast"},
    {MethodKind::Zigzag, "zigzag"},
    {MethodKind::PseudoGradient, "pseudo-gradient"},
    {MethodKind::PfGradient, "pf-gradient"},
    {MethodKind::PfSweep, "pf-sweep"},
    {MethodKind::Apf, "apf"},
    {MethodKind::LevyTaxis, "levy-taxis"},
    {MethodKind::SteLocal, "ste-local"},
};

}  // namespace

const char* to_string(MethodKind kind) {
  for (const Named& m : kMethods)
    if (m.kind == kind) return m.name;
  return "?";
}

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const Named& m : kMethods)
    names.emplace_back(m.name);
  return names;
}

MethodKind parse_method_kind(const std::string& name) {
  for (const Named& m : kMethods)
    if (name == m.name) return m.kind;
  std::string all;
  for (const Named& m : kMethods)
    all += std::string(all.empty() ? "" : ", ") + m.name;
  throw OptionError("ste.method", "unknown method '" + name + "'; use one of " + all);
}

std::vector<MethodKind> parse_method_list(const std::string& text) {
  std::vector<MethodKind> kinds;
  if (text == "all") {
    for (const Named& m : kMethods)
      kinds.push_back(m.kind);
    return kinds;
  }
  std::size_t from = 0;
  for (;;) {
    const std::size_t comma = text.find(',', from);
    const MethodKind k = parse_method_kind(text.substr(from, comma - from));
    if (std::find(kinds.begin(), kinds.end(), k) != kinds.end())
      throw OptionError("ste.method",
                        std::string(to_string(k)) + " is named twice in '" + text + "'");
    kinds.push_back(k);
    if (comma == std::string::npos) return kinds;
    from = comma + 1;
  }
}

bool stops_in_source_box(MethodKind kind) {
  return kind == MethodKind::Sweeping || kind == MethodKind::SurgeCast ||
         kind == MethodKind::Zigzag || kind == MethodKind::PseudoGradient;
}

bool ends_on_arrival(MethodKind kind) {
  return stops_in_source_box(kind) || kind == MethodKind::LevyTaxis;
}

methods::PfMethodOptions MethodOptions::pf_in_use() const {
  methods::PfMethodOptions o = pf;
  o.filter = methods::pf_options_for(kind == MethodKind::PfSweep ? methods::PfExploration::Sweep
                                                                 : methods::PfExploration::Gradient,
                                     pf.filter);
  if (pf_alpha) o.filter.alpha = *pf_alpha;
  if (pf_beta) o.filter.beta = *pf_beta;
  o.filter.detection_limit = tracking.detection_threshold;
  o.max_steps = tracking.max_steps;
  return o;
}

int MethodOptions::max_steps_in_use(double area) const {
  if (max_steps > 0) return max_steps;
  return std::max(50, static_cast<int>(std::ceil(2.0 * area / (tracking.step * tracking.step))));
}

void MethodOptions::validate() const {
  check_count("tracking.max_steps", max_steps, 0, 10000000, "0 means auto");
  tracking.validate();
  pf_in_use().validate();
  apf.validate();
  levy.validate();
  local.validate();
}

std::unique_ptr<methods::LocalizationMethod> make_method(const MethodOptions& given,
                                                         const methods::SearchArea& area,
                                                         std::uint64_t seed) {
  MethodOptions options = given;
  options.validate();
  options.tracking.max_steps = given.max_steps_in_use(area.width() * area.height());
  switch (options.kind) {
    case MethodKind::Ste:
      throw std::logic_error("make_method: STE is built by its Scenario");
    case MethodKind::Sweeping:
      return methods::make_sweeping(area, options.tracking);
    case MethodKind::SurgeCast:
      return methods::make_surge_cast(area, options.tracking);
    case MethodKind::Zigzag:
      return methods::make_zigzag(area, options.tracking);
    case MethodKind::PseudoGradient:
      return methods::make_pseudo_gradient(area, options.tracking);
    case MethodKind::PfGradient:
    case MethodKind::PfSweep: {
      methods::PfMethodOptions pf = options.pf_in_use();
      pf.seed = seed;
      std::unique_ptr<methods::LocalizationMethod> explorer;
      if (options.kind == MethodKind::PfGradient)
        explorer = methods::make_pseudo_gradient(area, options.tracking);
      else
        explorer = std::make_unique<methods::PredefinedSweep>(
            area, methods::SweepPatternOptions{options.tracking.step, options.tracking.max_steps});
      return std::make_unique<methods::ParticleFilterMethod>(area, std::move(explorer), pf,
                                                             to_string(options.kind));
    }
    case MethodKind::Apf: {
      methods::ApfOptions apf = options.apf;
      apf.max_steps = options.tracking.max_steps;
      return methods::make_apf_mapping(area, apf);
    }
    case MethodKind::LevyTaxis: {
      methods::LevyTaxisOptions levy = options.levy;
      levy.max_steps = options.tracking.max_steps;
      return std::make_unique<methods::AdaptiveLevyTaxis>(levy, seed);
    }
    case MethodKind::SteLocal: {
      methods::LocalFrameworkOptions local = options.local;
      local.max_samples = options.tracking.max_steps;
      return std::make_unique<methods::LocalFrameworkSte>(local, seed);
    }
  }
  throw std::logic_error("make_method: unknown method");
}

}  // namespace plumekit::run
