// The options-table mechanism (core/option_table.hpp) on a small struct: its
// checks name the field and the range, its defaults are the struct's, and the
// CLI binder (apps/cli.hpp) sets the fields and shows the defaults.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "apps/cli.hpp"
#include "core/error.hpp"
#include "core/option_table.hpp"

namespace plumekit {
namespace {

enum class Colour { Red, Blue };
const char* to_string(Colour c) {
  return c == Colour::Red ? "red" : "blue";
}
Colour parse_colour(const std::string& name) {
  if (name == "red") return Colour::Red;
  if (name == "blue") return Colour::Blue;
  throw OptionError("toy.colour", "unknown name '" + name + "'; use red or blue");
}

struct Toy {
  double speed = 1.5;
  double cell = 0.0;  // 0: automatic
  int count = 3;
  bool fast = false;
  bool tidy = true;
  std::string label = "plain";
  Colour colour = Colour::Red;
};

const OptionTable<Toy>& toy_table() {
  static const OptionTable<Toy> table{
      "Toy",
      {{"toy.speed", "--speed", &Toy::speed, positive(10.0, "m/s"), "Speed"},
       {"toy.cell", "--cell", &Toy::cell, zero_or(positive(1.0, "m")), "Cell",
        "{default} picks one for you"},
       {"toy.count", "--count", &Toy::count, count_range(1, 9), "Count"},
       {"toy.fast", "--fast", &Toy::fast, {}, "Go fast"},
       {"toy.tidy", "--tidy", &Toy::tidy, {}, "Tidy up"},
       {"toy.label", "--label", &Toy::label, {}, "Label"},
       {"toy.colour",
        "--colour",
        enum_field(&Toy::colour, &to_string, &parse_colour, "red, blue"),
        {},
        "Colour"},
       {"toy.hidden", "", &Toy::speed, {}, "Not a flag"}}};
  return table;
}

OptionError error_of(const Toy& toy) {
  try {
    validate(toy_table(), toy);
  } catch (const OptionError& e) {
    return e;
  }
  ADD_FAILURE() << "no OptionError";
  return OptionError("", "");
}

TEST(OptionTable, ValidateNamesTheFieldTheRangeAndTheDefault) {
  Toy toy;
  EXPECT_NO_THROW(validate(toy_table(), toy));
  toy.speed = -1.0;
  OptionError e = error_of(toy);
  EXPECT_EQ(e.field(), "toy.speed");
  EXPECT_NE(std::string(e.what()).find(
                "must be a finite number more than 0 and at most 10 m/s, got -1; the default "
                "is 1.5 m/s"),
            std::string::npos)
      << e.what();
  toy = Toy{};
  toy.count = 10;
  e = error_of(toy);
  EXPECT_EQ(e.field(), "toy.count");
  EXPECT_NE(std::string(e.what()).find("from 1 to 9, got 10; the default is 3"), std::string::npos)
      << e.what();
}

TEST(OptionTable, ZeroIsAllowedWhereItMeansAutomaticAndAdviceNamesTheDefault) {
  Toy toy;
  toy.cell = 0.0;
  EXPECT_NO_THROW(validate(toy_table(), toy));
  toy.cell = 2.0;
  const OptionError e = error_of(toy);
  EXPECT_EQ(e.field(), "toy.cell");
  EXPECT_NE(std::string(e.what()).find("got 2; 0 picks one for you"), std::string::npos)
      << e.what();
}

TEST(OptionTable, DefaultsAreTheStructsAndTheDocsSayThem) {
  const OptionTable<Toy>& t = toy_table();
  EXPECT_EQ(default_text(t.entry("toy.speed")), "1.5");
  EXPECT_EQ(default_text(t.entry("toy.count")), "3");
  EXPECT_EQ(default_text(t.entry("toy.tidy")), "true");
  EXPECT_EQ(default_text(t.entry("toy.label")), "plain");
  EXPECT_EQ(default_text(t.entry("toy.colour")), "red");
  EXPECT_EQ(t.entry("toy.speed").key(), "speed");
  const std::string md = option_markdown(t);
  EXPECT_NE(md.find("| `toy.speed` | `--speed` | `1.5` | more than 0 and at most 10 m/s | Speed |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| `toy.cell` | `--cell` | `0` | 0, or more than 0 and at most 1 m |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| `toy.colour` | `--colour` | `red` | one of red, blue |"), std::string::npos)
      << md;
  EXPECT_THROW(t.entry("toy.nothing"), std::logic_error);
}

TEST(OptionTable, CliFlagsSetTheFieldsAndShowTheDefaults) {
  CLI::App app;
  Toy toy;
  cli::add_table_flags(&app, toy, toy_table());
  EXPECT_EQ(app.get_option_no_throw("--hidden"), nullptr);
  const std::string help = app.help();
  EXPECT_NE(help.find("--speed FLOAT=1.5"), std::string::npos) << help;
  EXPECT_NE(help.find("--tidy BOOLEAN=true"), std::string::npos) << help;
  EXPECT_NE(help.find("--colour TEXT=red"), std::string::npos) << help;
  app.parse("--speed 2.5 --count 4 --fast --tidy false --label fancy --colour blue", false);
  EXPECT_EQ(toy.speed, 2.5);
  EXPECT_EQ(toy.count, 4);
  EXPECT_TRUE(toy.fast);
  EXPECT_FALSE(toy.tidy);
  EXPECT_EQ(toy.label, "fancy");
  EXPECT_EQ(toy.colour, Colour::Blue);
  // Errors name the flag, not the field, and only where the whole name stands.
  EXPECT_EQ(cli::with_flag_names(app, "toy.speed: must be ..."), "--speed: must be ...");
  EXPECT_EQ(cli::with_flag_names(app, "see toy.speed."), "see --speed.");
  EXPECT_EQ(cli::with_flag_names(app, "mytoy.speed_max: no; toy.speed.x: no"),
            "mytoy.speed_max: no; toy.speed.x: no");
}

TEST(OptionTable, CliOnlyAddsTheNamedEntries) {
  CLI::App app;
  Toy toy;
  cli::add_table_flags(&app, toy, toy_table(), {"toy.cell"});
  EXPECT_NE(app.get_option_no_throw("--cell"), nullptr);
  EXPECT_EQ(app.get_option_no_throw("--speed"), nullptr);
}

TEST(OptionTable, CliUnknownEnumNameIsTheLibrarysOptionError) {
  CLI::App app;
  Toy toy;
  cli::add_table_flags(&app, toy, toy_table());
  EXPECT_THROW(app.parse("--colour green", false), OptionError);
}

// An optional number whose unset value another part chooses (the plume model's sigma_M).
struct Chosen {
  std::optional<double> gain;
};
double chosen_gain() {
  return 7.0;
}

const OptionTable<Chosen>& chosen_table() {
  static const OptionTable<Chosen> table{
      "Chosen",
      {{"chosen.gain", "--gain",
        optional_field(&Chosen::gain,
                       [] { return option_number(chosen_gain()) + " for the model"; }),
        positive(10.0, ""), "Gain"}}};
  return table;
}

TEST(OptionTable, OptionalNumberSaysWhatUnsetMeansAndChecksOnlyWhenSet) {
  const OptionTable<Chosen>& t = chosen_table();
  EXPECT_EQ(default_text(t.entry("chosen.gain")), "7 for the model");
  EXPECT_NE(option_markdown(t).find("| `chosen.gain` | `--gain` | `7 for the model` | more than 0"),
            std::string::npos)
      << option_markdown(t);
  EXPECT_NO_THROW(validate(t, Chosen{}));
  EXPECT_THROW(validate(t, Chosen{20.0}), OptionError);
  EXPECT_EQ(value_text(t.entry("chosen.gain"), Chosen{2.5}), "2.5");

  CLI::App app;
  Chosen chosen;
  cli::add_table_flags(&app, chosen, t);
  EXPECT_NE(app.help().find("Gain (default: 7 for the model)"), std::string::npos) << app.help();
  app.parse("", false);
  EXPECT_FALSE(chosen.gain.has_value());
  app.parse("--gain 3", false);
  ASSERT_TRUE(chosen.gain.has_value());
  EXPECT_EQ(*chosen.gain, 3.0);
}

}  // namespace
}  // namespace plumekit
