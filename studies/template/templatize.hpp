#pragma once
// `study templatize`: turns an input file engineers already have into a template, so it need not
// be rewritten by hand (docs/methods/studies.md, "Templates"). Each variable names the place of one
// number in the file:
//   LINE:FIELD   the FIELD-th whitespace-separated field of line LINE (1-based), for
//                fixed-column text such as a WinDAM C input file; its spacing is kept
//   key.path     the number at the start of a YAML value (a unit after it is kept), e.g.
//                soil.erodibility in "erodibility: 300 (ft/h)/psf"; list items as key[2]
// The number becomes {NAME}; every other brace of the file is escaped (\{ \}), so a YAML flow
// mapping survives. Rendering the template with the numbers found gives the file back.
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace suite::studies {

struct Templatized {
  std::string text;                      // the template
  std::map<std::string, double> values;  // the numbers that were replaced, by variable
};

// InputError names the file, the variable and the location when a place holds no number.
Templatized templatize(const std::string& text, const std::string& source_name,
                       const std::vector<std::pair<std::string, std::string>>& variables);

}  // namespace suite::studies
