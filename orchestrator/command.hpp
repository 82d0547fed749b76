// Runs a short external command (sbatch, squeue, ...) and captures what it printed.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace rockcal::orch {

struct CommandResult {
  int exit_code = -1;  // -1 when it could not be started or was killed (see error)
  std::string out;
  std::string err;
  std::string error;  // why it did not run to an exit code, else ""
  bool ok() const { return exit_code == 0; }
};

// argv[0] is looked up in PATH. Killed (SIGKILL) after `timeout`; stdin is /dev/null and no other
// descriptor of the server leaks into it.
CommandResult run_command(const std::vector<std::string>& argv,
                          std::chrono::milliseconds timeout = std::chrono::seconds(60));

// "a 'b c'": argv as a shell would need it, for error messages and logs.
std::string command_text(const std::vector<std::string>& argv);

// Quotes `s` for a POSIX shell script (single quotes).
std::string shell_quote(const std::string& s);

}  // namespace rockcal::orch
