// Reading CSV tables: the real reference data of data/ and the messages for
// malformed files.
#include <gtest/gtest.h>

#include "core/io/csv_table.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using suite::io::CsvTable;
using suite::testing::input_error_of;

const std::filesystem::path kReference = std::filesystem::path(SUITE_DATA_DIR);

TEST(CsvTable, ReadsTheDissertationDamScenes) {
  const auto t = CsvTable::read(kReference / "dissertation_table_3_4_dam_scenes.csv");
  ASSERT_EQ(t.rows(), 8u);  // Table 3.4 lists eight scenes
  EXPECT_FALSE(t.comments().empty());
  const auto ex2 = t.find_row("scene", "example2");
  EXPECT_DOUBLE_EQ(t.number(ex2, "reservoir_level"), 3.25);
  EXPECT_DOUBLE_EQ(t.number(ex2, "water_particles"), 197542);
  EXPECT_DOUBLE_EQ(t.number(t.find_row("scene", "HansonE1S1"), "dam_height"), 4.60);
  EXPECT_EQ(t.numbers("gravity").size(), 8u);
  const std::string msg = input_error_of([&] { t.find_row("scene", "exemple2"); });
  EXPECT_NE(msg.find("no row with scene = 'exemple2'; did you mean 'example2'?"), std::string::npos) << msg;
}

TEST(CsvTable, ReadsMartinMoyce) {
  const auto t = CsvTable::read(kReference / "martin_moyce_1952_surge_front.csv");
  const auto T = t.numbers("T"), Z = t.numbers("Z");
  ASSERT_GT(T.size(), 10u);
  for (std::size_t i = 1; i < T.size(); ++i) {
    EXPECT_GT(T[i], T[i - 1]);  // the surge front only advances
    EXPECT_GE(Z[i], Z[i - 1]);
  }
}

TEST(CsvTable, QuotedFieldsAndBlanks) {
  const auto t = CsvTable::parse("# note\nname, value ,remark\n\"a, b\",  2.5 ,\"say \"\"hi\"\"\"\n", "q.csv");
  EXPECT_EQ(t.columns(), (std::vector<std::string>{"name", "value", "remark"}));
  EXPECT_EQ(t.text(0, "name"), "a, b");
  EXPECT_DOUBLE_EQ(t.number(0, "value"), 2.5);
  EXPECT_EQ(t.text(0, "remark"), "say \"hi\"");
  EXPECT_EQ(t.comments(), (std::vector<std::string>{"note"}));
}

TEST(CsvTable, MalformedFilesNameTheLine) {
  EXPECT_NE(input_error_of([] {
              CsvTable::parse("a,b\n1,2\n3\n", "m.csv");
            }).find("m.csv:3: 1 fields, but the header has 2 (a, b)"),
            std::string::npos);
  const auto t = CsvTable::parse("# c\na,b\n1,x\n", "n.csv");
  EXPECT_NE(input_error_of([&] { t.number(0, "b"); }).find("n.csv:3: column 'b' = 'x': expected a number"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { t.column("bb"); }).find("no column 'bb'; did you mean 'b'? (columns: a, b)"),
            std::string::npos);
  EXPECT_NE(
      input_error_of([] { CsvTable::parse("a\n\"open\n", "o.csv"); }).find("o.csv:2: a quoted field is not closed"),
      std::string::npos);
  EXPECT_NE(input_error_of([] { CsvTable::read("/nonexistent.csv"); }).find("no such file"), std::string::npos);
}

}  // namespace
