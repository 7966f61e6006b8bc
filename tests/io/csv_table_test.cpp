// The strict numeric CSV reader.

#include "odocal/io/csv_table.hpp"

#include <gtest/gtest.h>

namespace odocal {
namespace {

TEST(CsvTable, ParsesHeaderAndColumnsWithLineNumbers) {
  const CsvTable table = parse_csv_table("t, x ,y\n0,1.5,-2\n\n1,+3,4e-1\n", "f.csv");
  ASSERT_EQ(table.header, (std::vector<std::string>{"t", "x", "y"}));
  ASSERT_EQ(table.rows(), 2u);
  EXPECT_DOUBLE_EQ(table.column("x")[1], 3.0);
  EXPECT_DOUBLE_EQ(table.column("y")[1], 0.4);
  EXPECT_EQ(table.line_of_row[1], 4u);  // the blank line still counts
}

TEST(CsvTable, AcceptsByteOrderMarkAndCrlf) {
  const CsvTable table = parse_csv_table("\xEF\xBB\xBFt,x\r\n0,1\r\n", "f.csv");
  EXPECT_TRUE(table.has("t"));
  EXPECT_DOUBLE_EQ(table.column("x")[0], 1.0);
}

TEST(CsvTable, CommentHeaderOnlyWhenAllowed) {
  const std::string text = "# x_m,y_m\n1,2\n";
  EXPECT_FALSE(parse_csv_table(text, "track.csv").has("x_m"));
  const CsvTable table = parse_csv_table(text, "track.csv", {.header_may_be_comment = true});
  EXPECT_DOUBLE_EQ(table.column("y_m")[0], 2.0);
}

TEST(CsvTable, RejectsDuplicatedColumnName) {
  EXPECT_THROW(parse_csv_table("t,x,x\n", "f.csv"), InputError);
}

TEST(CsvTable, RejectsEmptyHeaderField) {
  EXPECT_THROW(parse_csv_table("t,,x\n", "f.csv"), InputError);
}

TEST(CsvTable, RejectsTooManyFields) {
  try {
    parse_csv_table("t,x\n0,1,2\n", "f.csv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "f.csv:2: expected 2 fields as in the header, got 3");
  }
}

TEST(CsvTable, RejectsOutOfRangeNumber) {
  try {
    parse_csv_table("t\n1e999\n", "f.csv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "f.csv:2: 't': expected a finite number, got '1e999'");
  }
}

TEST(CsvTable, MissingFileIsAnInputError) {
  EXPECT_THROW(read_csv_table("/nonexistent/file.csv"), InputError);
}

}  // namespace
}  // namespace odocal
