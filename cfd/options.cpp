#include "cfd/options.hpp"

#include <cmath>
#include <string>

#include "cfd/grid_check.hpp"
#include "core/error.hpp"
#include "core/option_check.hpp"
#include "map/map.hpp"

namespace plumekit::cfd {

namespace {

template <class E>
struct Named {
  E value;
  const char* name;
};
constexpr Named<Turbulence> kTurbulence[] = {{Turbulence::None, "none"},
                                             {Turbulence::MixingLength, "mixing-length"}};
constexpr Named<Convection> kConvection[] = {{Convection::Upwind, "upwind"},
                                             {Convection::Central, "central"},
                                             {Convection::VanLeer, "vanleer"}};
constexpr Named<LinearSolverKind> kLinearSolver[] = {{LinearSolverKind::Nullspace, "nullspace"},
                                                     {LinearSolverKind::Coupled, "coupled"}};

template <class E, std::size_t N>
const char* name_of(const Named<E> (&table)[N], E value) {
  for (const Named<E>& n : table)
    if (n.value == value) return n.name;
  return "?";
}

template <class E, std::size_t N>
std::string names_of(const Named<E> (&table)[N]) {
  std::string names;
  for (const Named<E>& n : table)
    names += (names.empty() ? "" : ", ") + std::string(n.name);
  return names;
}

template <class E, std::size_t N>
E parse(const Named<E> (&table)[N], const std::string& name, const std::string& field) {
  for (const Named<E>& n : table)
    if (name == n.name) return n.value;
  throw OptionError(field, "unknown name '" + name + "'; use one of " + names_of(table));
}

}  // namespace

const char* to_string(Turbulence t) {
  return name_of(kTurbulence, t);
}
const char* to_string(Convection c) {
  return name_of(kConvection, c);
}
const char* to_string(LinearSolverKind k) {
  return name_of(kLinearSolver, k);
}
std::string turbulence_names() {
  return names_of(kTurbulence);
}
std::string convection_names() {
  return names_of(kConvection);
}
std::string linear_solver_names() {
  return names_of(kLinearSolver);
}

Turbulence parse_turbulence(const std::string& name) {
  return parse(kTurbulence, name, "flow.turbulence");
}
Convection parse_convection(const std::string& name) {
  return parse(kConvection, name, "flow.convection");
}
LinearSolverKind parse_linear_solver(const std::string& name) {
  return parse(kLinearSolver, name, "flow.linear_solver");
}

double resolved_cell(double width, double height, const FlowOptions& options) {
  if (options.cell != 0.0) return options.cell;
  auto cells = [&](double cell) { return std::round(width / cell) * std::round(height / cell); };
  if (cells(kDefaultCell) <= kAutoCellMaxCells) return kDefaultCell;
  // The next "nice" cell up from the one that gives exactly the limit.
  const double exact = std::sqrt(width * height / kAutoCellMaxCells);
  double decade = std::pow(10.0, std::floor(std::log10(exact)));
  constexpr double kSteps[] = {1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8};
  for (int guard = 0; guard < 40; ++guard, decade *= 10.0)
    for (double step : kSteps)
      if (step * decade >= exact * (1 - 1e-12) && cells(step * decade) <= kAutoCellMaxCells)
        return step * decade;
  return exact;  // not reached: some step of a decade always fits
}

double resolved_cell(const Map& map, const FlowOptions& options) {
  return resolved_cell(map.width, map.height, options);
}

// The upper bounds are far beyond any useful setting; they catch unit
// mistakes and typos (a cell of 50 m, a viscosity of 1e9) before a solve that
// cannot succeed.
const OptionTable<FlowOptions>& flow_option_table() {
  using O = FlowOptions;
  static const OptionTable<O> table{
      "Flow (cfd::FlowOptions)",
      {{"flow.cell", "--cell", &O::cell, zero_or(positive(kMaxCell, "m")),
        "Flow cell size, m; 0: " + compact(kDefaultCell) + " m, or on arenas whose " +
            option_number(kDefaultCell * 100) + " cm grid would exceed " +
            option_number(kAutoCellMaxCells) +
            " cells, the round size that gives at most that many",
        "{default} (the default) is " + compact(kDefaultCell) + " m, or coarser on arenas over " +
            option_number(kAutoCellMaxCells) + " such cells"},
       {"flow.strict_gaps",
        "--strict-gaps",
        &O::strict_gaps,
        {},
        "Refuse a map with gaps open in it but narrower than a cell, instead of closing them "
        "with a warning"},
       {"flow.nu", "--nu", &O::nu, positive(10.0, "m^2/s"),
        "Kinematic (effective) viscosity, m^2/s",
        "the default is {default} m^2/s (air's molecular value is 1.5e-05)"},
       {"flow.turbulence",
        "--turbulence",
        enum_field(&O::turbulence, &to_string, &parse_turbulence, turbulence_names()),
        {},
        "Turbulence closure: " + turbulence_names()},
       {"flow.convection",
        "--convection",
        enum_field(&O::convection, &to_string, &parse_convection, convection_names()),
        {},
        "Convection scheme: " + convection_names() +
            " (vanleer: bounded, 2nd order; central: 2nd order; upwind: 1st order)"},
       {"flow.upwind_fallback",
        "--upwind-fallback",
        &O::upwind_fallback,
        {},
        "When central or vanleer convection does not converge, solve again with upwind (the "
        "report says so); false: fail instead"},
       {"flow.tolerance", "--tol", &O::tolerance, real_range(1e-14, 0.1, ""),
        "Stop when both normalised residuals are below this"},
       {"flow.max_iterations", "--max-iter", &O::max_iterations, count_range(0, 100000),
        "Give up after this many Newton iterations (0: 100, or 300 with mixing-length)",
        "0 means the default (100, or 300 with the mixing-length closure)"},
       {"flow.linear_solver",
        "--linear-solver",
        enum_field(&O::linear_solver, &to_string, &parse_linear_solver, linear_solver_names()),
        {},
        "Newton systems: " + linear_solver_names() +
            " (nullspace: divergence-free subspace, one unknown per grid node; coupled: u, v, "
            "p; same steps, coupled is slower)"},
       {"flow.verbose",
        "--verbose",
        &O::verbose,
        {},
        "Print the residuals of every iteration on stderr"},
       {"flow.kappa", "", &O::kappa, positive(1.0, ""), "Mixing-length (von Karman's) constant",
        "von Karman's constant is {default}"},
       {"flow.lm_max", "", &O::lm_max, real_range(-1e3, 1e3, "m"),
        "Mixing-length cap, m (0 or less: 0.09 times half the arena's smaller side)",
        "0 or less means 0.09 times half the arena's smaller side"},
       {"flow.closed", "", &O::closed, {}, "Openings are walls (a closed cavity)"},
       {"flow.sequencing",
        "",
        &O::sequencing,
        {},
        "Start Newton from the flow on a grid twice as coarse"}}};
  return table;
}

void FlowOptions::validate() const {
  plumekit::validate(flow_option_table(), *this);
  const char* walls[] = {"left", "right", "bottom", "top"};
  for (int k = 0; k < 4; ++k)
    check_range(std::string("flow.wall_speed.") + walls[k], wall_speed[k], -100.0, 100.0, "m/s",
                "0 is a no-slip wall");
}

}  // namespace plumekit::cfd
