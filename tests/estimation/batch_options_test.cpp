// The batch options' automatic defaults, resolved per log.

#include "odocal/estimation/batch_options.hpp"

#include <gtest/gtest.h>

namespace odocal {
namespace {

TEST(BatchOptions, TheDopplerSpeedIsFittedByDefaultWhereTheLogHasIt) {
  BatchOptions options;
  EXPECT_EQ(options.doppler_sigma_mps(true), BatchOptions::kDefaultDopplerSigmaMps);
  EXPECT_EQ(options.doppler_sigma_mps(false), 0.0);
  for (const TyreModelChoice model : {TyreModelChoice::kPhysical, TyreModelChoice::kAuto}) {
    options.tyre_model = model;
    EXPECT_EQ(options.doppler_sigma_mps(true), BatchOptions::kDefaultDopplerSigmaMps);
  }
  // The regression terms chosen by hand: their extrapolation to rest is pinned confidently wrong.
  options.tyre_model = TyreModelChoice::kExtended;
  EXPECT_EQ(options.doppler_sigma_mps(true), 0.0);
  // Asked for, it is used with any model; 0 turns it off.
  options.gnss_speed_sigma_mps = 0.05;
  EXPECT_EQ(options.doppler_sigma_mps(true), 0.05);
  EXPECT_EQ(options.doppler_sigma_mps(false), 0.0);
  options.tyre_model = TyreModelChoice::kNone;
  options.gnss_speed_sigma_mps = 0.0;
  EXPECT_EQ(options.doppler_sigma_mps(true), 0.0);
  EXPECT_TRUE(options.validate().empty());
  options.gnss_speed_sigma_mps = -2.0;
  EXPECT_FALSE(options.validate().empty());
}

TEST(BatchOptions, ConsistencyPartsAreOffOrAtLeastTwo) {
  BatchOptions options;
  EXPECT_EQ(options.consistency_parts, 0);
  for (const int parts : {0, 2, 4, 20}) {
    options.consistency_parts = parts;
    EXPECT_TRUE(options.validate().empty()) << parts;
  }
  options.consistency_parts = 1;
  EXPECT_NE(options.validate().find("consistency_parts = 1"), std::string::npos);
  options.consistency_parts = 21;
  EXPECT_NE(options.validate().find("consistency_parts"), std::string::npos);
  options.consistency_parts = -1;
  EXPECT_FALSE(options.validate().empty());
}

}  // namespace
}  // namespace odocal
