// The local executor: process groups, logs, exit statuses, SIGTERM-then-SIGKILL, orphan checks.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <fstream>

#include "orchestrator/job_files.hpp"
#include "orchestrator/local_executor.hpp"
#include "orchestrator/process_groups.hpp"
#include "support.hpp"

namespace rockcal::orch {
namespace {

using namespace std::chrono_literals;

struct ExecutorTest : ::testing::Test {
  test::TempDir dir;
  LaunchRequest shell(const std::string& script) {
    return {dir.path(), dir.path() / "log", {"-c", script}};
  }
  ExitStatus wait(Executor& ex, const std::string& handle) {
    ExitStatus s;
    test::poll_until([&] { return (s = ex.poll(handle)).finished; }, 20s);
    return s;
  }
};

LocalExecutorConfig direct(const std::string& program) {
  LocalExecutorConfig c;
  c.engine = program;
  c.ranks = 0;
  c.grace = 500ms;
  return c;
}

TEST_F(ExecutorTest, RunsInOwnGroupCapturingOutputAndExitCode) {
  LocalExecutor ex(direct("/bin/sh"));
  auto handle = ex.launch(shell("echo out; echo err >&2; ps -o pgid= -p $$; exit 3"));
  auto s = wait(ex, handle);
  EXPECT_TRUE(s.finished);
  EXPECT_EQ(s.exit_code, 3);
  auto log = read_text(dir.path() / "log").value_or("");
  EXPECT_NE(log.find("out"), std::string::npos);
  EXPECT_NE(log.find("err"), std::string::npos);
  EXPECT_NE(log.find(handle), std::string::npos) << "the job is its own process group leader";
  EXPECT_NE(std::to_string(getpgrp()), handle);
}

TEST_F(ExecutorTest, ReportsDeathBySignal) {
  LocalExecutor ex(direct("/bin/sh"));
  auto s = wait(ex, ex.launch(shell("kill -SEGV $$")));
  EXPECT_EQ(s.signal, SIGSEGV);
  EXPECT_NE(s.describe().find("signal"), std::string::npos);
}

TEST_F(ExecutorTest, CancelEscalatesToSigkillAndReachesTheWholeGroup) {
  LocalExecutor ex(direct("/bin/sh"));
  // Ignores SIGTERM, and has a grandchild that must not survive either.
  auto handle = ex.launch(shell("trap '' TERM; sleep 300 & sleep 300; wait"));
  pid_t pgid = std::stoi(handle);
  ASSERT_TRUE(test::poll_until([&] { return group_members(pgid).size() >= 3; }, 5s));
  auto t0 = std::chrono::steady_clock::now();
  auto s = ex.cancel(handle);
  EXPECT_EQ(s.signal, SIGKILL);
  EXPECT_GE(std::chrono::steady_clock::now() - t0, 400ms) << "SIGTERM first, with a grace period";
  EXPECT_TRUE(test::poll_until([&] { return group_members(pgid).empty(); }, 5s));
}

TEST_F(ExecutorTest, StopsOrphansOnlyWhenTheGroupRunsTheEngine) {
  // Jobs launched by a "previous server" (another executor instance) are found and stopped.
  LocalExecutor previous(direct(test::fake_engine()));
  LocalExecutor restarted(direct(test::fake_engine()));
  auto hanging_job = [&](const std::filesystem::path& job_dir) {
    std::filesystem::create_directories(job_dir);
    std::ofstream(job_dir / "job.json") << R"({"test": "uct", "bond": {"fr0": 17.0, "fs0": 1.0}})";
    auto handle =
        previous.launch({job_dir,
                         job_dir / "log",
                         {"run", (job_dir / "job.json").string(), "--out", job_dir.string()}});
    EXPECT_TRUE(test::poll_until(
        [&] { return group_runs_engine(std::stoi(handle), "fake-rockcal-dem.sh"); }, 5s));
    return handle;  // possibly still between env and bash: the search must see it all the same
  };
  // By the recorded handle.
  auto a = hanging_job(dir.path() / "a");
  EXPECT_TRUE(restarted.stop_orphan(a, dir.path() / "elsewhere"));
  EXPECT_TRUE(group_members(std::stoi(a)).empty());
  previous.poll(a);  // reap our zombie
  // With no handle stored (a crash right after launch): by the job directory.
  auto b = hanging_job(dir.path() / "b");
  EXPECT_TRUE(restarted.stop_orphan(std::nullopt, dir.path() / "b"));
  EXPECT_TRUE(group_members(std::stoi(b)).empty());
  previous.poll(b);
  EXPECT_FALSE(restarted.stop_orphan(std::nullopt, dir.path() / "b")) << "nothing left to stop";

  // A group that reuses a recorded number but runs something else is left alone.
  LocalExecutor other(direct("/bin/sleep"));
  auto unrelated = other.launch({dir.path(), dir.path() / "log2", {"30"}});
  EXPECT_FALSE(restarted.stop_orphan(unrelated, dir.path() / "c"));
  EXPECT_FALSE(group_members(std::stoi(unrelated)).empty());
  other.cancel(unrelated);
}

TEST(LocalExecutorCommand, UsesMpirunWithOversubscribeAndRootFlagOnlyAsRoot) {
  LocalExecutorConfig c;
  c.engine = "/x/rockcal-dem";
  c.ranks = 3;
  LocalExecutor ex(c);
  auto argv = ex.command({"/d", "/d/log", {"run", "/d/job.json", "--out", "/d"}});
  std::vector<std::string> expected = {"mpirun"};
  if (geteuid() == 0) expected.push_back("--allow-run-as-root");
  for (const char* a :
       {"--oversubscribe", "-np", "3", "/x/rockcal-dem", "run", "/d/job.json", "--out", "/d"}) {
    expected.push_back(a);
  }
  EXPECT_EQ(argv, expected);
  c.ranks = 0;
  EXPECT_EQ(LocalExecutor(c).command({"/d", "/d/log", {"run"}}),
            (std::vector<std::string>{"/x/rockcal-dem", "run"}));
}

}  // namespace
}  // namespace rockcal::orch
