// `fluidbed keys`: every field of the scene table listed with its default, unit, range and help;
// the TOML form a complete scene at the defaults; the validator refusing exactly what the
// table's ranges leave out.
#include <gtest/gtest.h>

#include <sstream>

#include "../test_support.hpp"
#include "core/errors.hpp"
#include "scene/scene_keys.hpp"
#include "scene/scene_loader.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;

namespace {

struct Field {
  std::string section, key;
  FieldInfo info;
  bool number = false, integer = false;
  bool optional = false;  // unset by default: it follows the key its help names
};

struct Collect {
  std::string section;
  std::vector<Field>* out;
  template <class T>
  void operator()(std::string_view key, const T&, const FieldInfo& info) const {
    out->push_back(
        {section, std::string(key), info,
         std::is_same_v<T, double> || std::is_same_v<T, std::optional<double>>,
         std::is_same_v<T, int>, std::is_same_v<T, std::optional<double>>});
  }
};

// Every field of the table, walked the way the loader walks it.
std::vector<Field> table_fields() {
  Settings s;
  std::vector<Field> fields;
  visit_sections(s, [&](std::string_view name, auto& section) {
    visit_fields(section, Collect{std::string(name), &fields});
  });
  return fields;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The section's part of a TOML text: from its [header] to the next one.
std::string toml_section(const std::string& text, const std::string& section) {
  const auto start = text.find("\n[" + section + "]\n");
  if (start == std::string::npos) return "";
  const auto end = text.find("\n[", start + 1);
  return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

std::string number_text(double v, bool integer) {
  std::ostringstream o;
  if (integer) {
    o << static_cast<long long>(v);
  } else {
    o.precision(17);
    o << v;
  }
  return o.str();
}

}  // namespace

TEST(Keys, EveryFieldIsListedWithItsUnitRangeAndHelp) {
  const CommandResult r = run_fluidbed("keys", "keys");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::string> lines = lines_of(r.out);
  const std::vector<Field> fields = table_fields();
  ASSERT_GT(fields.size(), 60u);
  std::size_t rows = 0;
  for (const std::string& line : lines)
    rows += line.find('.') != std::string::npos && line[0] != ' ';
  EXPECT_EQ(rows, fields.size()) << r.out;  // one row per field, no more
  for (const Field& f : fields) {
    const std::string name = f.section + "." + f.key;
    const auto row = std::find_if(lines.begin(), lines.end(), [&name](const std::string& l) {
      return l.rfind(name + " ", 0) == 0;
    });
    ASSERT_NE(row, lines.end()) << name << " missing from\n" << r.out;
    EXPECT_NE(row->find(std::string(f.info.help)), std::string::npos) << *row;
    if (!f.info.unit.empty()) {
      EXPECT_NE(row->find(" " + std::string(f.info.unit) + " "), std::string::npos) << *row;
    }
    if (f.number || f.integer) {
      EXPECT_NE(row->find(f.info.range.text()), std::string::npos) << *row;
    }
    EXPECT_FALSE(f.info.help.empty()) << name;
  }
  // The same as the engine's own listing, defaults included.
  for (const SceneKey& k : scene_keys()) {
    const auto row = std::find_if(lines.begin(), lines.end(), [&k](const std::string& l) {
      return l.rfind(k.section + "." + k.name + " ", 0) == 0;
    });
    ASSERT_NE(row, lines.end());
    EXPECT_NE(row->find(" " + k.default_value + " "), std::string::npos) << *row;
  }
}

TEST(Keys, OneSectionOrAOneLineRefusal) {
  CommandResult r = run_fluidbed("keys contact", "keys-contact");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("contact.stiffness "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("N/m"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("particles."), std::string::npos) << r.out;
  r = run_fluidbed("keys contcat", "keys-unknown");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("contcat"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  r = run_fluidbed("keys --format yaml", "keys-format");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("yaml"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(Keys, TomlIsACompleteSceneAtTheDefaultsThatRuns) {
  const CommandResult r = run_fluidbed("keys --format toml", "keys-toml");
  ASSERT_EQ(r.status, 0) << r.err;
  // Every key is written out, under its section.
  for (const Field& f : table_fields()) {
    const std::string part = toml_section(r.out, f.section);
    // A key unset by default is a line to uncomment: left out, it follows the key it names.
    EXPECT_NE(part.find((f.optional ? "\n# " : "\n") + f.key + " = "), std::string::npos)
        << f.section << "." << f.key;
  }
  // It loads, validates and resolves to the defaults, value for value.
  Settings loaded;
  ASSERT_NO_THROW(loaded = parse_scene(r.out, "keys.toml"));
  EXPECT_EQ(to_toml(loaded), to_toml(Settings{}));
  // A scene that sets a value differs: the comparison is not blind.
  EXPECT_NE(to_toml(parse_scene(r.out, "keys.toml", {"contact.friction=0.31"})),
            to_toml(Settings{}));
  // And it runs as is (shortened: the whole second would take minutes of this test's time).
  const auto dir = temp_dir("keys-toml-run");
  write_file(dir / "defaults.toml", r.out);
  const CommandResult run = run_fluidbed(
      "run " + (dir / "defaults.toml").string() + " --until 0.005 --out " + (dir / "out").string(),
      "keys-toml-run");
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "summary.json"));
}

TEST(Keys, ManPageListsEveryKeyAndCommand) {
  const CommandResult r = run_fluidbed("keys --format man", "keys-man");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find(".TH FLUIDBED 1"), r.out.find('\n') + 1) << r.out.substr(0, 200);
  for (const Field& f : table_fields()) {
    // roff escapes hyphens; no key has one, so each name reads as written.
    EXPECT_NE(r.out.find(".B " + f.key + " = "), std::string::npos) << f.key;
  }
  for (const char* section : {"[contact]", "[bubbles]", "[gas]"})
    EXPECT_NE(r.out.find(".SS " + std::string(section)), std::string::npos) << section;
  for (const char* command : {"run", "sweep", "view", "bench", "keys", "export", "study"})
    EXPECT_NE(r.out.find(".SS " + std::string(command) + "\n"), std::string::npos) << command;
  EXPECT_NE(r.out.find("\\-\\-until"), std::string::npos);  // the options, from the parser
  const CommandResult narrowed = run_fluidbed("keys contact --format man", "keys-man-section");
  EXPECT_EQ(narrowed.status, 2);
}

TEST(Keys, ValidatorRefusesExactlyWhatTheRangesLeaveOut) {
  int bounded = 0;
  for (const Field& f : table_fields()) {
    if (!f.number && !f.integer) continue;
    const Range& range = f.info.range;
    const std::string name = f.section + "." + f.key;
    // The Hertz-Mindlin material's keys mean something only with that law in a thick slab.
    std::vector<std::string> with;
    if (name == "contact.youngs_modulus" || name == "contact.poisson_ratio" ||
        name == "contact.restitution")
      for (const char* o : {"domain.thickness=0.012", "contact.law=hertz_mindlin",
                            "contact.youngs_modulus=1e7", "contact.poisson_ratio=0.3",
                            "contact.restitution=0.9"})
        if (std::string(o).rfind(name + "=", 0) != 0) with.push_back(o);
    const auto refusal = [&](double v) {
      try {
        std::vector<std::string> overrides = with;
        overrides.push_back(name + "=" + number_text(v, f.integer));
        parse_scene("", "t.toml", overrides);
      } catch (const InputError& e) {
        return std::string(e.what());
      }
      return std::string();
    };
    const double step = f.integer ? 1.0 : 0.5;
    if (range.bounded_below()) {
      ++bounded;
      const double outside = range.low_open ? range.low : range.low - step;
      EXPECT_NE(refusal(outside).find(name), std::string::npos) << name << " = " << outside;
      if (!range.low_open) {
        EXPECT_EQ(refusal(range.low), "") << name << " = " << range.low;
      }
    }
    if (range.bounded_above()) {
      const double outside = range.high_open ? range.high : range.high + step;
      EXPECT_NE(refusal(outside).find(name), std::string::npos) << name << " = " << outside;
      if (!range.high_open) {
        EXPECT_EQ(refusal(range.high), "") << name << " = " << range.high;
      }
    }
  }
  EXPECT_GT(bounded, 30);
  // The one-line words for each kind of range.
  const auto error_of = [](const std::string& o) {
    return fluidbed::testing::scene_error("", {o});
  };
  EXPECT_EQ(error_of("time.dt=0"), "time.dt must be positive (got 0.000000)");
  EXPECT_EQ(error_of("contact.damping=-1"), "contact.damping must not be negative (got -1.000000)");
  EXPECT_EQ(error_of("gas.cells_x=2"), "gas.cells_x must be at least 3");
  EXPECT_EQ(error_of("bubbles.threshold=1"), "bubbles.threshold must be in (0, 1) (got 1.000000)");
}
