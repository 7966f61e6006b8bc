// Reading logs: the CSV parser's throughput (MB/s) and a whole example log.

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "odocal/io/csv_table.hpp"
#include "odocal/io/log_reader.hpp"

namespace {

std::string wheel_csv(std::size_t rows) {
  std::string text = "t,rl_ticks,rr_ticks\n";
  for (std::size_t k = 0; k < rows; ++k) {
    text += fmt::format("{:.3f},{},{}\n", 0.02 * static_cast<double>(k), 5 * k, 5 * k + k / 7);
  }
  return text;
}

void BM_ParseCsv(benchmark::State& state) {
  const std::string text = wheel_csv(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    odocal::CsvTable table = odocal::parse_csv_table(text, "wheels.csv");
    benchmark::DoNotOptimize(table.columns.back().back());
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(text.size()));
}
BENCHMARK(BM_ParseCsv)->Arg(75'000)->Unit(benchmark::kMillisecond);

void BM_ReadExampleLog(benchmark::State& state) {
  for (auto _ : state) {
    odocal::Log log = odocal::read_log(ODOCAL_SOURCE_DIR "/examples/figure-eight");
    benchmark::DoNotOptimize(log.wheels.rev_rl.back());
  }
}
BENCHMARK(BM_ReadExampleLog)->Unit(benchmark::kMillisecond);

}  // namespace
