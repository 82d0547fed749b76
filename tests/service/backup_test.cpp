// `rockcal backup` / `restore`: a copy taken while a writer commits results is sound
// (integrity_check ok) and holds every result committed before it started; a restore puts it back;
// the backup never overwrites the database itself, and a restore refuses under a running server.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <mutex>
#include <set>
#include <thread>

#include "api/cli/backup_cli.hpp"
#include "db/backup.hpp"
#include "db/store.hpp"
#include "support.hpp"

namespace rockcal::db {
namespace {

std::string hash_of(int i) {
  std::string h = "h";
  h += std::to_string(i);
  return h;
}

// One campaign with one job, run and finished with a result: what a server commits per job.
std::string commit_result(Store& store, int i) {
  std::string hash = hash_of(i);
  store.create_campaign("sweep", "c", "{}", false, {{"uct", 1.0 * i, 2, "{}", hash}});
  auto job = store.claim_job("local");
  if (!job) throw std::runtime_error("nothing to claim");
  ResultRow r;
  r.hash = job->hash;
  r.job_id = job->id;
  r.test = "uct";
  r.fr0 = job->fr0;
  r.fs0 = 2;
  r.peak_load = i;
  r.engine_version = "v";
  r.result = std::string(4000, 'r');  // result.json-sized rows, so the copy takes a while
  r.curve = std::string(4000, 'c');
  if (!store.finish_success(job->id, r)) throw std::runtime_error("not running");
  return hash;
}

std::set<std::string> result_hashes(const std::string& path) {
  Connection conn(path);
  auto st = conn.prepare(
      "SELECT r.hash FROM results r JOIN jobs j ON j.id = r.job_id WHERE j.state = 'succeeded'");
  std::set<std::string> out;
  while (st.step()) out.insert(st.text(0));
  return out;
}

TEST(Backup, UnderWriteLoadHoldsEveryCommittedResultAndRestores) {
  test::TempDir dir;
  const std::string live = (dir.path() / "live.db").string();
  Store store(live);
  for (int i = 0; i < 1500; ++i) commit_result(store, i);  // about 12 MB

  std::mutex mutex;
  std::vector<std::string> committed;
  std::atomic<bool> stop{false};
  std::atomic<int> next{1500};
  std::thread writer([&] {
    while (!stop) {
      auto hash = commit_result(store, next++);
      std::lock_guard lock(mutex);
      committed.push_back(hash);
    }
  });
  auto committed_now = [&] {
    std::lock_guard lock(mutex);
    return committed;
  };
  ASSERT_TRUE(
      test::poll_until([&] { return committed_now().size() >= 20; }, std::chrono::seconds(30)));

  int written_during_backups = 0;
  std::string last_copy;
  for (int k = 0; k < 3; ++k) {
    auto before = committed_now();
    last_copy = (dir.path() / ("copy" + std::to_string(k) + ".db")).string();
    auto report = backup_database(live, last_copy);
    auto after = committed_now();
    written_during_backups += static_cast<int>(after.size() - before.size());
    EXPECT_EQ(report.integrity, "ok");
    EXPECT_GT(report.pages, 2900);
    auto in_copy = result_hashes(last_copy);
    for (int i = 0; i < 1500; ++i) ASSERT_TRUE(in_copy.count(hash_of(i))) << i;
    for (const auto& h : before)
      ASSERT_TRUE(in_copy.count(h)) << h << " committed before the backup";
    EXPECT_LE(in_copy.size(), 1500 + after.size());
    EXPECT_FALSE(std::filesystem::exists(last_copy + "-wal")) << "a backup is one file";
  }
  stop = true;
  writer.join();
  EXPECT_GT(written_during_backups, 0) << "the writer never committed during a backup";

  const std::string restored = (dir.path() / "restored.db").string();
  auto report = restore_database(last_copy, restored);
  EXPECT_EQ(report.integrity, "ok");
  EXPECT_EQ(result_hashes(restored), result_hashes(last_copy));
  // The server opens it as usual (migrations already applied). A copy may hold the writer's last
  // campaign before its job finished (three transactions per result), so count what was copied.
  std::int64_t copied_campaigns = 0;
  {
    Connection conn(last_copy);
    auto st = conn.prepare("SELECT count(*) FROM campaigns");
    if (st.step()) copied_campaigns = st.int64(0);
  }
  Store reopened(restored);
  EXPECT_EQ(reopened.campaign_count(), copied_campaigns);
  EXPECT_GE(copied_campaigns, static_cast<std::int64_t>(result_hashes(restored).size()));
}

TEST(Backup, RefusesToOverwriteTheDatabaseItself) {
  test::TempDir dir;
  const std::string live = (dir.path() / "live.db").string();
  Store store(live);
  try {
    backup_database(live, live);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "the backup must not overwrite the database itself");
  }
  try {
    backup_database((dir.path() / "none.db").string(), (dir.path() / "b.db").string());
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "no database " + (dir.path() / "none.db").string());
  }
}

TEST(Backup, RestoreRefusesWhileAServerHoldsTheLock) {
  test::TempDir dir;
  const std::string live = (dir.path() / "live.db").string();
  { Store store(live); }
  backup_database(live, (dir.path() / "b.db").string());
  std::filesystem::create_directories(live + ".d");
  int fd = open((live + ".d/server.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  ASSERT_EQ(flock(fd, LOCK_EX | LOCK_NB), 0);
  try {
    api::run_restore((dir.path() / "b.db").string(), live, "");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "a rockcal server is running on " + live + " (" + live +
                                         ".d/server.lock is locked); stop it before restoring");
  }
  close(fd);
  EXPECT_EQ(api::run_restore((dir.path() / "b.db").string(), live, ""), 0);
}

}  // namespace
}  // namespace rockcal::db
