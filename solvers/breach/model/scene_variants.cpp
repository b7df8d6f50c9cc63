#include "solvers/breach/model/scene_variants.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string_view>

#include "core/config/units.hpp"
#include "core/errors.hpp"

namespace suite::breach {

namespace {

using config::Range;

// What the scene must hold for a key to be set here as Scene::read would read it.
enum class Form { any, internal_erosion, power_law_storage, peaked_inflow, constant_inflow };

struct Key {
  const char* path;
  const char* unit;  // "": a plain number (Section::number); else a quantity, converted to this SI unit
  Range range;       // as Scene::read checks it
  Form form;
  double& (*field)(Scene&);  // the number it sets, or
  // for keys that rebuild a part of the scene: sets the value; false if that breaks a check
  // within its section (a triangle's peak below its base)
  bool (*set)(Scene&, double) = nullptr;
};

// One row per key. The units and ranges repeat those of the section readers (Embankment::read,
// Soil::read, StageStorage::read, Hydrograph::read, scene.cpp); tests/studies/test_scene_variants.cpp
// compares every key, in and out of its range, with reading the scene again.
const std::vector<Key>& key_table() {
  static const std::vector<Key> table = {
      {"dam.height", "m", Range::positive(), Form::any, [](Scene& s) -> double& { return s.dam.height; }},
      {"dam.crest_width", "m", Range::at_least(0), Form::any, [](Scene& s) -> double& { return s.dam.crest_width; }},
      {"dam.crest_length", "m", Range::positive(), Form::any, [](Scene& s) -> double& { return s.dam.crest_length; }},
      {"dam.upstream_slope", "", Range::positive(), Form::any,
       [](Scene& s) -> double& { return s.dam.upstream_slope; }},
      {"dam.downstream_slope", "", Range::positive(), Form::any,
       [](Scene& s) -> double& { return s.dam.downstream_slope; }},
      {"dam.foundation", "m", Range::any(), Form::any, [](Scene& s) -> double& { return s.dam.foundation; }},
      {"soil.erodibility", "m^3/(N s)", Range::at_least(0), Form::any, [](Scene& s) -> double& { return s.soil.kd; }},
      {"soil.critical_shear_stress", "Pa", Range::at_least(0), Form::any,
       [](Scene& s) -> double& { return s.soil.tau_c; }},
      {"soil.undrained_shear_strength", "Pa", Range::at_least(0), Form::any,
       [](Scene& s) -> double& { return s.soil.s_u; }},
      {"soil.unit_weight", "N/m^3", Range::positive(), Form::any, [](Scene& s) -> double& { return s.soil.gamma_t; }},
      {"reservoir.initial_level", "m", Range::any(), Form::any,
       [](Scene& s) -> double& { return s.reservoir.initial_level; }},
      {"reservoir.storage.alpha", "", Range::positive(), Form::power_law_storage, nullptr,
       [](Scene& s, double v) {
         const auto& p = s.reservoir.storage;
         s.reservoir.storage = StageStorage::power_law(v, p.bottom(), p.exponent());
         return true;
       }},
      {"reservoir.storage.exponent", "", Range::between(1.0, 5.0), Form::power_law_storage, nullptr,
       [](Scene& s, double v) {
         const auto& p = s.reservoir.storage;
         s.reservoir.storage = StageStorage::power_law(p.alpha(), p.bottom(), v);
         return true;
       }},
      {"reservoir.storage.bottom", "m", Range::any(), Form::power_law_storage, nullptr,
       [](Scene& s, double v) {
         const auto& p = s.reservoir.storage;
         s.reservoir.storage = StageStorage::power_law(p.alpha(), v, p.exponent());
         return true;
       }},
      // Hydrograph::read takes the triangle's base in [0, peak].
      {"inflow.peak", "m^3/s", Range::at_least(0), Form::peaked_inflow, nullptr,
       [](Scene& s, double v) {
         if (v < s.inflow.base()) return false;
         s.inflow = s.inflow.with_peak(v);
         return true;
       }},
      {"inflow.discharge", "m^3/s", Range::at_least(0), Form::constant_inflow, nullptr,
       [](Scene& s, double v) {
         s.inflow = s.inflow.with_peak(v);
         return true;
       }},
      {"breach.initial_width", "m", Range::positive(), Form::any,
       [](Scene& s) -> double& { return s.breach.initial_width; }},
      {"breach.side_slope", "", Range::at_least(0), Form::any, [](Scene& s) -> double& { return s.breach.side_slope; }},
      {"headcut.formation_depth", "m", Range::positive(), Form::any,
       [](Scene& s) -> double& { return s.breach.formation_depth; }},
      {"headcut.jet_friction", "", Range::positive(), Form::any,
       [](Scene& s) -> double& { return s.breach.headcut.jet_friction; }},
      {"headcut.jet_diffusion", "", Range::positive(), Form::any,
       [](Scene& s) -> double& { return s.breach.headcut.jet_diffusion; }},
      {"headcut.critical_height_factor", "", Range::positive(), Form::any,
       [](Scene& s) -> double& { return s.breach.headcut.critical_height_factor; }},
      {"internal_erosion.elevation", "m", Range::any(), Form::internal_erosion,
       [](Scene& s) -> double& { return s.internal_erosion.elevation; }},
      {"internal_erosion.initial_diameter", "m", Range::positive(), Form::internal_erosion,
       [](Scene& s) -> double& { return s.internal_erosion.initial_diameter; }},
      {"internal_erosion.entrance_loss", "", Range::at_least(0), Form::internal_erosion,
       [](Scene& s) -> double& { return s.internal_erosion.entrance_loss; }},
      {"internal_erosion.collapse_fraction", "", Range::between(0.05, 1.0), Form::internal_erosion,
       [](Scene& s) -> double& { return s.internal_erosion.collapse_fraction; }},
      {"internal_erosion.debris_bulking", "", Range::between(1.0, 2.0), Form::internal_erosion,
       [](Scene& s) -> double& { return s.internal_erosion.debris_bulking; }},
  };
  return table;
}

bool scene_has(const Scene& s, Form form) {
  switch (form) {
    case Form::any:
      return true;
    case Form::internal_erosion:
      return s.internal_erosion.enabled;
    case Form::power_law_storage:
      return s.reservoir.storage.is_power_law();
    case Form::peaked_inflow:
      return s.inflow.kind() == Hydrograph::Kind::triangular || s.inflow.kind() == Hydrograph::Kind::sine;
    case Form::constant_inflow:
      return s.inflow.kind() == Hydrograph::Kind::constant;
  }
  return false;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// The value of `text` as Section::number or Section::quantity reads the override key=text
// (std::from_chars, then the unit converted to the key's SI unit, then the range), or nothing
// where they would not accept it or YAML might read the text as anything but this plain scalar:
// only digits, letters, spaces and . - + * / ^ ( ) _ pass, starting with a digit, '.' or '-'.
std::optional<double> value_of(const Key& key, std::string_view text) {
  text = trim(text);
  if (text.empty()) return std::nullopt;
  const bool plain = std::all_of(text.begin(), text.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) ||
           std::string_view(" .-+*/^()_").find(c) != std::string_view::npos;
  });
  const char first = text.front();
  if (!plain || !(std::isdigit(static_cast<unsigned char>(first)) || first == '.' || first == '-')) return std::nullopt;
  if (first == '-' && (text.size() == 1 || text[1] == ' ')) return std::nullopt;  // YAML: a list item
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || !std::isfinite(v)) return std::nullopt;
  const std::string_view given = trim(text.substr(static_cast<std::size_t>(end - text.data())));
  if (*key.unit == '\0') {
    if (!given.empty()) return std::nullopt;
  } else if (!given.empty()) {
    try {
      v = units::convert(v, given, key.unit);
    } catch (const InputError&) {
      return std::nullopt;
    }
  }
  if (!key.range.contains(v)) return std::nullopt;
  return v;
}

}  // namespace

SceneVariants::SceneVariants(const config::Config& cfg) {
  const auto root = cfg.root();
  // Asked before Scene::read, which writes the defaults it uses into the tree.
  auto given = [&](const char* section, const char* key) {
    const auto s = root.optional_section(section);
    return s && s->has(key);
  };
  initial_width_given_ = given("breach", "initial_width");
  formation_depth_given_ = given("headcut", "formation_depth");
  base_ = Scene::read_complete(cfg);
}

std::optional<Scene> SceneVariants::with(const std::vector<std::pair<std::string, std::string>>& settings) const {
  Scene s = base_;
  bool width_given = initial_width_given_, depth_given = formation_depth_given_;
  for (const auto& [path, text] : settings) {
    const auto& table = key_table();
    const auto key = std::find_if(table.begin(), table.end(), [&](const Key& k) { return path == k.path; });
    if (key == table.end() || !scene_has(s, key->form)) return std::nullopt;
    const auto v = value_of(*key, text);
    if (!v) return std::nullopt;
    if (key->field) {
      key->field(s) = *v;
    } else if (!key->set(s, *v)) {
      return std::nullopt;
    }
    width_given = width_given || path == "breach.initial_width";
    depth_given = depth_given || path == "headcut.formation_depth";
  }
  if (!width_given) s.breach.initial_width = BreachSettings::default_initial_width(s.dam);
  if (!depth_given) s.breach.formation_depth = BreachSettings::default_formation_depth(s.dam);
  if (s.cross_section_problem()) return std::nullopt;
  return s;
}

std::vector<std::string> SceneVariants::keys() {
  std::vector<std::string> out;
  for (const auto& k : key_table()) out.emplace_back(k.path);
  return out;
}

}  // namespace suite::breach
