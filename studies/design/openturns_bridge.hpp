#pragma once
// Internal to studies/design: the OpenTURNS side of distributions and sampling. Include it only
// from .cpp files that need OpenTURNS (its headers are slow to compile).
#include <mutex>
#include <openturns/Distribution.hxx>

#include "studies/design/distributions.hpp"

namespace suite::studies {

// The OpenTURNS distribution of `d` (see the table in distributions.hpp); InputError if `d` is
// invalid (validate()).
OT::Distribution to_openturns(const Distribution& d);

// OT::RandomGenerator is one generator per process, shared by every OpenTURNS object. Whoever
// seeds it and then draws from it (directly or through an experiment, a distribution's
// getSample(), a bootstrap) must hold this mutex for the whole seed-and-draw sequence, or two
// threads interleave their draws and neither result is reproducible. All of studies/design does.
std::mutex& openturns_random_mutex();

}  // namespace suite::studies
