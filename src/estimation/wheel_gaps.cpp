#include "odocal/estimation/wheel_gaps.hpp"

#include <algorithm>

namespace odocal {

double median_sample_period_s(const WheelStream& wheels) {
  if (wheels.size() < 2) return 0.0;
  std::vector<double> steps(wheels.size() - 1);
  for (std::size_t k = 1; k < wheels.size(); ++k) steps[k - 1] = wheels.t_s[k] - wheels.t_s[k - 1];
  const auto middle = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
  std::nth_element(steps.begin(), middle, steps.end());
  return *middle;
}

std::vector<WheelGap> find_wheel_gaps(const WheelStream& wheels, double max_gap_s) {
  std::vector<WheelGap> gaps;
  for (std::size_t k = 1; k < wheels.size(); ++k) {
    const double step = wheels.t_s[k] - wheels.t_s[k - 1];
    if (step > max_gap_s) gaps.push_back({k, wheels.t_s[k - 1], step});
  }
  return gaps;
}

void break_chain_at_gaps(WheelStream& wheels, const std::vector<WheelGap>& gaps) {
  if (gaps.empty()) return;
  wheels.chain_break.assign(wheels.size(), 0);
  for (const WheelGap& gap : gaps) {
    wheels.chain_break[gap.sample] = 1;
    wheels.rev_rl[gap.sample] = 0.0;
    wheels.rev_rr[gap.sample] = 0.0;
    if (!wheels.rev_fl.empty()) wheels.rev_fl[gap.sample] = 0.0;
    if (!wheels.rev_fr.empty()) wheels.rev_fr[gap.sample] = 0.0;
  }
}

}  // namespace odocal
