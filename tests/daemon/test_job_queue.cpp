// The bounded queue with reservations, and the ids and names that may reach the store.
#include <gtest/gtest.h>

#include <set>

#include "daemon/job_queue.h"
#include "daemon/job_store.h"

namespace mdhd::service_test {
namespace {

TEST(JobQueue, ReservationsCountAgainstTheLimitAndOrderIsKept) {
  service::JobQueue q(2);
  ASSERT_TRUE(q.reserve());
  ASSERT_TRUE(q.reserve());
  EXPECT_FALSE(q.reserve());  // two slots taken before anything is queued
  q.release();
  ASSERT_TRUE(q.reserve());
  q.pushReserved("a");
  q.pushReserved("b");
  EXPECT_FALSE(q.reserve());
  q.pushRestored("c");  // restored jobs are queued whatever the limit
  EXPECT_EQ(q.size(), 3u);
  EXPECT_TRUE(q.remove("b"));
  EXPECT_FALSE(q.remove("b"));
  EXPECT_EQ(q.pop(), "a");
  EXPECT_EQ(q.pop(), "c");
  EXPECT_EQ(q.pop(), std::nullopt);
  EXPECT_TRUE(q.reserve());
}

TEST(JobIds, RandomHexOfFixedShape) {
  std::set<std::string> seen;
  for (int i = 0; i < 1000; ++i) {
    const std::string id = service::newJobId();
    EXPECT_TRUE(service::isJobId(id)) << id;
    seen.insert(id);
  }
  EXPECT_EQ(seen.size(), 1000u);
  for (const char* bad : {"", "../x", "0123456789abcdef0123456789abcdeF",
                          "0123456789abcdef0123456789abcde", "0123456789abcdef0123456789abcdef0"}) {
    EXPECT_FALSE(service::isJobId(bad)) << bad;
  }
}

TEST(MachineNames, SafeSpellingOnly) {
  for (const char* good : {"3axis-mill", "AC_trunnion.v2", "m"}) {
    EXPECT_TRUE(service::isMachineName(good)) << good;
  }
  for (const char* bad : {"", ".hidden", "-x", "a/b", "a b", "..", "a\\b", "caf\xc3\xa9"}) {
    EXPECT_FALSE(service::isMachineName(bad)) << bad;
  }
  EXPECT_FALSE(service::isMachineName(std::string(65, 'a')));
}

}  // namespace
}  // namespace mdhd::service_test
