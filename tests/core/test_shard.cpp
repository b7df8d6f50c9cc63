// --shard K/N: the share of an array task, and the message for every malformed value.
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "core/run/shard.hpp"

namespace suite {
namespace {

TEST(Shard, ParsesIndexAndCount) {
  const Shard s = parse_shard("3/16");
  EXPECT_EQ(s.index, 3);
  EXPECT_EQ(s.count, 16);
  EXPECT_EQ(parse_shard("0/1").count, 1);
}

TEST(Shard, RejectsWhatIsNotKOverNWithKBelowN) {
  for (const char* bad : {"16/16", "-1/4", "3", "3/", "/4", "a/b", "1/0", "2/4x", "1.5/4"}) {
    try {
      parse_shard(bad);
      ADD_FAILURE() << "'" << bad << "' accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("--shard '") + bad + "': write K/N"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace suite
