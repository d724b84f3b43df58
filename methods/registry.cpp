#include "methods/registry.hpp"

#include <stdexcept>

#include "core/error.hpp"
#include "methods/method_options.hpp"

namespace plumekit::methods {

namespace {

// One line per method. An explicit list rather than self-registering static objects: the methods
// live in a static library, and the linker drops an object file nobody references, with its
// registration. The order is the --method order (and `--method all`'s, the docs' table's).
std::vector<MethodSpec> builtin_methods() {
  return {
      ste_spec(),
      sweeping_spec(),
      surge_cast_spec(),
      zigzag_spec(),
      pseudo_gradient_spec(),
      pf_gradient_spec(),
      pf_sweep_spec(),
      apf_spec(),
      levy_taxis_spec(),
      ste_local_spec(),
  };
}

std::vector<MethodSpec>& registry() {
  static std::vector<MethodSpec> methods = builtin_methods();
  return methods;
}

// The tunnel's, the same way.
const std::vector<TunnelMethodSpec>& tunnel_registry() {
  static const std::vector<TunnelMethodSpec> methods{
      ste_3d_spec(),
      surge_spiral_spec(),
      surge_cast_2d_spec(),
  };
  return methods;
}

// The spec named `name` in `specs`; OptionError on `field` listing their names otherwise.
template <class Spec>
const Spec& find_spec(const std::vector<Spec>& specs, const std::string& name, const char* field) {
  std::string all;
  for (const Spec& s : specs) {
    if (s.name == name) return s;
    all += (all.empty() ? "" : ", ") + s.name;
  }
  throw OptionError(field, "unknown method '" + name + "'; use one of " + all);
}

// "NAME[,NAME...]" (each once) or "all" (every one of `specs`, in their order); OptionError on
// `field` otherwise.
template <class Spec>
std::vector<std::string> parse_spec_list(const std::vector<Spec>& specs, const std::string& text,
                                         const char* field) {
  std::vector<std::string> names;
  if (text == "all") {
    for (const Spec& s : specs)
      names.push_back(s.name);
    return names;
  }
  std::size_t from = 0;
  for (;;) {
    const std::size_t comma = text.find(',', from);
    const std::string name = find_spec(specs, text.substr(from, comma - from), field).name;
    for (const std::string& n : names)
      if (n == name) throw OptionError(field, name + " is named twice in '" + text + "'");
    names.push_back(name);
    if (comma == std::string::npos) return names;
    from = comma + 1;
  }
}

}  // namespace

const char* to_string(RunEnd end) {
  switch (end) {
    case RunEnd::OwnStopRule:
      return "own stop rule";
    case RunEnd::SourceBox:
      return "source box";
    case RunEnd::SourceDisc:
      return "0.5 m disc";
  }
  return "?";
}

const std::vector<MethodSpec>& method_registry() {
  return registry();
}

void add_method(MethodSpec spec) {
  if (spec.name.empty()) throw std::invalid_argument("add_method: a method needs a name");
  if (spec.traits.uses_plume_model ? !spec.model_factory : !spec.factory)
    throw std::invalid_argument("add_method: method '" + spec.name + "' has no factory");
  for (const MethodSpec& s : registry())
    if (s.name == spec.name)
      throw std::invalid_argument("add_method: method '" + spec.name + "' is registered already");
  registry().push_back(std::move(spec));
}

const MethodSpec& find_method(const std::string& name) {
  return find_spec(registry(), name, "ste.method");
}

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const MethodSpec& s : registry())
    names.push_back(s.name);
  return names;
}

std::vector<std::string> parse_method_list(const std::string& text) {
  return parse_spec_list(registry(), text, "ste.method");
}

const std::vector<TunnelMethodSpec>& tunnel_method_registry() {
  return tunnel_registry();
}

const TunnelMethodSpec& find_tunnel_method(const std::string& name) {
  return find_spec(tunnel_registry(), name, "tunnel.method");
}

std::vector<std::string> parse_tunnel_method_list(const std::string& text) {
  return parse_spec_list(tunnel_registry(), text, "tunnel.method");
}

std::string tunnel_methods_help() {
  const std::vector<TunnelMethodSpec>& all = tunnel_registry();
  std::string help;
  for (std::size_t k = 0; k < all.size(); ++k)
    help += std::string(k == 0                ? ""
                        : k + 1 == all.size() ? " or "
                                              : ", ") +
            all[k].name + " (" + all[k].description + ", " + all[k].source + ")";
  return help;
}

bool uses_plume_model(const std::string& name) {
  return find_method(name).traits.uses_plume_model;
}

bool stops_in_source_box(const std::string& name) {
  return find_method(name).traits.ends == RunEnd::SourceBox;
}

bool ends_on_arrival(const std::string& name) {
  return find_method(name).traits.ends_on_arrival();
}

std::string registry_markdown() {
  std::string md =
      "# Localization methods\n\n"
      "Generated from the method registry (`methods/registry.cpp`); "
      "`MethodRegistry.DocsTableIsTheRegistry` checks it\n"
      "(rewrite it with `build/plumekit methods --markdown > docs/methods-registry.md`).\n\n"
      "| `--method` | what | from | plume model | teams | a run ends |\n"
      "|---|---|---|---|---|---|\n";
  for (const MethodSpec& s : registry())
    md += "| `" + s.name + "` | " + s.description + " | " + s.source + " | " +
          (s.traits.uses_plume_model ? "yes" : "no") + " | " + (s.traits.teams ? "yes" : "no") +
          " | " + to_string(s.traits.ends) + ", budget |\n";
  md +=
      "\n## In the wind tunnel (`localize tunnel`, `evaluate tunnel`)\n\n"
      "| `--method` | what | from | a run ends |\n"
      "|---|---|---|---|\n";
  for (const TunnelMethodSpec& s : tunnel_registry())
    md += "| `" + s.name + "` | " + s.description + " | " + s.source + " | " +
          (s.tracker ? "in the source's box while in the plume, time limit"
                     : "own stop rule, budget") +
          " |\n";
  return md;
}

std::unique_ptr<LocalizationMethod> make_method(const MethodOptions& given, const SearchArea& area,
                                                std::uint64_t seed, const PlumeModelParts* model) {
  const MethodSpec& spec = find_method(given.name);
  if (spec.traits.uses_plume_model) {
    if (model == nullptr)
      throw std::logic_error("make_method: " + spec.name + " needs its scenario's plume model");
    return spec.model_factory(*model);
  }
  MethodOptions options = given;
  options.validate();
  options.tracking.max_steps = given.max_steps_in_use(area.width() * area.height());
  return spec.factory(options, area, seed);
}

}  // namespace plumekit::methods
