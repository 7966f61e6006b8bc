#include "import_command.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <memory>

#include "odocal/io/csv_import.hpp"

namespace odocal::cli {
namespace {

struct ImportArgs {
  std::string map_file;
  std::string out_dir;
  std::string source_dir;
};

void run_import(const ImportArgs& args) {
  const std::filesystem::path map_file(args.map_file);
  const std::filesystem::path source =
      args.source_dir.empty() ? map_file.parent_path() : std::filesystem::path(args.source_dir);
  const ImportSummary summary = import_csv(map_file, source, args.out_dir);
  fmt::print("imported     {} -> {}\n", source.string(), args.out_dir);
  fmt::print("{:<8} {:>8} {:>12} {:>10} {:>14}\n", "stream", "rows", "duration s", "rate Hz",
             "largest gap s");
  for (const ImportedStreamSummary& s : summary.streams) {
    fmt::print("{:<8} {:>8} {:>12.1f} {:>10.1f} {:>14.3f}\n", s.name, s.rows, s.duration_s,
               s.median_rate_hz, s.largest_gap_s);
  }
  fmt::print("distance     {:.1f} m (rear wheels, nominal circumferences)\n",
             summary.wheel_distance_m);
}

}  // namespace

void add_import_command(CLI::App& app) {
  CLI::App* import =
      app.add_subcommand("import", "Convert other loggers' files into an odocal log");
  import->require_subcommand(1);
  auto args = std::make_shared<ImportArgs>();
  CLI::App* csv =
      import->add_subcommand("csv", "CSV files described by a YAML column map (docs/importing.md)");
  csv->add_option("--map", args->map_file, "Column map YAML")->required();
  csv->add_option("--out", args->out_dir, "Output log directory")->required();
  csv->add_option("--in", args->source_dir,
                  "Directory of the logger's files (default: the map's directory)");
  csv->callback([args] { run_import(*args); });
}

}  // namespace odocal::cli
