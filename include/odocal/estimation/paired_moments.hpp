#pragma once
// Running sums of paired samples (x, y): the least-squares line of y on x and their Pearson
// correlation, for checks that compare one signal with another (the doctor's, a reader's).

#include <cmath>
#include <cstddef>
#include <limits>

namespace odocal {

class PairedMoments {
 public:
  void add(double x, double y) {
    sx_ += x;
    sy_ += y;
    sxx_ += x * x;
    syy_ += y * y;
    sxy_ += x * y;
    ++count_;
  }

  std::size_t count() const { return count_; }
  // The (co)variances about the means, per sample.
  double variance_x() const { return centred_xx() / n(); }
  double variance_y() const { return centred_yy() / n(); }

  // Of y on x with an intercept; NaN when x does not vary.
  double slope() const {
    const double vx = centred_xx();
    return vx > 0.0 ? centred_xy() / vx : kNaN;
  }
  // NaN when x or y does not vary.
  double correlation() const {
    const double vx = centred_xx(), vy = centred_yy();
    return vx > 0.0 && vy > 0.0 ? centred_xy() / std::sqrt(vx * vy) : kNaN;
  }

 private:
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double n() const { return count_ > 0 ? static_cast<double>(count_) : kNaN; }
  double centred_xx() const { return sxx_ - sx_ * sx_ / n(); }
  double centred_yy() const { return syy_ - sy_ * sy_ / n(); }
  double centred_xy() const { return sxy_ - sx_ * sy_ / n(); }

  double sx_ = 0.0, sy_ = 0.0, sxx_ = 0.0, syy_ = 0.0, sxy_ = 0.0;
  std::size_t count_ = 0;
};

}  // namespace odocal
