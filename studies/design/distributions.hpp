#pragma once
// Probability distributions of uncertain study variables (docs/methods/studies.md), read from YAML and
// handed to OpenTURNS for sampling. Every distribution is given in the parameters of the variable
// itself (never of its logarithm), with these keys and these OpenTURNS classes:
//
//   uniform      lower, upper                 OT::Uniform(a = lower, b = upper)
//   normal       mean, std                    OT::Normal(mu = mean, sigma = std)
//   lognormal    mean, std, location = 0      mean and standard deviation of X itself (NOT of
//                                             log X): OT::LogNormalMuSigma(mu, sigma, gamma)
//                                             .getDistribution(), i.e. OT::LogNormal with
//                                             sigma_log^2 = log(1 + (std / (mean - location))^2),
//                                             mu_log = log(mean - location) - sigma_log^2 / 2
//   loguniform   lower, upper (0 < lower)     bounds of X itself: OT::LogUniform(aLog = log lower,
//                                             bLog = log upper)
//   triangular   lower, mode, upper           OT::Triangular(a = lower, m = mode, b = upper)
//   exponential  rate, location = 0           OT::Exponential(lambda = rate, gamma = location);
//                                             pdf rate exp(-rate (x - location)), x >= location
//   beta         alpha, beta, lower, upper    OT::Beta(alpha, beta, a = lower, b = upper); pdf
//                                             proportional to (x - a)^(alpha-1) (b - x)^(beta-1)
//   gamma        shape, rate, location = 0    OT::Gamma(k = shape, lambda = rate, gamma = location);
//                                             pdf proportional to (x - gamma)^(k-1) exp(-lambda (x - gamma))
//   gumbel       scale, location              OT::Gumbel(beta = scale, gamma = location) (maximum
//                                             Gumbel); cdf exp(-exp(-(x - location) / scale))
//   weibull      scale, shape, location = 0   OT::WeibullMin(beta = scale, alpha = shape,
//                                             gamma = location); cdf 1 - exp(-((x - location) / scale)^shape)
//
//   variables:
//     - {name: Kd, distribution: {type: lognormal, mean: 1.0, std: 0.5}}
//
// OpenTURNS stays out of this header (its headers are slow to compile); the conversion
// to_openturns() lives in studies/design/openturns_bridge.hpp.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/config/config.hpp"

namespace suite::studies {

struct Distribution {
  std::string type;                          // one of distribution_types()
  std::map<std::string, double> parameters;  // keys as above; optional keys hold their defaults
  // Truncation to [lower, upper] (a variable with a distribution and explicit bounds, as Dakota
  // truncates bounded uncertain variables); OpenTURNS' TruncatedDistribution.
  std::optional<std::pair<double, double>> truncation;
};

// The accepted values of `type`, in the order above.
const std::vector<std::string>& distribution_types();

// Reads a mapping such as {type: normal, mean: 2, std: 0.5}. InputError (file:line, key) for an
// unknown type (with a did-you-mean), a missing or non-numeric parameter, or an invalid one
// (std <= 0, lower >= upper, a mode outside [lower, upper], mean <= location for lognormal, ...).
// Unknown keys are left to Config::finish().
Distribution read_distribution(const config::Section& s);

// Throws InputError if `d` (e.g. built in code) has an unknown type, a missing parameter or an
// invalid one; the message names the distribution and the parameter.
void validate(const Distribution& d);

// Cumulative distribution function and quantile (inverse cdf, p in [0, 1]) of `d`, via OpenTURNS.
double cdf(const Distribution& d, double x);
double quantile(const Distribution& d, double p);

// E.g. "normal(mean=2, std=0.5)".
std::string describe(const Distribution& d);

}  // namespace suite::studies
