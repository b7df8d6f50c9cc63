#pragma once
// Dakota's parameters file: what Dakota writes before each evaluation of an analysis driver,
// in its "standard" layout or its APREPRO layout (interface keyword `aprepro`).
//
// Byte layout, as written by Dakota (snl-dakota/dakota src/ProcessApplicInterface.cpp,
// write_parameters_file; src/StandardParametersFileWriter.cpp and
// src/ApreproParametersFileWriter.cpp in newer releases; the array writers in
// src/dakota_data_io.hpp), with write_precision = 15 and field width w = 22:
//
//   standard: every line is 21 spaces, a field of width 22 (right-aligned), one space, a tag
//   (below, after the 3 characters "// "):
//                                           2 variables
//                       1.500000000000000e+00 x1
//                      -2.000000000000000e+00 x2
//                                           1 functions
//                                           1 ASV_1:f
//                                           2 derivative_variables
//                                           1 DVV_1:x1
//                                           2 DVV_2:x2
//                                           0 analysis_components
//                                           1 eval_id
//                                           0 metadata
//   Real values are scientific with 15 digits after the point (16 significant digits).
//
//   aprepro: every line is 20 spaces and "{ TAG = VALUE }", the tag left-aligned in width 15,
//   the value right-aligned in width 22; string values (analysis components, metadata) are
//   quoted and only the opening quote takes the width:
//                     { DAKOTA_VARS     =                      2 }
//                     { x1              =  1.500000000000000e+00 }
//                     { x2              = -2.000000000000000e+00 }
//                     { DAKOTA_FNS      =                      1 }
//                     { ASV_1:f         =                      1 }
//                     { DAKOTA_DER_VARS =                      2 }
//                     { DVV_1:x1        =                      1 }
//                     { DVV_2:x2        =                      2 }
//                     { DAKOTA_AN_COMPS =                      1 }
//                     { AC_1:drv        =                      "a b" }
//                     { DAKOTA_EVAL_ID  =                      1 }
//                     { DAKOTA_METADATA =                      0 }
//
// DVV values are 1-based positions of the derivative variables among the variables; the
// `<n> metadata` block (Dakota 6.16 and newer) is always written and optional when read.
#include <string>
#include <utility>
#include <vector>

namespace suite::dakota {

struct Parameters {
  std::vector<std::pair<std::string, double>> variables;  // name, value; in Dakota's order
  std::vector<std::string> responses;                     // response descriptors
  std::vector<int> asv;                                   // empty on write: 1 (value only) for each response
  std::vector<std::string> derivative_variables;          // empty on write: every variable
  std::vector<std::string> analysis_components;
  std::string eval_id = "1";  // "1", or "1:2" for a nested or batch evaluation
  // Additions beyond the brief, both optional: the driver named in the `AC_i:<driver>` tags
  // ("" writes plain `AC_i`), and the metadata descriptors (`<name> MD_i`).
  std::string analysis_driver;
  std::vector<std::string> metadata;
};

enum class ParametersFormat { standard, aprepro };

// The file's text, byte for byte as Dakota writes it. Throws InputError for a name with
// white space, a value that is not finite, an ASV of the wrong length or a derivative
// variable that is not a variable.
std::string write_parameters(const Parameters& parameters, ParametersFormat format);

// Reads either layout (decided by the first line). White space is free, as in Dakota's own
// reader (dakota.interfacing). Throws InputError naming "<source_name>:<line>" and what was
// expected. One evaluation per file: batch files are refused.
Parameters read_parameters(const std::string& text, const std::string& source_name);

// The layout of `text` as read_parameters sees it.
ParametersFormat detect_parameters_format(const std::string& text);

}  // namespace suite::dakota
