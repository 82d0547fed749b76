// The example configuration (deploy/rockcal.conf) and the serve flags are one list of options:
// the file as shipped starts a server with its values, a flag on the command line wins over it,
// and a key that is not a flag is refused.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "orchestrator/command.hpp"
#include "support.hpp"

namespace rockcal::test {
namespace {

// The shipped file with its paths moved into `dir`.
std::filesystem::path local_copy(const std::filesystem::path& dir) {
  std::ifstream in(DEPLOY_DIR "/rockcal.conf");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  EXPECT_NE(text.find("\ndata-dir = \"/var/lib/rockcal/rockcal.db.d\"\n"), std::string::npos);
  std::string moved = "\"";
  moved += dir.string();
  moved += "/";
  text = std::regex_replace(text, std::regex("\"/var/lib/rockcal/"), moved);
  auto path = dir / "rockcal.conf";
  std::ofstream(path) << text;
  return path;
}

TEST(ConfigFile, TheShippedExampleStartsAServerWithItsValues) {
  TempDir dir;
  ServerProcess server(dir.path(), {"--config", local_copy(dir.path()).string()});
  server.start();
  auto c = server.client();
  EXPECT_EQ(get_json(c, "/healthz")["workers"], 2);  // workers = 2 in the file
  std::ifstream out(dir.path() / "serve.out");
  std::string line;
  std::getline(out, line);
  EXPECT_NE(line.find("(local executor, 2 workers, 1 ranks per job"), std::string::npos) << line;
  EXPECT_NE(line.find("data " + (dir.path() / "rockcal.db.d").string()), std::string::npos) << line;
  EXPECT_EQ(server.terminate(), 0);
}

TEST(ConfigFile, AFlagOnTheCommandLineWinsOverTheFile) {
  TempDir dir;
  ServerProcess server(dir.path(), {"--config", local_copy(dir.path()).string(), "--workers", "3"});
  server.start();
  auto c = server.client();
  EXPECT_EQ(get_json(c, "/healthz")["workers"], 3);
  EXPECT_EQ(server.terminate(), 0);
}

TEST(ConfigFile, AKeyThatIsNoFlagIsRefused) {
  TempDir dir;
  auto path = dir.path() / "bad.conf";
  std::ofstream(path) << "[serve]\nworker = 2\n";
  auto r = orch::run_command({rockcal_binary(), "serve", "--config", path.string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("serve.worker"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rockcal::test
