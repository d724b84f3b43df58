// The method registry (methods/registry.hpp): a new method needs only its own code and one
// add_method() call to run through the whole run loop, and the registry's names are what the CLI
// offers.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "map/map.hpp"
#include "methods/method_options.hpp"
#include "methods/registry.hpp"
#include "run/method_run.hpp"
#include "run/scenario.hpp"
#include "support/cli_runner.hpp"

namespace plumekit::methods {
namespace {

// A trivial method, defined here and nowhere else: it walks one step upwind per stop (against
// the measured wind) and stops after its step budget. Its own code plus one registry line.
class UpwindWalk : public LocalizationMethod {
 public:
  explicit UpwindWalk(const TrackingOptions& o) : step_(o.step), max_steps_(o.max_steps) {}
  std::string name() const override { return "upwind-walk"; }
  void observe(const Observation& o) override {
    last_ = o;
    ++stops_;
  }
  Move next(Vec2 robot) override {
    const double w = norm(last_.wind);
    const Vec2 dir = w > 0.0 ? Vec2{-last_.wind.x / w, -last_.wind.y / w} : Vec2{0.0, 0.0};
    return {{robot.x + step_ * dir.x, robot.y + step_ * dir.y}, {}, 0.0};
  }
  std::optional<Vec2> estimate() const override { return last_.position; }
  std::string stopped_by() const override { return stops_ >= max_steps_ ? "max_samples" : ""; }

 private:
  double step_;
  int max_steps_;
  Observation last_;
  int stops_ = 0;
};

MethodSpec upwind_walk_spec() {
  return {"upwind-walk",
          "one step upwind per stop (a test's own method)",
          "registry_test",
          MethodTraits{false, RunEnd::OwnStopRule},
          [](const MethodOptions& o, const SearchArea&, std::uint64_t) {
            return std::make_unique<UpwindWalk>(o.tracking);
          },
          {}};
}

// The one registry line, once per test binary.
void register_upwind_walk() {
  static const bool added = (add_method(upwind_walk_spec()), true);
  (void)added;
}

TEST(MethodRegistry, NamesAreUniqueAndEveryMethodHasTheFactoryItsTraitsNeed) {
  std::set<std::string> names;
  for (const MethodSpec& s : method_registry()) {
    EXPECT_TRUE(names.insert(s.name).second) << s.name;
    EXPECT_FALSE(s.description.empty()) << s.name;
    EXPECT_FALSE(s.source.empty()) << s.name;
    // STE is made from the scenario's plume model; every other from its options and area.
    EXPECT_EQ(s.traits.uses_plume_model, s.name == "ste") << s.name;
    EXPECT_EQ(static_cast<bool>(s.factory), !s.traits.uses_plume_model) << s.name;
    EXPECT_EQ(static_cast<bool>(s.model_factory), s.traits.uses_plume_model) << s.name;
    EXPECT_EQ(s.traits.teams, s.name == "ste") << s.name;  // seed 004 ch. 13's teams run STE
  }
  EXPECT_EQ(method_names().front(), "ste");
}

TEST(MethodRegistry, TraitsSayHowARunEnds) {
  for (const char* tracker : {"sweeping", "surge-cast", "zigzag", "pseudo-gradient"}) {
    EXPECT_TRUE(stops_in_source_box(tracker)) << tracker;
    EXPECT_TRUE(ends_on_arrival(tracker)) << tracker;
  }
  EXPECT_FALSE(stops_in_source_box("levy-taxis"));
  EXPECT_TRUE(ends_on_arrival("levy-taxis"));
  for (const char* own : {"ste", "pf-gradient", "pf-sweep", "apf", "ste-local"})
    EXPECT_FALSE(ends_on_arrival(own)) << own;
}

TEST(MethodRegistry, RefusesDuplicatesAndMethodsWithoutFactories) {
  EXPECT_THROW(add_method(sweeping_spec()), std::invalid_argument);
  MethodSpec empty{"no-factory", "d", "s", {}, {}, {}};
  EXPECT_THROW(add_method(empty), std::invalid_argument);
  MethodSpec model_without_its_factory = sweeping_spec();
  model_without_its_factory.name = "no-model-factory";
  model_without_its_factory.traits.uses_plume_model = true;
  EXPECT_THROW(add_method(model_without_its_factory), std::invalid_argument);
  // STE is made only with its scenario's plume model.
  MethodOptions ste;
  ste.name = "ste";
  const Map map = default_arena();
  EXPECT_THROW(make_method(ste, {&map}, 1), std::logic_error);
  EXPECT_THROW(find_method("no-factory"), OptionError);
}

TEST(MethodRegistry, ListsAndAllFollowTheRegistry) {
  EXPECT_EQ(parse_method_list("all"), method_names());
  EXPECT_EQ(parse_method_list("zigzag,ste"), (std::vector<std::string>{"zigzag", "ste"}));
  EXPECT_THROW(parse_method_list("zigzag,zigzag"), OptionError);
  EXPECT_THROW(parse_method_list("infotaxis"), OptionError);
}

// Before the test's own method is added: the shipped methods only.
TEST(MethodRegistry, DocsTableIsTheRegistry) {
  ASSERT_EQ(method_names().back(), "ste-local") << "run before any test adds a method";
  const std::string path = std::string(PLUMEKIT_SOURCE_DIR) + "/docs/methods-registry.md";
  if (std::getenv("PLUMEKIT_WRITE_DOCS")) std::ofstream(path) << registry_markdown();
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), registry_markdown());
}

using MethodRegistryCli = test::CliTest;

// `plumekit localize --help` lists the registry's methods, in its order.
TEST_F(MethodRegistryCli, LocalizeHelpListsTheRegistry) {
  const test::CliResult r = run("localize --help");
  ASSERT_EQ(r.code, 0) << r.err;
  std::string names;
  for (const MethodSpec& s : method_registry())
    if (s.name != "upwind-walk") names += (names.empty() ? "" : ", ") + s.name;
  std::string help;  // CLI11 wraps the description: join its lines
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);)
    help += line.substr(std::min(line.find_first_not_of(' '), line.size())) + " ";
  EXPECT_NE(help.find("Localization method: " + names + " "), std::string::npos) << r.out;
}

// `plumekit methods` prints the registry: its JSON names every method of the floor and the tunnel
// in order, and --markdown is docs/methods-registry.md.
TEST_F(MethodRegistryCli, MethodsCommandPrintsTheRegistry) {
  const test::CliResult j = run("methods --json");
  ASSERT_EQ(j.code, 0) << j.err;
  const nlohmann::json out = nlohmann::json::parse(j.out);
  std::vector<std::string> floor, tunnel;
  for (const auto& m : out.at("methods"))
    floor.push_back(m.at("name"));
  for (const auto& m : out.at("tunnel_methods"))
    tunnel.push_back(m.at("name"));
  EXPECT_EQ(floor.front(), "ste");
  EXPECT_EQ(floor.back(), "ste-local");  // the program's own registry: no test's method
  EXPECT_EQ(floor.size(), 10u);
  EXPECT_EQ(tunnel, (std::vector<std::string>{"ste-3d", "surge-spiral", "surge-cast-2d"}));
  EXPECT_TRUE(out.at("methods").at(0).at("teams").get<bool>());
  const test::CliResult md = run("methods --markdown");
  ASSERT_EQ(md.code, 0) << md.err;
  std::ifstream in(std::string(PLUMEKIT_SOURCE_DIR) + "/docs/methods-registry.md");
  std::stringstream page;
  page << in.rdbuf();
  EXPECT_EQ(md.out, page.str());
  const test::CliResult text = run("methods");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("surge-cast-2d"), std::string::npos) << text.out;
}

TEST(MethodRegistry, ANewMethodRunsEndToEndThroughTheScenarioAndTheRunLoop) {
  register_upwind_walk();
  EXPECT_EQ(method_names().back(), "upwind-walk");
  Map map = default_arena(6.0, 3.0);
  map.name = "open";
  run::SteOptions o;
  o.method.name = "upwind-walk";
  o.method.max_steps = 12;
  const run::Scenario sc(map, o);
  EXPECT_FALSE(sc.has_model());  // the registry says it needs no plume model
  const run::LocalizationResult a = sc.run({4.5, 1.5}, {1.0, 1.5}, 5);
  const run::LocalizationResult b = sc.run({4.5, 1.5}, {1.0, 1.5}, 5);
  EXPECT_EQ(a.method, "upwind-walk");
  EXPECT_EQ(a.samples, 12);
  EXPECT_EQ(a.stopped_by, "max_samples");
  ASSERT_EQ(a.steps.size(), b.steps.size());
  EXPECT_EQ(a.estimate, b.estimate);
  for (const run::Step& s : a.steps)
    EXPECT_TRUE(sc.free_space().contains(s.position));
  // It moved: each stop is a step from the last, or stopped at a wall.
  EXPECT_GT(a.distance_m, 0.0);
}

}  // namespace
}  // namespace plumekit::methods

namespace plumekit::methods {
namespace {

// The tunnel's methods are listed the same way: each spec makes a method of its own name, the
// --method help and "all" follow the list, and an unknown name is refused naming the field.
TEST(TunnelMethodRegistry, EachSpecMakesItsMethodAndTheListsFollowTheRegistry) {
  TunnelMethodInputs in;
  in.tunnel = {{0.0, 0.0, 0.0}, {10.0, 4.0, 2.0}};
  in.margin = 0.1;
  in.search.altitude = 1.0;
  std::vector<std::string> names;
  for (const TunnelMethodSpec& s : tunnel_method_registry()) {
    names.push_back(s.name);
    ASSERT_TRUE(static_cast<bool>(s.factory)) << s.name;
    const std::unique_ptr<LocalizationMethod3> m = s.factory(in);
    EXPECT_EQ(m->name(), s.name);
    EXPECT_EQ(m->reads_while_moving(), s.tracker) << s.name;
    EXPECT_EQ(m->plume_threshold().has_value(), s.tracker) << s.name;
    EXPECT_NE(tunnel_methods_help().find(s.name + " (" + s.description + ", " + s.source + ")"),
              std::string::npos);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"ste-3d", "surge-spiral", "surge-cast-2d"}));
  EXPECT_EQ(parse_tunnel_method_list("all"), names);
  EXPECT_EQ(parse_tunnel_method_list("surge-cast-2d,ste-3d"),
            (std::vector<std::string>{"surge-cast-2d", "ste-3d"}));
  EXPECT_THROW(parse_tunnel_method_list("ste-3d,ste-3d"), OptionError);
  try {
    find_tunnel_method("ste");
    ADD_FAILURE() << "an unknown tunnel method was accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "tunnel.method");
  }
}

}  // namespace
}  // namespace plumekit::methods
