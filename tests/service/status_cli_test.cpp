// `rockcal status` as a user runs it, against a live server (fake engine): piped output (a CI log,
// the logged quick start) ends with the readable summary, not JSON; `--json` prints the campaign
// object alone on stdout, also with `--wait`.
#include <gtest/gtest.h>

#include "api_server_fixture.hpp"
#include "orchestrator/command.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

struct StatusCli : ApiServerFixture {
  std::int64_t submit_sweep() {
    auto c = client();
    auto r = c.Post("/api/v1/campaigns", sweep_request({"uct", "btt"}, {31, 37}, {1}).dump(),
                    "application/json");
    EXPECT_TRUE(r && r->status == 201);
    return r ? json::parse(r->body)["id"].get<std::int64_t>() : 0;
  }
  orch::CommandResult status(std::int64_t id, std::vector<std::string> flags) {
    std::vector<std::string> argv = {rockcal_binary(), "status", std::to_string(id), "--server",
                                     "http://127.0.0.1:" + std::to_string(port)};
    argv.insert(argv.end(), flags.begin(), flags.end());
    return orch::run_command(argv, 60s);
  }
};

TEST_F(StatusCli, WaitEndsWithTheSummaryNotJson) {
  start();
  const std::int64_t id = submit_sweep();
  const auto r = status(id, {"--wait"});
  ASSERT_EQ(r.exit_code, 0) << r.err << r.error;
  const std::string id_text = std::to_string(id);
  const std::string end = "\nsweep " + id_text +
                          " succeeded: 4 jobs, 4 succeeded, 0 failed\n"
                          "results: rockcal results " +
                          id_text + " (--csv for one row per job)\n";
  ASSERT_GE(r.out.size(), end.size()) << r.out;
  EXPECT_EQ(r.out.substr(r.out.size() - end.size()), end) << r.out;
  EXPECT_EQ(r.out.find('{'), std::string::npos) << "no JSON by default:\n" << r.out;
  EXPECT_EQ(r.out.find('\r'), std::string::npos) << "no redraws in a log:\n" << r.out;
}

TEST_F(StatusCli, JsonPrintsTheCampaignObject) {
  start();
  const std::int64_t id = submit_sweep();
  const auto waited = status(id, {"--wait", "--json"});
  ASSERT_EQ(waited.exit_code, 0) << waited.err << waited.error;
  const json done = json::parse(waited.out);  // stdout is the JSON alone
  EXPECT_EQ(done["id"], id);
  EXPECT_EQ(done["state"], "succeeded");
  EXPECT_EQ(done["progress"]["succeeded"], 4);
  const auto now = status(id, {"--json"});
  ASSERT_EQ(now.exit_code, 0) << now.err << now.error;
  EXPECT_EQ(json::parse(now.out), done);
}

// Without --server the client reads $ROCKCAL_SERVER; a server it cannot reach is named with the
// way to give another.
TEST_F(StatusCli, TheServerComesFromRockcalServerWithoutTheFlag) {
  start();
  const std::int64_t id = submit_sweep();
  setenv("ROCKCAL_SERVER", ("http://127.0.0.1:" + std::to_string(port)).c_str(), 1);
  const auto r = orch::run_command({rockcal_binary(), "status", std::to_string(id), "--json"}, 60s);
  unsetenv("ROCKCAL_SERVER");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.error;
  EXPECT_EQ(json::parse(r.out)["id"], id);
}

TEST_F(StatusCli, AServerItCannotReachIsNamed) {
  const auto r =
      orch::run_command({rockcal_binary(), "list", "--server", "http://127.0.0.1:1"}, 60s);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "rockcal: cannot reach the server at http://127.0.0.1:1 (Connection error; give "
            "its URL with --server or $ROCKCAL_SERVER)\n");
}

}  // namespace
}  // namespace rockcal::test
