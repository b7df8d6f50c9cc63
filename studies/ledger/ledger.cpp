#include "studies/ledger/ledger.hpp"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"

namespace suite::studies {

std::string input_hash(const std::vector<std::string>& names, const std::vector<double>& values) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&](const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  for (std::size_t i = 0; i < names.size(); ++i) {
    mix(names[i].data(), names[i].size());
    const auto bits = std::bit_cast<std::uint64_t>(i < values.size() ? values[i] : 0.0);
    mix(&bits, sizeof bits);
  }
  return fmt::format("{:016x}", h);
}

namespace {
// JSON has no NaN: a non-finite response is written as null and read back as NaN.
nlohmann::json numbers(const std::vector<double>& v) {
  auto a = nlohmann::json::array();
  for (double x : v) a.push_back(std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr));
  return a;
}
std::vector<double> numbers(const nlohmann::json& a) {
  std::vector<double> v;
  for (const auto& x : a) v.push_back(x.is_null() ? std::nan("") : x.get<double>());
  return v;
}
}  // namespace

Ledger::Ledger(std::filesystem::path path)
    : log_(std::move(path), "study ledger", [](const std::string& last) {
        try {
          return nlohmann::json::parse(last).contains("eval_id");
        } catch (const nlohmann::json::exception&) {
          return false;
        }
      }) {}

void Ledger::append(const LedgerEntry& e) {
  const nlohmann::json j = {{"eval_id", e.eval_id}, {"inputs", numbers(e.inputs)},
                            {"hash", e.hash},       {"status", e.ok ? "ok" : "failed"},
                            {"reason", e.reason},   {"responses", numbers(e.responses)},
                            {"wall_s", e.wall_s},   {"host", e.host}};
  log_.append(j.dump());
}

std::vector<LedgerEntry> Ledger::read(const std::filesystem::path& path) {
  std::vector<LedgerEntry> out;
  std::ifstream in(path);
  if (!in) return out;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    const bool last = in.peek() == std::char_traits<char>::eof();
    try {
      const auto j = nlohmann::json::parse(line);
      LedgerEntry e;
      e.eval_id = j.at("eval_id").get<long>();
      e.inputs = numbers(j.at("inputs"));
      e.hash = j.at("hash").get<std::string>();
      e.ok = j.at("status").get<std::string>() == "ok";
      e.reason = j.value("reason", "");
      e.responses = numbers(j.at("responses"));
      e.wall_s = j.value("wall_s", 0.0);
      e.host = j.value("host", "");
      out.push_back(std::move(e));
    } catch (const nlohmann::json::exception& ex) {
      if (last) break;  // torn by a kill mid-write: that evaluation reruns
      throw InputError(fmt::format("{}:{}: not a ledger line ({}); remove or repair the line and resume again",
                                   path.string(), number, ex.what()));
    }
  }
  return out;
}

}  // namespace suite::studies
