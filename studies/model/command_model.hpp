#pragma once
// Any program as a study's model, the way Dakota runs analysis drivers (docs/methods/studies.md):
// each evaluation gets a tagged work directory with the rendered input files and a Dakota
// parameters file, the program runs there (own process group, captured output, time limit,
// retries), and its responses come from a Dakota results file or from a summary.json.
//
//   model:
//     type: command
//     command: ["{bindir}/breach", "dam.yaml", "--out", "run"]   # or a program and a Dakota
//                                                                 # driver: [./driver.sh, params.in, results.out]
//     templates: [{file: dam.tmpl, to: dam.yaml}]    # rendered with the point's values
//     parameters_file: {name: params.in, format: standard}   # optional: standard | aprepro
//     results: {file: results.out, format: dakota}           # or {file: run/summary.json, format: summary}
//     responses: [peak_outflow]
//     copy: [soil_table.csv]                                 # files copied into each work dir
//     work_directory: {name: "workdir.{eval_id}", keep: true}
//     time_limit: 10 min                                     # per attempt; default none
//     retries: 1                                             # extra attempts after a failure
//
// Relative paths (templates, copy, the program when it contains a '/') are taken from the
// study file's folder; work directories are made in the study's output folder. `{bindir}` in
// the command is the folder of the suite's executables (the one `study` runs from).
#include <filesystem>
#include <string>
#include <vector>

#include "core/dakota/parameters_file.hpp"
#include "studies/model/model.hpp"
#include "studies/template/template.hpp"

namespace suite::studies {

class CommandModel : public Model {
 public:
  struct Settings {
    std::vector<std::string> command;
    std::vector<std::pair<Template, std::string>> templates;  // template, file name in the work dir
    std::string parameters_file;                              // "" = none
    dakota::ParametersFormat parameters_format = dakota::ParametersFormat::standard;
    std::string results_file;
    bool results_are_summary = false;
    std::vector<std::string> responses, variables;
    std::vector<std::filesystem::path> copy;
    std::string work_name = "workdir.{eval_id}";
    bool keep = true;
    double time_limit_s = 0.0;
    int retries = 0;
    std::filesystem::path work_root;
  };
  explicit CommandModel(Settings s) : s_(std::move(s)) {}
  static std::unique_ptr<Model> read(const config::Section& model, const std::vector<std::string>& variables,
                                     const std::filesystem::path& work_root);

  Outcome evaluate(long eval_id, const std::map<std::string, double>& values) const override;
  // Every template file rendered (not written): the program itself is not run.
  void check(const std::map<std::string, double>& values) const override {
    for (const auto& [tpl, to] : s_.templates) tpl.render(values);
  }
  const std::vector<std::string>& responses() const override { return s_.responses; }

 private:
  Outcome attempt(const std::filesystem::path& dir, long eval_id, const std::map<std::string, double>& values) const;
  Settings s_;
};

}  // namespace suite::studies
