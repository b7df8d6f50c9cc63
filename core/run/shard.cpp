#include "core/run/shard.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace suite {

Shard parse_shard(const std::string& value, const std::string& flag) {
  Shard s;
  const auto slash = value.find('/');
  try {
    std::size_t used_k = 0, used_n = 0;
    if (slash == std::string::npos) throw std::invalid_argument(value);
    const std::string k = value.substr(0, slash), n = value.substr(slash + 1);
    s.index = std::stoi(k, &used_k);
    s.count = std::stoi(n, &used_n);
    if (used_k != k.size() || used_n != n.size()) s.count = 0;
  } catch (const std::exception&) {
    s.count = 0;
  }
  if (s.count < 1 || s.index < 0 || s.index >= s.count)
    throw InputError(fmt::format("{} '{}': write K/N with 0 <= K < N, e.g. 3/16", flag, value));
  return s;
}

}  // namespace suite
