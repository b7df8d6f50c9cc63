#include "carving/batch/run_batch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "carving/batch/manifest.hpp"
#include "carving/batch/results_table.hpp"
#include "carving/batch/seed_register.hpp"
#include "carving/measure/measure_seed.hpp"
#include "carving/measure/seed_profile.hpp"
#include "core/config/config.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/mpi/collective_try.hpp"
#include "core/mpi/task_farm.hpp"

namespace suite::carving {
namespace {

nlohmann::json number(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json();
}
double number(const nlohmann::json& j) {
  return j.is_null() ? std::nan("") : j.get<double>();
}

std::string encode(const SeedRow& r) {
  return nlohmann::json{{"id", r.id},
                        {"method", r.method},
                        {"d",
                         {number(r.length_mm), number(r.width_mm), number(r.thickness_mm), number(r.volume_mm3),
                          number(r.surface_mm2), number(r.density_mg_mm3)}},
                        {"n_views", r.n_views},
                        {"ok", r.ok},
                        {"quality", r.quality},
                        {"message", r.message},
                        {"wall_s", r.wall_s},
                        {"host", r.host}}
      .dump();
}

SeedRow decode(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  SeedRow r;
  r.id = j.at("id").get<std::string>();
  r.method = j.at("method").get<std::string>();
  const auto& d = j.at("d");
  r.length_mm = number(d[0]), r.width_mm = number(d[1]), r.thickness_mm = number(d[2]);
  r.volume_mm3 = number(d[3]), r.surface_mm2 = number(d[4]), r.density_mg_mm3 = number(d[5]);
  r.n_views = j.at("n_views").get<int>();
  r.ok = j.at("ok").get<bool>();
  r.quality = j.at("quality").get<std::string>();
  r.message = j.at("message").get<std::string>();
  r.wall_s = j.at("wall_s").get<double>();
  r.host = j.at("host").get<std::string>();
  return r;
}

// Every profile the batch names, read and checked before any seed is measured.
std::map<std::filesystem::path, SeedProfile> read_profiles(const std::vector<SeedEntry>& seeds,
                                                           const std::filesystem::path& fallback) {
  std::map<std::filesystem::path, SeedProfile> profiles;
  for (const auto& s : seeds) {
    const auto path = s.profile.empty() ? fallback : s.profile;
    if (path.empty())
      throw InputError(
          fmt::format("seed '{}' names no profile and the batch has no --profile; give one of them", s.id));
    if (!profiles.count(path)) profiles.emplace(path, read_seed_profile(config::Config::from_file(path)));
  }
  return profiles;
}

std::filesystem::path results_file(const BatchOptions& o) {
  return o.out / (o.shard_count > 0 ? fmt::format("results.{}.csv", o.shard_index) : "results.csv");
}

}  // namespace

BatchCounts run_batch(const BatchOptions& options, Logger& log) {
  const bool farm = options.comm && options.comm->size() > 1;
  const bool writer = !farm || options.comm->is_root();
  std::vector<SeedEntry> seeds;
  std::map<std::filesystem::path, SeedProfile> profiles;
  std::vector<long> pending;
  BatchCounts counts;
  std::unique_ptr<ResultsWriter> results;
  auto prepare = [&] {
    seeds = read_manifest(options.manifest);
    profiles = read_profiles(seeds, options.profile);
    if (!writer) return;
    register_seeds(options.out, seeds);
    std::set<std::string> done;
    for (const auto& row : read_results(results_file(options)))
      if (row.ok || !options.retry_failed) done.insert(row.id);
    for (std::size_t i = 0; i < seeds.size(); ++i) {
      if (options.shard_count > 0 && static_cast<int>(i % options.shard_count) != options.shard_index) continue;
      ++counts.seeds;
      if (done.count(seeds[i].id)) {
        ++counts.skipped;
      } else {
        pending.push_back(static_cast<long>(i));
      }
    }
    results = std::make_unique<ResultsWriter>(results_file(options));
  };
  if (farm) {
    mpi::collective_try(*options.comm, prepare);
  } else {
    prepare();
  }
  if (writer)
    log.info("{} seeds, {} already measured, {} to measure{}", counts.seeds, counts.skipped, pending.size(),
             farm ? fmt::format(" on {} worker ranks", options.comm->size() - 1) : "");

  auto measure = [&](long index) {
    const SeedEntry& seed = seeds[static_cast<std::size_t>(index)];
    const auto& profile = profiles.at(seed.profile.empty() ? options.profile : seed.profile);
    return measure_seed(seed, profile, options.out / "seeds" / safe_folder_name(seed.id));
  };
  const auto started = std::chrono::steady_clock::now();
  auto record = [&](const SeedRow& row) {
    results->append(row);
    ++counts.measured;
    if (!row.ok) ++counts.failed;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const double eta = elapsed / counts.measured * (pending.size() - counts.measured);
    if (row.ok) {
      log.info("seed {}/{} '{}': {:.4g} mm^3, {:.3g} x {:.3g} x {:.3g} mm ({:.2f} s); ETA {:.0f} s", counts.measured,
               pending.size(), row.id, row.volume_mm3, row.length_mm, row.width_mm, row.thickness_mm, row.wall_s, eta);
    } else {
      log.warn("seed {}/{} '{}' failed: {}", counts.measured, pending.size(), row.id, row.message);
    }
  };
  if (farm) {
    mpi::run_task_farm(
        *options.comm, pending, [&](long i) { return encode(measure(i)); },
        [&](const std::string& text) { record(decode(text)); });
  } else {
    for (long i : pending) record(measure(i));
  }
  if (writer) {
    results.reset();
    if (options.shard_count == 0) merge_batch(options.out);  // the table in manifest order
  }
  return counts;
}

void merge_batch(const std::filesystem::path& out) {
  const std::vector<std::string> order = registered_ids(out);
  std::map<std::string, SeedRow> newest;
  std::vector<std::filesystem::path> files;
  if (std::filesystem::exists(out / "results.csv")) files.push_back(out / "results.csv");
  const std::regex shard(R"(results\.[0-9]+\.csv)");
  for (const auto& e : std::filesystem::directory_iterator(out))
    if (std::regex_match(e.path().filename().string(), shard)) files.push_back(e.path());
  std::sort(files.begin() + (files.empty() || files[0].filename() != "results.csv" ? 0 : 1), files.end());
  for (const auto& f : files)
    for (auto& row : read_results(f)) newest[row.id] = std::move(row);
  write_results(out / "results.csv", in_order(order, std::move(newest)));
}

}  // namespace suite::carving
