// A prepared log's accelerometer against its input's: the prepared log starts at first motion,
// and its forward readings are the input's less the offset that the preparation removed.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>

#include "odocal/data/log.hpp"

namespace odocal::testing {

inline void expect_forward_offset_removed(const ImuStream& in, const ImuStream& out,
                                          double removed_mps2) {
  const auto first = static_cast<std::size_t>(
      std::lower_bound(in.t_s.begin(), in.t_s.end(), out.t_s.front()) - in.t_s.begin());
  for (std::size_t k = 0; k < out.size(); k += 97) {
    ASSERT_EQ(out.t_s[k], in.t_s[first + k]);
    EXPECT_NEAR(out.ax_mps2[k], in.ax_mps2[first + k] - removed_mps2, 1e-12);
  }
}

}  // namespace odocal::testing
