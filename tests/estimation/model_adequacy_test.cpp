// Model adequacy against residuals with a known dependence: drawn white residuals are explained;
// a heading error per metre proportional to lateral acceleration, or an along-track error
// proportional to longitudinal acceleration or to the grade, or a Doppler distance short of the
// wheels' under acceleration, is named.

#include "odocal/estimation/model_adequacy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace odocal {
namespace {

// A drive of 1 s intervals weaving at 10-20 m/s over hills of up to 5 % grade (known when
// `grade_known`): heading error k_y a_y per metre and along-track error k_x a_x + k_g grade per
// metre, plus white noise.
std::vector<OdometryResidualSample> drive(double k_y, double k_x, std::uint64_t seed,
                                          double k_g = 0.0, bool grade_known = false) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<OdometryResidualSample> samples;
  Eigen::Vector3d pose(0.0, 0.0, 0.0);
  for (int i = 0; i < 400; ++i) {
    const double t = i;
    const double speed = 15.0 + 5.0 * std::sin(0.07 * t);
    const double next_speed = 15.0 + 5.0 * std::sin(0.07 * (t + 1.0));
    const double yaw_rate = 0.2 * std::sin(0.21 * t);
    const double ay = speed * yaw_rate, ax = next_speed - speed;
    Eigen::Vector3d next = pose;
    next.x() += speed * std::cos(pose.z());
    next.y() += speed * std::sin(pose.z());
    next.z() += yaw_rate;
    OdometryResidualSample s{
        t, t + 1.0, pose, next, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    const double grade = 0.05 * std::sin(0.013 * t);
    if (grade_known) s.grade = grade;
    s.error = Eigen::Vector3d((k_x * ax + k_g * grade) * speed + 0.01 * noise(rng),
                              0.01 * noise(rng), k_y * ay * speed + 1e-3 * noise(rng));
    s.whitened = Eigen::Vector3d(s.error(0) / 0.01, s.error(1) / 0.01, s.error(2) / 1e-3);
    samples.push_back(s);
    pose = next;
  }
  return samples;
}

TEST(ModelAdequacy, WhiteResidualsAreExplained) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const ModelAdequacy m = assess_model_adequacy(drive(0.0, 0.0, seed));
    EXPECT_TRUE(m.judged);
    EXPECT_TRUE(m.explains) << m.verdict;
    EXPECT_NEAR(m.chi2_per_dof, 1.0, 0.15);
    EXPECT_NE(m.verdict.find("explains this log"), std::string::npos);
  }
}

TEST(ModelAdequacy, NamesTheQuantityTheResidualsFollow) {
  const ModelAdequacy load = assess_model_adequacy(drive(2e-5, 0.0, 3));
  EXPECT_FALSE(load.explains);
  EXPECT_NE(load.verdict.find("heading residual follows lateral acceleration"), std::string::npos)
      << load.verdict;
  const ModelAdequacy slip = assess_model_adequacy(drive(0.0, 2e-3, 4));
  EXPECT_FALSE(slip.explains);
  EXPECT_NE(slip.verdict.find("along-track residual follows longitudinal acceleration"),
            std::string::npos)
      << slip.verdict;
}

TEST(ModelAdequacy, NamesTheGradeWhereTheLogHasIt) {
  // Slip with the climbing force (0.75 per mille of the distance at 5 %), beyond acceleration and
  // speed.
  const ModelAdequacy climb = assess_model_adequacy(drive(0.0, 0.0, 7, 1.5e-2, true));
  EXPECT_FALSE(climb.explains);
  EXPECT_NE(climb.verdict.find("along-track residual follows grade"), std::string::npos)
      << climb.verdict;
  // The same hills without slip are explained, the grade tested all the same.
  const ModelAdequacy no_slip = assess_model_adequacy(drive(0.0, 0.0, 7, 0.0, true));
  EXPECT_TRUE(no_slip.explains) << no_slip.verdict;
  EXPECT_EQ(no_slip.dependences.size(), 5u);
  // Without the altitude the grade is not a quantity the verdict can name.
  const ModelAdequacy unknown = assess_model_adequacy(drive(0.0, 0.0, 7, 1.5e-2, false));
  EXPECT_EQ(unknown.dependences.size(), 4u);
  EXPECT_EQ(unknown.verdict.find("grade"), std::string::npos) << unknown.verdict;
  // No altitude for the first quarter of the log (a long log whose first block had none): the
  // grade is tested where it is known.
  std::vector<OdometryResidualSample> partly = drive(0.0, 0.0, 7, 1.5e-2, true);
  for (std::size_t i = 0; i < partly.size() / 4; ++i)
    partly[i].grade = std::numeric_limits<double>::quiet_NaN();
  const ModelAdequacy known_later = assess_model_adequacy(partly);
  ASSERT_EQ(known_later.dependences.size(), 5u);
  EXPECT_NE(known_later.verdict.find("along-track residual follows grade"), std::string::npos)
      << known_later.verdict;
}

TEST(ModelAdequacy, NamesTheSlipTheDopplerSpeedSees) {
  // The poses follow the wheels between fixes, so the along-track residual stays white; the
  // Doppler distance per interval falls short of the wheels' by 2 per mille per m/s^2.
  std::vector<OdometryResidualSample> samples = drive(0.0, 0.0, 8);
  std::mt19937_64 rng(8);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (std::size_t i = 1; i + 1 < samples.size(); ++i) {
    const double distance = (samples[i].pose1 - samples[i].pose0).head<2>().norm();
    const double ax = (samples[i + 1].pose1 - samples[i + 1].pose0).head<2>().norm() - distance;
    samples[i].doppler_error_m = -2e-3 * ax * distance + noise(rng);
  }
  const ModelAdequacy slip = assess_model_adequacy(samples);
  EXPECT_EQ(slip.dependences.size(), 6u);
  EXPECT_FALSE(slip.explains);
  EXPECT_NE(slip.verdict.find("Doppler speed residual follows longitudinal acceleration"),
            std::string::npos)
      << slip.verdict;
  EXPECT_NE(slip.verdict.find("not simultaneous"), std::string::npos) << slip.verdict;
  // White Doppler residuals are explained; where the log has none, the Doppler is not tested.
  for (OdometryResidualSample& s : samples) s.doppler_error_m = noise(rng);
  const ModelAdequacy white = assess_model_adequacy(samples);
  EXPECT_EQ(white.dependences.size(), 6u);
  EXPECT_TRUE(white.explains) << white.verdict;
  EXPECT_EQ(assess_model_adequacy(drive(0.0, 0.0, 8)).dependences.size(), 4u);
}

TEST(ModelAdequacy, NamesTheModelItJudges) {
  // Residuals of a fit with tyre terms judge that model, not the plain two-wheel one.
  const ModelAdequacy plain = assess_model_adequacy(drive(0.0, 0.0, 6));
  EXPECT_EQ(plain.verdict.rfind("the two-wheel model explains this log", 0), 0u) << plain.verdict;
  const ModelAdequacy white = assess_model_adequacy(drive(0.0, 0.0, 6), "physical");
  EXPECT_EQ(white.verdict.rfind("the two-wheel model with the physical tyre terms explains", 0), 0u)
      << white.verdict;
  const ModelAdequacy slip = assess_model_adequacy(drive(0.0, 2e-3, 4), "extended");
  EXPECT_EQ(slip.verdict.rfind("the two-wheel model with the extended tyre terms does not", 0), 0u)
      << slip.verdict;
  EXPECT_NE(slip.verdict.find("the tyre terms leave that in the residuals"), std::string::npos);
  EXPECT_EQ(slip.verdict.find("constant circumference"), std::string::npos);
}

TEST(ModelAdequacy, TooFewIntervalsAreNotJudged) {
  auto samples = drive(0.0, 0.0, 5);
  samples.resize(8);
  const ModelAdequacy m = assess_model_adequacy(samples);
  EXPECT_FALSE(m.judged);
  EXPECT_FALSE(m.explains);  // not "explained" where nothing was judged
  EXPECT_NE(m.verdict.find("too few"), std::string::npos);
}

}  // namespace
}  // namespace odocal
