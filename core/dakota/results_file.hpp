#pragma once
// Dakota's results file: what an analysis driver leaves for Dakota after an evaluation.
//
// Reading follows Dakota's own reader (snl-dakota/dakota src/DakotaResponse.cpp:
// Response::failure_reported and Response::read_flexible_fn_vals):
// - leading white space skipped, the first four characters "fail" in any case mark a failed
//   evaluation (the rest of the file is ignored);
// - otherwise function values, each a number optionally followed by a label (any word that
//   is not a number); white space, including line breaks, separates them; several values may
//   share a line;
// - exactly the expected count of values (Dakota: "Expected N function value(s) but found M").
// This reader also refuses NaN and infinities, and gradients/Hessians ("[ ... ]"), which the
// suite never requests.
//
// Writing follows dakota.interfacing (snl-dakota/dakota
// interfaces/Python/dakota/interfacing/interfacing.py, Results._write_results): one value a
// line as "%24.16E %s", e.g. "  5.0000000000000000E+00 response_fn_1"; "FAIL" for a failure.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace suite::dakota {

struct Results {
  bool failed = false;
  std::vector<double> values;       // empty when failed
  std::vector<std::string> labels;  // one per value; "" where the file gave none
};

// Throws InputError naming "<source_name>:<line>" for a word that is not a number, NaN or an
// infinity, too few or too many values, or gradient/Hessian data.
Results read_results(const std::string& text, const std::string& source_name, std::size_t expected);

// "%24.16E <label>\n" per value ("%24.16E\n" for an empty label). Throws InputError for a
// value that is not finite (write write_failure() instead) or a label with white space.
std::string write_results(const std::vector<std::pair<std::string, double>>& labelled_values);

// "FAIL\n", the failure marker dakota.interfacing writes.
std::string write_failure();

}  // namespace suite::dakota
