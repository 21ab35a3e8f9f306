// What a start makes of the store a dead process left: running jobs queued again
// and finished, a job the process died under too often failed instead of rerun,
// and one service per data folder.
#include <gtest/gtest.h>

#include "daemon/job_store.h"
#include "job_helpers.h"
#include "service_fixture.h"

namespace mdhd::service_test {
namespace {

// The store as a process that died while `id` ran leaves it.
void leaveRunning(const service::ServiceConfig& c, const std::string& id) {
  service::JobStore store(c.data_dir);
  if (!store.job(id)) store.insertJob(id, tinyJob().dump(), "");
  store.markRunning(id);
}

TEST(Restart, JobsLeftRunningRunAgain) {
  TempDir dir;
  service::ServiceConfig c = testConfig(dir.path());
  c.max_interruptions = 2;
  const std::string again = service::newJobId();
  const std::string other = service::newJobId();
  leaveRunning(c, again);
  leaveRunning(c, other);
  RunningService svc(c);
  auto cli = svc.client();
  const nlohmann::json rerun = waitSettled(*cli, again);
  EXPECT_EQ(rerun["status"], "done");
  EXPECT_EQ(rerun["interrupted"], 1);
  EXPECT_EQ(rerun["attempts"], 2);
  EXPECT_EQ(rerun["report"]["status"], "clean");
  EXPECT_EQ(waitSettled(*cli, other)["status"], "done");  // 1 interruption: below the limit
}

TEST(Restart, TheLimitOfInterruptionsFailsTheJobWithAReport) {
  TempDir dir;
  service::ServiceConfig c = testConfig(dir.path());
  c.max_interruptions = 1;
  const std::string id = service::newJobId();
  leaveRunning(c, id);
  RunningService svc(c);
  auto cli = svc.client();
  const nlohmann::json doc = getJson(*cli, "/api/v1/jobs/" + id);
  EXPECT_EQ(doc["status"], "failed");
  EXPECT_EQ(doc["interrupted"], 1);
  EXPECT_EQ(doc["report"]["status"], "error");
  EXPECT_NE(doc["report"]["error"]["message"].get<std::string>().find("stopped while running"),
            std::string::npos);
}

TEST(Restart, OneServicePerDataFolder) {
  TempDir dir;
  const service::ServiceConfig c = testConfig(dir.path());
  RunningService first(c);
  try {
    service::Service second(c);
    FAIL() << "a second service opened the same data folder";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("another mdhd serve"), std::string::npos) << e.what();
  }
}

// DELETE of a job that finishes between the route's read and its cancel: the store
// cancels only what is still unfinished, so a done job keeps its status and report.
TEST(JobStoreCancel, OnlyUnfinishedJobsAreCancelled) {
  TempDir dir;
  service::JobStore store((dir.path() / "data").string());
  store.insertJob("00000000000000000000000000000001", tinyJob().dump(), "");
  store.insertJob("00000000000000000000000000000002", tinyJob().dump(), "");
  store.markRunning("00000000000000000000000000000002");
  store.insertJob("00000000000000000000000000000003", tinyJob().dump(), "");
  store.finishJob("00000000000000000000000000000003", "done", std::string(R"({"status":"clean"})"),
                  false);
  EXPECT_TRUE(store.cancelUnfinished("00000000000000000000000000000001"));
  EXPECT_TRUE(store.cancelUnfinished("00000000000000000000000000000002"));
  EXPECT_FALSE(store.cancelUnfinished("00000000000000000000000000000003"));
  EXPECT_EQ(store.job("00000000000000000000000000000001")->status, "cancelled");
  EXPECT_EQ(store.job("00000000000000000000000000000002")->status, "cancelled");
  const auto done = store.job("00000000000000000000000000000003");
  EXPECT_EQ(done->status, "done");
  ASSERT_TRUE(done->report.has_value());
  EXPECT_EQ(*done->report, R"({"status":"clean"})");
}

}  // namespace
}  // namespace mdhd::service_test
