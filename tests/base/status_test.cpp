#include "crowdbake/base/status.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace crowdbake {
namespace {

// The names sit in a table in StatusCode's order: a code added or moved without its name
// would name another code.
TEST(StatusCodeName, EachCodeHasItsOwnName) {
  EXPECT_STREQ(status_code_name(StatusCode::kOk), "ok");
  EXPECT_STREQ(status_code_name(StatusCode::kInvalidPack), "invalid pack");
  EXPECT_STREQ(status_code_name(StatusCode::kInvalidFsm), "invalid behaviour fsm");
  EXPECT_STREQ(status_code_name(StatusCode::kInternal), "internal error");
  EXPECT_STREQ(status_code_name(StatusCode::kOutputError), "output error");
  std::set<std::string> names;
  for (int c = 0; c <= static_cast<int>(StatusCode::kLast); ++c)
    names.insert(status_code_name(static_cast<StatusCode>(c)));
  EXPECT_EQ(names.size(), static_cast<size_t>(StatusCode::kLast) + 1);
  EXPECT_EQ(names.count("unknown"), 0u);
  EXPECT_STREQ(status_code_name(static_cast<StatusCode>(99)), "unknown");
}

TEST(Status, DefaultIsOkAndCarriesItsMessage) {
  EXPECT_TRUE(Status().ok());
  const Status s(StatusCode::kIoError, "a.pack: cannot open");
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.code(), StatusCode::kIoError);
  EXPECT_EQ(s.message(), "a.pack: cannot open");
}

}  // namespace
}  // namespace crowdbake
