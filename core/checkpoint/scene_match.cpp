#include "core/checkpoint/scene_match.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>

#include "core/errors.hpp"

namespace suite::checkpoint {

namespace {

constexpr const char* kSeparator = " = ";

bool covered(const std::string& key, const std::vector<std::string>& may_change) {
  return std::any_of(may_change.begin(), may_change.end(), [&](const std::string& entry) {
    if (key.size() < entry.size() || key.compare(0, entry.size(), entry) != 0) return false;
    return key.size() == entry.size() || key[entry.size()] == '.' || key[entry.size()] == '[';
  });
}

std::string shown(const std::map<std::string, std::string>& keys, const std::string& key) {
  const auto it = keys.find(key);
  return it == keys.end() ? "not set" : "'" + it->second + "'";
}

}  // namespace

std::string SceneRecord::text() const {
  std::string out;
  for (const auto& [key, value] : keys_) out += key + kSeparator + value + "\n";
  return out;
}

std::vector<unsigned char> SceneRecord::bytes() const {
  const std::string t = text();
  return {t.begin(), t.end()};
}

SceneRecord SceneRecord::from_text(const std::string& text, const std::string& where) {
  std::map<std::string, std::string> keys;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto cut = line.find(kSeparator);
    if (cut == std::string::npos || cut == 0)
      throw InputError(
          fmt::format("{}: line {} of its scene record ('{}') is not 'key = value'; the file is "
                      "damaged: restart from another checkpoint or start again",
                      where, number, line));
    keys[line.substr(0, cut)] = line.substr(cut + std::char_traits<char>::length(kSeparator));
  }
  return SceneRecord(std::move(keys));
}

SceneRecord SceneRecord::from_bytes(const std::vector<unsigned char>& bytes, const std::string& where) {
  return from_text(std::string(bytes.begin(), bytes.end()), where);
}

std::vector<std::string> SceneRecord::differences(const SceneRecord& now,
                                                  const std::vector<std::string>& may_change) const {
  std::vector<std::string> keys;
  for (const auto& [key, value] : keys_) {
    const auto it = now.keys_.find(key);
    if ((it == now.keys_.end() || it->second != value) && !covered(key, may_change)) keys.push_back(key);
  }
  for (const auto& [key, value] : now.keys_)
    if (!keys_.count(key) && !covered(key, may_change)) keys.push_back(key);
  std::sort(keys.begin(), keys.end());
  return keys;
}

void SceneRecord::require_same(const SceneRecord& now, const std::vector<std::string>& may_change,
                               const std::string& where) const {
  const auto keys = differences(now, may_change);
  if (keys.empty()) return;
  std::string list;
  for (const auto& key : keys)
    list +=
        fmt::format("{}{}: {} there, {} here", list.empty() ? "" : "; ", key, shown(keys_, key), shown(now.keys_, key));
  std::string allowed;
  for (const auto& key : may_change) allowed += (allowed.empty() ? "" : ", ") + key;
  throw InputError(fmt::format("{} was written for another scene ({}); restart with the scene it was written with{}",
                               where, list,
                               allowed.empty() ? "" : fmt::format(" (a restart may change only {})", allowed)));
}

void require_later_end(double end, double time, const std::string& where) {
  if (!(end > time * (1 + 1e-12)))
    throw InputError(fmt::format("time.end = {} s: {} is at t = {} s already; give a later time.end to extend the run",
                                 end, where, time));
}

}  // namespace suite::checkpoint
