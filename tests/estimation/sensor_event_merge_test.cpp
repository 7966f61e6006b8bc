// The reference filter's four-way merge of the sensor time bases, against the independent
// answer: every event materialised and stable-sorted by (time, kind).

#include "estimation/sensor_event_merge.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>

#include "odocal/error.hpp"

namespace odocal {
namespace {

// Strictly increasing times on a 10 ms grid, so the four streams share many instants.
std::vector<double> random_times(std::mt19937& rng, int count) {
  std::uniform_int_distribution<int> gap(1, 4);
  std::vector<double> t_s;
  int tick = gap(rng);
  for (int k = 0; k < count; ++k, tick += gap(rng)) t_s.push_back(0.01 * tick);
  return t_s;
}

std::vector<SensorEvent> sorted_events(const Log& log, double begin_s) {
  std::vector<SensorEvent> events;
  const auto add = [&](const std::vector<double>& t_s, SensorEventKind kind) {
    for (std::size_t k = 0; k < t_s.size(); ++k)
      if (t_s[k] >= begin_s) events.push_back({t_s[k], kind, k});
  };
  if (log.imu) add(log.imu->t_s, SensorEventKind::kImu);
  add(log.gnss.t_s, SensorEventKind::kGnss);
  if (log.heading) add(log.heading->t_s, SensorEventKind::kHeading);
  add(log.wheels.t_s, SensorEventKind::kWheel);
  std::stable_sort(events.begin(), events.end(), [](const SensorEvent& a, const SensorEvent& b) {
    return std::tie(a.t_s, a.kind) < std::tie(b.t_s, b.kind);
  });
  return events;
}

std::vector<SensorEvent> merged_events(const Log& log, double begin_s) {
  SensorEventMerge merge(log, begin_s);
  const std::size_t announced = merge.remaining();
  std::vector<SensorEvent> events;
  while (const std::optional<SensorEvent> event = merge.next()) events.push_back(*event);
  EXPECT_EQ(events.size(), announced);
  EXPECT_EQ(merge.remaining(), 0u);
  return events;
}

void expect_same_order(const std::vector<SensorEvent>& actual,
                       const std::vector<SensorEvent>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    EXPECT_EQ(actual[i].t_s, expected[i].t_s) << "event " << i;
    EXPECT_EQ(actual[i].kind, expected[i].kind) << "event " << i;
    EXPECT_EQ(actual[i].index, expected[i].index) << "event " << i;
  }
}

ImuStream imu_at(std::vector<double> t_s) {
  ImuStream imu;
  imu.t_s = std::move(t_s);
  return imu;
}

HeadingStream heading_at(std::vector<double> t_s) {
  HeadingStream heading;
  heading.t_s = std::move(t_s);
  return heading;
}

Log random_log(std::mt19937& rng, bool with_imu, bool with_heading) {
  Log log;
  log.wheels.t_s = random_times(rng, 300);
  log.gnss.t_s = random_times(rng, 120);
  if (with_imu) log.imu = imu_at(random_times(rng, 250));
  if (with_heading) log.heading = heading_at(random_times(rng, 80));
  return log;
}

TEST(SensorEventMerge, OrdersLikeAStableSortByTimeThenKind) {
  std::mt19937 rng(7);
  for (const bool with_imu : {true, false}) {
    for (const bool with_heading : {true, false}) {
      const Log log = random_log(rng, with_imu, with_heading);
      for (const double begin_s : {-1.0, 0.0, 0.5, 1.234}) {
        SCOPED_TRACE(::testing::Message() << "imu " << with_imu << ", heading " << with_heading
                                          << ", begin " << begin_s);
        expect_same_order(merged_events(log, begin_s), sorted_events(log, begin_s));
      }
    }
  }
}

TEST(SensorEventMerge, SharedInstantsPutInputBeforeMeasurementsBeforeTheWheel) {
  Log log;
  log.wheels.t_s = {1.0};
  log.gnss.t_s = {1.0};
  log.imu = imu_at({1.0});
  log.heading = heading_at({1.0});
  const std::vector<SensorEvent> events = merged_events(log, 0.0);
  ASSERT_EQ(events.size(), 4u);
  EXPECT_EQ(events[0].kind, SensorEventKind::kImu);
  EXPECT_EQ(events[1].kind, SensorEventKind::kGnss);
  EXPECT_EQ(events[2].kind, SensorEventKind::kHeading);
  EXPECT_EQ(events[3].kind, SensorEventKind::kWheel);
}

TEST(SensorEventMerge, RejectsATimeBaseThatIsNotStrictlyIncreasing) {
  Log log;
  log.wheels.t_s = {0.0, 0.1, 0.2};
  log.gnss.t_s = {0.0, 0.5};
  log.imu = imu_at({0.0, 0.1, 0.1, 0.3});
  try {
    SensorEventMerge merge(log, 0.0);
    FAIL() << "a repeated IMU time was accepted";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "the IMU stream's time is not strictly increasing at sample 2");
  }
  log.imu.reset();
  log.wheels.t_s[2] = std::nan("");
  EXPECT_THROW(SensorEventMerge(log, 0.0), Error);
}

}  // namespace
}  // namespace odocal
