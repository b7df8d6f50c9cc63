#pragma once
// Strict YAML configuration.
//
//   auto cfg = config::Config::from_file("scene.yaml", {"soil.cohesion=5 kPa", "output.every=10"});
//   auto soil = cfg.root().section("soil");
//   double c0 = soil.quantity("cohesion", "Pa", config::Range::at_least(0));   // required
//   double phi = soil.quantity("friction_angle", "deg", 30.0, config::Range::between(0, 90));
//   std::string wall = cfg.root().choice("wall", {"slip", "sticky", "friction"}, "slip");
//   cfg.finish();   // unknown keys -> InputError with "did you mean"
//
// Values with units may carry them ("2.5 m", "30 min", "1200 cfs"); a bare number is read in
// the unit the program asks for. A default that is used is written into the tree, so
// effective_yaml() is the complete configuration the run used. Every error is an InputError of
// one line: "<file>:<line>:<col>: key '<path>' = '<value>': <problem>; <what is valid>".
// Nothing here is collective: every rank reads the same file and reaches the same verdict.
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace YAML {
class Node;
}

namespace suite::config {

struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;  // true: value must be > min
  bool max_open = false;  // true: value must be < max

  static Range any() { return {}; }
  static Range at_least(double v) { return {v, std::numeric_limits<double>::infinity(), false, false}; }
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range between(double lo, double hi) { return {lo, hi, false, false}; }
  bool contains(double v) const;
  std::string describe() const;  // e.g. "> 0", "in [0, 90]"
};

class Config;
struct State;

// A view of one mapping in the tree, with its key path ("soil", "inlets[0]").
class Section {
 public:
  const std::string& path() const { return path_; }
  bool has(const std::string& key) const;

  Section section(const std::string& key) const;  // required mapping
  std::optional<Section> optional_section(const std::string& key) const;
  // The section, or an empty one added to the tree if absent: defaults read from it then
  // appear in the effective configuration.
  Section section_or_empty(const std::string& key) const;
  std::vector<Section> sections(const std::string& key) const;  // required list of mappings

  // Plain values. T is one of bool, int, long long, double, std::string, std::vector<double>,
  // std::vector<long long>, std::vector<std::string>.
  template <class T>
  T get(const std::string& key) const;
  template <class T>
  T get(const std::string& key, const T& fallback) const;

  // Numbers with a range, and quantities with a unit (returned in `unit`).
  double number(const std::string& key, Range range) const;
  double number(const std::string& key, double fallback, Range range) const;
  double quantity(const std::string& key, const std::string& unit, Range range = {}) const;
  double quantity(const std::string& key, const std::string& unit, double fallback, Range range = {}) const;
  long long integer(const std::string& key, long long fallback, long long min, long long max) const;

  // A table of rows, each a list of `columns` quantities in the given units, e.g. a hydrograph
  // [[0 h, 0 cfs], [2 h, 1200 cfs]] read with units {"s", "m^3/s"}.
  std::vector<std::vector<double>> table(const std::string& key, const std::vector<std::string>& units) const;

  // One of `valid`; a near miss gets a suggestion.
  std::string choice(const std::string& key, const std::vector<std::string>& valid) const;
  std::string choice(const std::string& key, const std::vector<std::string>& valid, const std::string& fallback) const;

  // A file named by `key`: a relative path is taken from the folder of the scene file (from the
  // working directory for a scene given as a string). InputError if it is not a readable file.
  // The effective configuration then holds the absolute path.
  std::filesystem::path file(const std::string& key) const;
  // The same for a list of files.
  std::vector<std::filesystem::path> files(const std::string& key) const;
  // The folder relative paths are read from (the scene file's; empty: the working directory).
  const std::filesystem::path& base_dir() const;
  // Replaces a value in the effective configuration by the one the program resolved it to
  // (e.g. a command's relative program path made absolute), so a rerun from elsewhere works.
  void record(const std::string& key, const std::vector<std::string>& values) const;

  // A subtree passed on without checking (e.g. PETSc options); all its keys count as known.
  YAML::Node raw(const std::string& key) const;

  // Throws the standard InputError for `key` of this section ("<file>:<line>:<col>: key
  // '<path>' = '<value>': <problem>"), for checks that involve several keys.
  [[noreturn]] void reject(const std::string& key, const std::string& problem) const;

 private:
  friend class Config;
  Section(std::shared_ptr<State> state, std::shared_ptr<YAML::Node> node, std::string path);
  YAML::Node child(const std::string& key) const;  // marks key as requested
  std::string child_path(const std::string& key) const;
  template <class T>
  T convert(const std::string& key, const YAML::Node& n) const;
  double parse_quantity(const std::string& key, const YAML::Node& n, const std::string& unit) const;
  // Rejects v outside range, saying so when n was a bare number read in `unit`.
  void check_range(const std::string& key, const YAML::Node& n, double v, const std::string& unit,
                   const Range& range) const;
  void store_default(const std::string& key, const YAML::Node& value) const;
  void resolve(const std::string& key, std::string value) const;  // for Config::resolved()

  std::shared_ptr<State> state_;
  std::shared_ptr<YAML::Node> node_;
  std::string path_;
};

class Config {
 public:
  // `overrides` are "key.path=value" strings from the command line; value is YAML ("5", "[1, 2]",
  // "2.5 m"). Throws InputError naming the file (and line) or the override, which messages call
  // `override_origin` (a study's values: "model.set").
  static Config from_file(const std::filesystem::path& path, const std::vector<std::string>& overrides = {},
                          const std::string& override_origin = "command-line override");
  static Config from_string(const std::string& text, const std::string& source_name,
                            const std::vector<std::string>& overrides = {},
                            const std::string& override_origin = "command-line override");

  Section root() const;
  // Throws InputError for the first key in the file that the program never asked for, with
  // the closest known key as a suggestion and the list of keys valid at that place.
  void finish() const;
  // The configuration as used: file + overrides + defaults that were applied.
  std::string effective_yaml() const;
  void write_effective(const std::filesystem::path& path) const;
  // Every key the program read, by path ("soil.regions[0].trapezoid.height"), with the value as
  // it understood it: numbers to the last bit, quantities in the unit it asked for ("3.75 m"
  // and "375 cm" both read "3.75 m"), defaults included, a file as its size and content digest.
  // Two runs that read the same map ran the same scene (restart checks compare it).
  const std::map<std::string, std::string>& resolved() const;
  const std::string& source_name() const;

 private:
  explicit Config(std::shared_ptr<State> s) : state_(std::move(s)) {}
  std::shared_ptr<State> state_;
};

// True for "key.path=value" arguments (the form overrides take on a command line).
bool looks_like_override(const std::string& arg);

}  // namespace suite::config
