#include "experiments/experiment_progress.hpp"

#include <fmt/format.h>

namespace odocal::experiments {

ExperimentProgress::ExperimentProgress(std::FILE* out, int total_pieces)
    : out_(out), total_(total_pieces) {}

void ExperimentProgress::begin(const std::string& label) {
  piece_start_ = Clock::now();
  fmt::print(out_, "[{:>3}/{}] {} ... ", done_ + 1, total_, label);
  std::fflush(out_);
}

void ExperimentProgress::end(bool reused) {
  const double piece_s = std::chrono::duration<double>(Clock::now() - piece_start_).count();
  ++done_;
  if (reused) {
    fmt::print(out_, "reused\n");
    return;
  }
  ++computed_;
  computed_s_ += piece_s;
  // Pieces still to do are assumed to cost what the computed ones cost on average.
  const double left_s = computed_s_ / computed_ * (total_ - done_);
  fmt::print(out_, "{:.1f} s (elapsed {:.0f} s, ~{:.0f} s left)\n", piece_s, elapsed_s(), left_s);
  std::fflush(out_);
}

double ExperimentProgress::elapsed_s() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

}  // namespace odocal::experiments
