#include "table_checks.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace odocal::detail {

void require_known_columns(const CsvTable& table, std::initializer_list<std::string_view> allowed) {
  for (const std::string& name : table.header) {
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      throw InputError({table.file, 1, name}, fmt::format("unknown column (expected one of {})",
                                                          fmt::join(allowed, ", ")));
    }
  }
}

void require_rows(const CsvTable& table, std::size_t min_rows, std::string_view need) {
  if (table.rows() >= min_rows) return;
  if (table.rows() == 0) throw InputError({table.file, 0, ""}, "empty stream: no data rows");
  throw InputError({table.file, 0, ""},
                   fmt::format("time span too short: {} data row(s), {}", table.rows(), need));
}

void require_increasing_time(const CsvTable& table) {
  const std::vector<double>& t = table.column("t");
  for (std::size_t k = 1; k < t.size(); ++k) {
    if (t[k] > t[k - 1]) continue;
    const std::string problem =
        t[k] == t[k - 1]
            ? fmt::format("duplicated time {} (also on line {}); time must strictly increase", t[k],
                          table.line_of_row[k - 1])
            : fmt::format(
                  "time goes backwards: {} after {} on line {}; time must strictly "
                  "increase",
                  t[k], t[k - 1], table.line_of_row[k - 1]);
    throw InputError(table.at(k, "t"), problem);
  }
  require_within(table, "t", kTimeS, "a time in seconds");
}

void require_range(const CsvTable& table, std::string_view column, double min, double max,
                   std::string_view expected) {
  const std::vector<double>& values = table.column(column);
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (values[k] < min || values[k] > max) {
      throw InputError(table.at(k, column),
                       fmt::format("{} is out of range: expected {}", values[k], expected));
    }
  }
}

void require_within(const CsvTable& table, std::string_view column, PhysicalRange range,
                    std::string_view what) {
  require_range(table, column, range.min, range.max,
                fmt::format("{} from {:g} to {:g}", what, range.min, range.max));
}

}  // namespace odocal::detail
