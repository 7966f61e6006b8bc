#pragma once
// Progress of a long experiment on the terminal: which piece runs, how many are done, and the
// time left estimated from the pieces computed so far.

#include <chrono>
#include <cstdio>
#include <string>

namespace odocal::experiments {

class ExperimentProgress {
 public:
  ExperimentProgress(std::FILE* out, int total_pieces);

  void begin(const std::string& label);
  void end(bool reused);
  double elapsed_s() const;

 private:
  using Clock = std::chrono::steady_clock;
  std::FILE* out_;
  int total_;
  int done_ = 0;
  int computed_ = 0;
  double computed_s_ = 0.0;
  Clock::time_point start_ = Clock::now();
  Clock::time_point piece_start_;
};

}  // namespace odocal::experiments
