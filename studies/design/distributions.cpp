#include "studies/design/distributions.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <functional>
#include <openturns/Beta.hxx>
#include <openturns/Exponential.hxx>
#include <openturns/Gamma.hxx>
#include <openturns/Gumbel.hxx>
#include <openturns/LogNormalMuSigma.hxx>
#include <openturns/LogUniform.hxx>
#include <openturns/Normal.hxx>
#include <openturns/Triangular.hxx>
#include <openturns/TruncatedDistribution.hxx>
#include <openturns/Uniform.hxx>
#include <openturns/WeibullMin.hxx>
#include <optional>

#include "core/errors.hpp"
#include "studies/design/openturns_bridge.hpp"

namespace suite::studies {

namespace {

using config::Range;

struct Parameter {
  std::string key;
  Range range;
  std::optional<double> fallback;  // absent: required
};

// A check that involves several parameters: the key to blame and the problem, or nothing.
struct Problem {
  std::string key, text;
};
using CrossCheck = std::function<std::optional<Problem>(const std::map<std::string, double>&)>;

struct Spec {
  std::string type;
  std::vector<Parameter> parameters;
  CrossCheck cross;
};

std::optional<Problem> upper_above_lower(const std::map<std::string, double>& p) {
  if (p.at("upper") <= p.at("lower"))
    return Problem{"upper", fmt::format("must be greater than lower ({})", p.at("lower"))};
  return std::nullopt;
}

const std::vector<Spec>& specs() {
  static const std::vector<Spec> table = {
      {"uniform", {{"lower", Range::any(), {}}, {"upper", Range::any(), {}}}, upper_above_lower},
      {"normal", {{"mean", Range::any(), {}}, {"std", Range::positive(), {}}}, nullptr},
      {"lognormal",
       {{"mean", Range::any(), {}}, {"std", Range::positive(), {}}, {"location", Range::any(), 0.0}},
       [](const std::map<std::string, double>& p) -> std::optional<Problem> {
         if (p.at("mean") <= p.at("location"))
           return Problem{"mean", fmt::format("must be greater than location ({}): mean and std are those of the "
                                              "variable itself, which is above its location",
                                              p.at("location"))};
         return std::nullopt;
       }},
      {"loguniform", {{"lower", Range::positive(), {}}, {"upper", Range::any(), {}}}, upper_above_lower},
      {"triangular",
       {{"lower", Range::any(), {}}, {"mode", Range::any(), {}}, {"upper", Range::any(), {}}},
       [](const std::map<std::string, double>& p) -> std::optional<Problem> {
         if (auto bad = upper_above_lower(p)) return bad;
         if (p.at("mode") < p.at("lower") || p.at("mode") > p.at("upper"))
           return Problem{"mode", fmt::format("must lie in [lower, upper] = [{}, {}]", p.at("lower"), p.at("upper"))};
         return std::nullopt;
       }},
      {"exponential", {{"rate", Range::positive(), {}}, {"location", Range::any(), 0.0}}, nullptr},
      {"beta",
       {{"alpha", Range::positive(), {}},
        {"beta", Range::positive(), {}},
        {"lower", Range::any(), {}},
        {"upper", Range::any(), {}}},
       upper_above_lower},
      {"gamma",
       {{"shape", Range::positive(), {}}, {"rate", Range::positive(), {}}, {"location", Range::any(), 0.0}},
       nullptr},
      {"gumbel", {{"scale", Range::positive(), {}}, {"location", Range::any(), {}}}, nullptr},
      {"weibull",
       {{"scale", Range::positive(), {}}, {"shape", Range::positive(), {}}, {"location", Range::any(), 0.0}},
       nullptr},
  };
  return table;
}

const Spec* find_spec(const std::string& type) {
  for (const auto& s : specs())
    if (s.type == type) return &s;
  return nullptr;
}

}  // namespace

const std::vector<std::string>& distribution_types() {
  static const std::vector<std::string> types = [] {
    std::vector<std::string> t;
    for (const auto& s : specs()) t.push_back(s.type);
    return t;
  }();
  return types;
}

Distribution read_distribution(const config::Section& s) {
  Distribution d;
  d.type = s.choice("type", distribution_types());
  const Spec& spec = *find_spec(d.type);
  for (const auto& p : spec.parameters)
    d.parameters[p.key] = p.fallback ? s.number(p.key, *p.fallback, p.range) : s.number(p.key, p.range);
  if (spec.cross)
    if (auto bad = spec.cross(d.parameters)) s.reject(bad->key, bad->text);
  return d;
}

void validate(const Distribution& d) {
  const Spec* spec = find_spec(d.type);
  if (!spec)
    throw InputError(fmt::format("distribution type '{}' is unknown; valid types: {}", d.type,
                                 fmt::join(distribution_types(), ", ")));
  for (const auto& p : spec->parameters) {
    auto it = d.parameters.find(p.key);
    if (it == d.parameters.end())
      throw InputError(fmt::format("{} distribution: parameter '{}' is missing", d.type, p.key));
    if (!std::isfinite(it->second) || !p.range.contains(it->second))
      throw InputError(fmt::format("{} distribution: parameter '{}' = {} must be {}", d.type, p.key, it->second,
                                   p.range.describe()));
  }
  for (const auto& [key, value] : d.parameters) {
    (void)value;
    bool known = false;
    for (const auto& p : spec->parameters) known = known || p.key == key;
    if (!known) throw InputError(fmt::format("{} distribution: unknown parameter '{}'", d.type, key));
  }
  if (spec->cross)
    if (auto bad = spec->cross(d.parameters))
      throw InputError(fmt::format("{} distribution: parameter '{}' = {} {}", d.type, bad->key,
                                   d.parameters.at(bad->key), bad->text));
}

namespace {
OT::Distribution untruncated(const Distribution& d);
}  // namespace

OT::Distribution to_openturns(const Distribution& d) {
  validate(d);
  const OT::Distribution base = untruncated(d);
  if (!d.truncation) return base;
  const auto [lo, hi] = *d.truncation;
  if (!(lo < hi) || base.computeCDF(hi) - base.computeCDF(lo) <= 0.0)
    throw InputError(fmt::format("{}: the bounds [{}, {}] leave no probability to truncate to", describe(d), lo, hi));
  return OT::TruncatedDistribution(base, lo, hi);
}

namespace {
OT::Distribution untruncated(const Distribution& d) {
  const auto& p = d.parameters;
  const std::string& t = d.type;
  if (t == "uniform") return OT::Uniform(p.at("lower"), p.at("upper"));
  if (t == "normal") return OT::Normal(p.at("mean"), p.at("std"));
  if (t == "lognormal") return OT::LogNormalMuSigma(p.at("mean"), p.at("std"), p.at("location")).getDistribution();
  if (t == "loguniform") return OT::LogUniform(std::log(p.at("lower")), std::log(p.at("upper")));
  if (t == "triangular") return OT::Triangular(p.at("lower"), p.at("mode"), p.at("upper"));
  if (t == "exponential") return OT::Exponential(p.at("rate"), p.at("location"));
  if (t == "beta") return OT::Beta(p.at("alpha"), p.at("beta"), p.at("lower"), p.at("upper"));
  if (t == "gamma") return OT::Gamma(p.at("shape"), p.at("rate"), p.at("location"));
  if (t == "gumbel") return OT::Gumbel(p.at("scale"), p.at("location"));
  if (t == "weibull") return OT::WeibullMin(p.at("scale"), p.at("shape"), p.at("location"));
  throw InputError(fmt::format("distribution type '{}' has no OpenTURNS counterpart", t));  // unreachable
}

}  // namespace

double cdf(const Distribution& d, double x) {
  return to_openturns(d).computeCDF(x);
}

double quantile(const Distribution& d, double p) {
  if (!(p >= 0.0 && p <= 1.0)) throw InputError(fmt::format("quantile: probability {} is not in [0, 1]", p));
  return to_openturns(d).computeQuantile(p)[0];
}

std::string describe(const Distribution& d) {
  std::vector<std::string> parts;
  const Spec* spec = find_spec(d.type);
  if (spec) {
    for (const auto& p : spec->parameters)
      if (auto it = d.parameters.find(p.key); it != d.parameters.end())
        parts.push_back(fmt::format("{}={}", p.key, it->second));
  } else {
    for (const auto& [k, v] : d.parameters) parts.push_back(fmt::format("{}={}", k, v));
  }
  return fmt::format("{}({})", d.type, fmt::join(parts, ", "));
}

}  // namespace suite::studies
