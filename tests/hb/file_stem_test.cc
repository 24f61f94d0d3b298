// File names made of the user's texts (hb/file_stem.h): never a path, a
// hidden file or an option, and one per item.
#include "hb/file_stem.h"

#include <set>
#include <string>

#include <gtest/gtest.h>

namespace beamid::hb {
namespace {

TEST(FileStem, KeepsPlainCharactersAndReplacesTheRest) {
  EXPECT_EQ(FileStem("frf-high_2.5N", "p_"), "frf-high_2.5N");
  EXPECT_EQ(FileStem("1,5 N", "p_"), "1_5_N");
  EXPECT_EQ(FileStem("../../etc/passwd", "p_"), "p_.._.._etc_passwd");
  EXPECT_EQ(FileStem("-rf", "p_"), "p_-rf");
  EXPECT_EQ(FileStem(".hidden", "p_"), "p_.hidden");
  EXPECT_EQ(FileStem("", "p_"), "p_");
  EXPECT_EQ(FileStem("très", "p_"), "tr__s");  // each byte of a UTF-8 character
  EXPECT_EQ(FileStem(std::string(300, 'a'), "p_").size(), 120u);
}

TEST(FileStem, AStemTakenGetsANumber) {
  std::set<std::string> taken;
  EXPECT_EQ(UniqueFileStem("low", "p_", taken), "low");
  EXPECT_EQ(UniqueFileStem("low", "p_", taken), "low-2");
  EXPECT_EQ(UniqueFileStem("l/w", "p_", taken), "l_w");
  EXPECT_EQ(UniqueFileStem("low", "p_", taken), "low-3");
}

}  // namespace
}  // namespace beamid::hb
