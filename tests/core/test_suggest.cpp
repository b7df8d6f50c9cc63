#include <gtest/gtest.h>

#include "core/config/suggest.hpp"

namespace {

TEST(Suggest, EditDistanceCountsTranspositionsAsOneEdit) {
  EXPECT_EQ(suite::edit_distance("cohesion", "cohesion"), 0u);
  EXPECT_EQ(suite::edit_distance("cohesoin", "cohesion"), 1u);
  EXPECT_EQ(suite::edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(suite::edit_distance("", "abc"), 3u);
}

TEST(Suggest, OnlyPlausibleTyposAreSuggested) {
  const std::vector<std::string> keys{"cohesion", "friction_angle", "density"};
  EXPECT_EQ(suite::closest_match("cohesoin", keys).value_or(""), "cohesion");
  EXPECT_EQ(suite::closest_match("Density", keys).value_or(""), "density");
  EXPECT_FALSE(suite::closest_match("gravity", keys).has_value());
  EXPECT_EQ(suite::closest_match("sinus", {"table", "sine"}).value_or(""), "sine");
  EXPECT_FALSE(suite::closest_match("ab", {"xy"}).has_value()) << "short words: one edit at most";
}

}  // namespace
