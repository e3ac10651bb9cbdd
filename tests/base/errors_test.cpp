#include "base/errors.hpp"

#include <gtest/gtest.h>

using sculpt::SourceLocation;

TEST(SourceLocation, PrintsWhatIsKnown) {
  EXPECT_EQ((SourceLocation{"a.bsp", 3, 7}).str(), "a.bsp:3:7");
  EXPECT_EQ((SourceLocation{"a.bsp", 3, 0}).str(), "a.bsp:3");
  EXPECT_EQ((SourceLocation{"a.bsp", 0, 0}).str(), "a.bsp");
  EXPECT_FALSE(SourceLocation{}.known());
}

TEST(Errors, CarryTheirLocationAndDeriveFromStandardTypes) {
  try {
    throw sculpt::InvalidInput("bad number", {"c.txt", 12, 4});
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "bad number");
    EXPECT_EQ(dynamic_cast<const sculpt::InvalidInput&>(e).where().str(), "c.txt:12:4");
  }
  try {
    throw sculpt::IoError("out.off", "cannot open");
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "out.off: cannot open");
  }
}
