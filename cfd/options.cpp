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
// cannot succeed. cfd/README.md lists them.
void FlowOptions::validate() const {
  if (cell != 0.0)  // 0: the default, chosen from the arena's size
    check_positive("flow.cell", cell, kMaxCell, "m",
                   "0 (the default) is 0.05 m, or coarser on arenas over 640000 such cells");
  check_positive("flow.nu", nu, 10.0, "m^2/s",
                 "the default is 0.01 m^2/s (air's molecular value is 1.5e-05)");
  check_range("flow.tolerance", tolerance, 1e-14, 0.1, "", "the default is 1e-08");
  check_count("flow.max_iterations", max_iterations, 0, 100000,
              "0 means the default (100, or 300 with the mixing-length closure)");
  check_positive("flow.kappa", kappa, 1.0, "", "von Karman's constant is 0.41");
  check_range("flow.lm_max", lm_max, -1e3, 1e3, "m",
              "0 or less means 0.09 times half the arena's smaller side");
  const char* walls[] = {"left", "right", "bottom", "top"};
  for (int k = 0; k < 4; ++k)
    check_range(std::string("flow.wall_speed.") + walls[k], wall_speed[k], -100.0, 100.0, "m/s",
                "0 is a no-slip wall");
}

}  // namespace plumekit::cfd
