#pragma once
// import csv --sync's edits of a staged log: a stream's clock moved (its t column), or one column
// of wheels.csv moved in time against the others (a bus signal logged late).

#include <filesystem>
#include <string>

namespace odocal::detail {

// Adds shift_s to the first column (t) of every row, leaving every other byte; line by line, so
// that a file of any length passes through.
void shift_times(const std::filesystem::path& file, double shift_s);

// Each row's `column` becomes its value late_s later (linear between rows, the ends held), for a
// column that was logged late_s after the rest of its row.
void advance_column(const std::filesystem::path& file, const std::string& column, double late_s);

}  // namespace odocal::detail
