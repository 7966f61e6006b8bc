#pragma once
// Checks shared by the stream readers; each throws InputError naming file, line and column.

#include <initializer_list>
#include <string_view>

#include "odocal/data/physical_limits.hpp"
#include "odocal/io/csv_table.hpp"

namespace odocal::detail {

// Every header column must be one of `allowed`.
void require_known_columns(const CsvTable& table, std::initializer_list<std::string_view> allowed);

// The table must have at least `min_rows` data rows; `need` says why, for the message.
void require_rows(const CsvTable& table, std::size_t min_rows, std::string_view need);

// Column "t" must exist, be strictly increasing and lie within kTimeS.
void require_increasing_time(const CsvTable& table);

// Every value of `column` must lie in [min, max].
void require_range(const CsvTable& table, std::string_view column, double min, double max,
                   std::string_view expected);

// The same for a physical range; the message is "<what> from <min> to <max>".
void require_within(const CsvTable& table, std::string_view column, PhysicalRange range,
                    std::string_view what);

}  // namespace odocal::detail
