#pragma once
// Messages echo values from the data (a file name, a field, a cell): a control character there
// would split the line or drive the terminal. Escaped, every message stays one printable line.

#include <string>
#include <string_view>

namespace odocal::cli {

// Control characters (and DEL) as \xNN; everything else, UTF-8 included, as it is.
std::string printable_line(std::string_view message);

}  // namespace odocal::cli
