#include "studies/model/command_model.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/dakota/results_file.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/run/executable_path.hpp"
#include "studies/model/process.hpp"

namespace suite::studies {

namespace {

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  if (!in) throw InputError(fmt::format("cannot read '{}'", p.string()));
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = 0; (at = s.find(from, at)) != std::string::npos; at += to.size())
    s.replace(at, from.size(), to);
  return s;
}

}  // namespace

std::unique_ptr<Model> CommandModel::read(const config::Section& s, const std::vector<std::string>& variables,
                                          const std::filesystem::path& work_root) {
  using config::Range;
  Settings st;
  st.variables = variables;
  st.work_root = work_root;
  st.command = s.get<std::vector<std::string>>("command");
  std::vector<std::string> given = st.command;
  if (st.command.empty())
    s.reject("command", "name the program and its arguments, e.g. [./driver.sh, params.in, results.out]");
  for (auto& a : st.command) a = replace_all(a, "{bindir}", executable_dir().string());
  // A program named by a relative path is the study folder's, not the work directory's.
  if (st.command[0].find('/') != std::string::npos && std::filesystem::path(st.command[0]).is_relative())
    given[0] = st.command[0] = std::filesystem::absolute(s.base_dir() / st.command[0]).lexically_normal().string();
  s.record("command", given);  // study.yaml names the program absolutely; {bindir} stays a tag
  for (const auto& t : s.has("templates") ? s.sections("templates") : std::vector<config::Section>{}) {
    const auto file = t.file("file");
    const std::string to = t.get<std::string>("to", file.filename().string());
    Template tpl = Template::parse(read_text(file), file.string());
    for (const auto& name : tpl.names())
      if (std::find(variables.begin(), variables.end(), name) == variables.end())
        t.reject("file", fmt::format("the template uses '{}', which is not a variable of the study", name));
    st.templates.emplace_back(std::move(tpl), to);
  }
  if (auto p = s.optional_section("parameters_file")) {
    st.parameters_file = p->get<std::string>("name", "params.in");
    st.parameters_format = p->choice("format", {"standard", "aprepro"}, "standard") == "aprepro"
                               ? dakota::ParametersFormat::aprepro
                               : dakota::ParametersFormat::standard;
  }
  const auto results = s.section("results");
  st.results_file = results.get<std::string>("file");
  st.results_are_summary = results.choice("format", {"dakota", "summary"}, "dakota") == "summary";
  st.responses = s.get<std::vector<std::string>>("responses");
  if (st.responses.empty()) s.reject("responses", "name at least one response");
  if (s.has("copy")) st.copy = s.files("copy");
  const auto wd = s.section_or_empty("work_directory");
  st.work_name = wd.get<std::string>("name", st.work_name);
  if (st.work_name.find("{eval_id}") == std::string::npos)
    wd.reject("name", "must contain {eval_id}, so evaluations running at once do not share a folder");
  st.keep = wd.get<bool>("keep", true);
  st.time_limit_s = s.quantity("time_limit", "s", 0.0, Range::at_least(0));
  st.retries = static_cast<int>(s.integer("retries", 0, 0, 10));
  return std::make_unique<CommandModel>(std::move(st));
}

Outcome CommandModel::attempt(const std::filesystem::path& dir, long eval_id,
                              const std::map<std::string, double>& values) const {
  Outcome out;
  out.responses.assign(s_.responses.size(), std::nan(""));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  for (const auto& [tpl, to] : s_.templates) io::write_file_atomic(dir / to, tpl.render(values));
  for (const auto& c : s_.copy) std::filesystem::copy(c, dir / c.filename(), std::filesystem::copy_options::recursive);
  if (!s_.parameters_file.empty()) {
    dakota::Parameters p;
    for (const auto& v : s_.variables) p.variables.emplace_back(v, values.at(v));
    p.responses = s_.responses;
    p.eval_id = std::to_string(eval_id);
    io::write_file_atomic(dir / s_.parameters_file, dakota::write_parameters(p, s_.parameters_format));
  }
  const ProcessResult pr = run_process(s_.command, dir, s_.time_limit_s);
  if (!pr.started || pr.timed_out || pr.exit_status != 0) {
    out.reason = pr.reason;
    return out;
  }
  const auto results = dir / s_.results_file;
  if (!std::filesystem::exists(results)) {
    out.reason = fmt::format("'{}' finished but wrote no {}", s_.command[0], results.string());
    return out;
  }
  if (s_.results_are_summary) {
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(read_text(results));
    } catch (const nlohmann::json::exception& e) {
      out.reason = fmt::format("{}: not JSON ({})", results.string(), e.what());
      return out;
    }
    for (std::size_t i = 0; i < s_.responses.size(); ++i) {
      const auto it = j.find(s_.responses[i]);
      if (it == j.end() || !(it->is_number() || it->is_boolean())) {
        out.reason = fmt::format("{}: no numeric '{}'", results.string(), s_.responses[i]);
        return out;
      }
      out.responses[i] = it->is_boolean() ? (it->get<bool>() ? 1.0 : 0.0) : it->get<double>();
    }
  } else {
    const auto r = dakota::read_results(read_text(results), results.string(), s_.responses.size());
    if (r.failed) {
      out.reason = fmt::format("{} reports a failed evaluation", results.string());
      return out;
    }
    out.responses = r.values;
  }
  for (std::size_t i = 0; i < out.responses.size(); ++i)
    if (!std::isfinite(out.responses[i])) {
      out.reason = fmt::format("response '{}' is not finite", s_.responses[i]);
      return out;
    }
  out.ok = true;
  return out;
}

Outcome CommandModel::evaluate(long eval_id, const std::map<std::string, double>& values) const {
  const auto dir = s_.work_root / replace_all(s_.work_name, "{eval_id}", std::to_string(eval_id));
  Outcome out;
  for (int a = 0; a <= s_.retries; ++a) {
    try {
      out = attempt(dir, eval_id, values);
    } catch (const std::exception& e) {
      out = Outcome{false, e.what(), std::vector<double>(s_.responses.size(), std::nan(""))};
    }
    if (out.ok) break;
  }
  if (out.ok && !s_.keep) std::filesystem::remove_all(dir);
  if (!out.ok && s_.retries > 0) out.reason = fmt::format("{} (after {} attempts)", out.reason, s_.retries + 1);
  return out;
}

}  // namespace suite::studies
