#pragma once
// Dakota's annotated tabular data file (environment keyword `tabular_data`), byte for byte as
// current Dakota writes it (snl-dakota/dakota src/dakota_tabular_io.cpp: write_header_tabular,
// write_leading_columns; src/DakotaResponse.cpp: Response::write_tabular[_labels];
// src/dakota_data_io.hpp: write_data_tabular), with the default write_precision 10:
//
//   %eval_id interface x1             x2             f              \n
//   1        NO_ID      0.9            1.1            0.0002         \n
//
// - header: "%", "eval_id" left-aligned in width 7, " ", "interface" (width 8, so no padding),
//   " ", then each label left-aligned in width 14 and a space;
// - rows: the id left-aligned in width 8 and a space, the interface id ("NO_ID" when empty)
//   left-aligned in width 10 and a space, then each value as "%.10g" left-aligned in width
//   precision + 4 = 14 and a space; every line ends with that space and "\n".
// Everything after the header is left-aligned because Dakota's header and interface writers
// set std::left on the stream and never reset it (compare the rows of
// snl-dakota/dakota-examples official/drivers/black-box_simulation_windows/dakota_tabular.dat).
// Older Dakota releases right-aligned the values; the reader accepts any spacing.
//
// Failed evaluations: Dakota has no failure marker in this file. With failure_capture abort
// (the default) the study stops and no row is written; with retry only the successful
// attempt is written; with recover the row holds the recovery values like any other row.
// Responses Dakota did not compute (ASV bit off) are written "N/A". Pass NaN responses for a
// failure recovered as NaN: they are written "nan", as Dakota's stream writes a NaN.
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace suite::dakota {

struct Row {
  long eval_id = 0;
  std::string interface_id;  // "" where the file says NO_ID (or EMPTY, Dakota 6.1)
  std::vector<double> variables;
  std::vector<double> responses;  // NaN where the file says N/A or nan
};

class TabularWriter {
 public:
  // Writes the header line at once. `precision` is Dakota's output_precision (default 10);
  // the value columns are precision + 4 wide. Throws InputError for a label with white space.
  TabularWriter(std::ostream& out, std::vector<std::string> variables, std::vector<std::string> responses,
                bool with_interface = true, int precision = 10);

  // One evaluation; "" interface_id writes NO_ID. Flushes, as Dakota does, so a crash keeps
  // the rows written. Throws InputError for counts that do not match the header.
  void row(long eval_id, const std::string& interface_id, const std::vector<double>& variables,
           const std::vector<double>& responses);

 private:
  std::ostream& out_;
  std::size_t num_variables_;
  std::size_t num_responses_;
  bool with_interface_;
  int precision_;
};

// Reads an annotated file (header, eval id and, if with_interface, interface id columns):
// the first num_variables value columns are variables, the rest responses. Throws InputError
// naming "<source_name>:<line>" for a missing or unexpected header, a row with the wrong
// column count, or a value that is not a number, N/A or nan.
std::vector<Row> read_tabular(const std::string& text, const std::string& source_name, std::size_t num_variables,
                              bool with_interface = true);

}  // namespace suite::dakota
