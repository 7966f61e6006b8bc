#include "import_command.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <memory>

#include "odocal/bag/bag_import.hpp"
#include "odocal/bag/bag_listing.hpp"
#include "odocal/io/csv_import.hpp"

namespace odocal::cli {
namespace {

struct ImportArgs {
  std::string map_file;
  std::string out_dir;
  std::string source_dir;
  bool sync{};
};

void print_summary(const std::string& source, const std::string& out_dir,
                   const ImportSummary& summary) {
  fmt::print("imported     {} -> {}\n", source, out_dir);
  fmt::print("{:<8} {:>8} {:>12} {:>10} {:>14}\n", "stream", "rows", "duration s", "rate Hz",
             "largest gap s");
  for (const ImportedStreamSummary& s : summary.streams) {
    fmt::print("{:<8} {:>8} {:>12.1f} {:>10.1f} {:>14.3f}\n", s.name, s.rows, s.duration_s,
               s.median_rate_hz, s.largest_gap_s);
  }
  fmt::print("distance     {:.1f} m (rear wheels, nominal circumferences)\n",
             summary.wheel_distance_m);
  for (const std::string& note : summary.notes) fmt::print("note         {}\n", note);
  for (const std::string& warning : summary.warnings)
    fmt::print(stderr, "odocal: warning: {}\n", warning);
}

void run_import(const ImportArgs& args) {
  const std::filesystem::path map_file(args.map_file);
  const std::filesystem::path source =
      args.source_dir.empty() ? map_file.parent_path() : std::filesystem::path(args.source_dir);
  CsvImportOptions options;
  options.sync_clocks = args.sync;
  print_summary(source.string(), args.out_dir, import_csv(map_file, source, args.out_dir, options));
}

struct BagImportArgs {
  std::string bag;
  std::string map_file;
  std::string out_dir;
  bool list{};
};

void run_bag_import(const BagImportArgs& args) {
  if (args.list) {
    fmt::print("{}", bag::format_bag_listing(bag::list_bag(args.bag)));
    return;
  }
  if (args.map_file.empty() || args.out_dir.empty())
    throw CLI::ValidationError("import bag", "needs --map and --out (or --list)");
  print_summary(args.bag, args.out_dir, bag::import_bag(args.map_file, args.bag, args.out_dir));
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
  csv->add_flag("--sync", args->sync,
                "Estimate the GNSS and IMU clock offsets against the wheels (as odocal doctor) "
                "and apply them");
  csv->callback([args] { run_import(*args); });

  auto bag_args = std::make_shared<BagImportArgs>();
  CLI::App* bag = import->add_subcommand(
      "bag", "ROS bags: ROS 1 .bag, ROS 2 MCAP and SQLite3 (docs/importing.md)");
  bag->add_option("BAG", bag_args->bag, "Bag file or rosbag2 directory")->required();
  bag->add_option("--map", bag_args->map_file, "Topic map YAML (docs/importing.md)");
  bag->add_option("--out", bag_args->out_dir, "Output log directory");
  bag->add_flag("--list", bag_args->list,
                "Print the topics: type, encoding, count, rate and time span");
  bag->callback([bag_args] { run_bag_import(*bag_args); });
}

}  // namespace odocal::cli
