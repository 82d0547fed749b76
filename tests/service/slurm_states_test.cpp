// The Slurm executor's pure parts: Slurm states onto rockcal's, squeue/sacct/sbatch output, the
// outcome of what squeue and the completion marker say, and the batch script it submits.
#include <gtest/gtest.h>

#include "orchestrator/slurm/slurm_executor.hpp"
#include "orchestrator/slurm/states.hpp"

namespace rockcal::orch::slurm {
namespace {

TEST(SlurmStates, MapOntoRockcalStatesAsTheIssueSays) {
  EXPECT_EQ(phase_of("PENDING"), Phase::pending);
  EXPECT_EQ(phase_of("REQUEUED"), Phase::pending);
  EXPECT_EQ(phase_of("REQUEUE_HOLD"), Phase::pending);
  EXPECT_EQ(phase_of("RUNNING"), Phase::running);
  EXPECT_EQ(phase_of("COMPLETING"), Phase::running);
  EXPECT_EQ(phase_of("SUSPENDED"), Phase::running);
  EXPECT_EQ(phase_of("COMPLETED"), Phase::completed);
  for (auto s : {"FAILED", "TIMEOUT", "NODE_FAIL", "OUT_OF_MEMORY", "BOOT_FAIL", "DEADLINE"}) {
    EXPECT_EQ(phase_of(s), Phase::failed) << s;
  }
  EXPECT_EQ(phase_of("CANCELLED"), Phase::cancelled);
  EXPECT_EQ(phase_of("CANCELLED by 0"), Phase::cancelled);  // sacct's spelling
  EXPECT_EQ(phase_of("PREEMPTED"), Phase::requeue);
  EXPECT_EQ(phase_of("RUNNING+"), Phase::running);
  EXPECT_EQ(phase_of("SOME_NEW_STATE"), Phase::running) << "an unknown state must not end a job";
}

TEST(SlurmStates, ParsesSqueueSacctAndSbatchOutput) {
  auto q = parse_squeue("12|RUNNING|None\n13|PENDING|Resources\n14_1|RUNNING|None\n\nbad line\n");
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q["12"].state, "RUNNING");
  EXPECT_EQ(q["13"].reason, "Resources");
  auto a = parse_sacct("20|CANCELLED by 0|0:15\n20.batch|CANCELLED|0:15\n21|TIMEOUT|0:0\n");
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a["20"].state, "CANCELLED by 0");
  EXPECT_EQ(a["21"].state, "TIMEOUT");
  EXPECT_EQ(parse_sbatch_id("4242\n"), "4242");
  EXPECT_EQ(parse_sbatch_id("4242;cluster-a\n"), "4242");
  try {
    parse_sbatch_id("sbatch: error: Batch job submission failed\n");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(),
                 "sbatch printed no job id: 'sbatch: error: Batch job submission failed'");
  }
}

ExitStatus seen(std::optional<JobState> slurm, std::optional<int> marker) {
  return status_from("7", {std::move(slurm), marker});
}

TEST(SlurmStatus, TheMarkerAndSlurmTogetherDecideTheOutcome) {
  // The marker with 0 is enough, whatever squeue says or does not say yet.
  auto ok = seen(JobState{"RUNNING", "None"}, 0);
  EXPECT_TRUE(ok.finished);
  EXPECT_EQ(ok.ending, Ending::run);
  EXPECT_EQ(ok.exit_code, 0);

  auto pending = seen(JobState{"PENDING", "Priority"}, std::nullopt);
  EXPECT_FALSE(pending.finished);
  EXPECT_TRUE(pending.pending);

  // A non-zero marker while Slurm still runs the job: wait for Slurm's verdict.
  EXPECT_FALSE(seen(JobState{"COMPLETING", "None"}, 1).finished);
  // FAILED with a marker: the engine's own exit code (2 = invalid spec, not retried).
  auto invalid = seen(JobState{"FAILED", "NonZeroExitCode"}, 2);
  EXPECT_EQ(invalid.ending, Ending::run);
  EXPECT_EQ(invalid.exit_code, 2);

  auto timeout = seen(JobState{"TIMEOUT", "TimeLimit"}, std::nullopt);
  EXPECT_TRUE(timeout.finished);
  EXPECT_EQ(timeout.ending, Ending::failed);
  EXPECT_EQ(timeout.scheduler_state, "TIMEOUT");
  EXPECT_EQ(timeout.reason, "Slurm job 7 ended TIMEOUT (TimeLimit)");
  EXPECT_EQ(timeout.describe(), "Slurm job 7 ended TIMEOUT (TimeLimit)");
  // TIMEOUT stays TIMEOUT even when the script got to write a marker.
  EXPECT_EQ(seen(JobState{"TIMEOUT", "TimeLimit"}, 143).ending, Ending::failed);

  auto oom = seen(JobState{"OUT_OF_MEMORY", "OutOfMemory"}, std::nullopt);
  EXPECT_EQ(oom.reason, "Slurm job 7 ended OUT_OF_MEMORY (OutOfMemory)");
  auto node = seen(JobState{"NODE_FAIL", "None"}, std::nullopt);
  EXPECT_EQ(node.reason, "Slurm job 7 ended NODE_FAIL");

  auto cancelled = seen(JobState{"CANCELLED", "None"}, std::nullopt);
  EXPECT_EQ(cancelled.ending, Ending::cancelled);
  EXPECT_EQ(cancelled.reason, "Slurm job 7 was cancelled in Slurm (CANCELLED)");

  auto preempted = seen(JobState{"PREEMPTED", "None"}, std::nullopt);
  EXPECT_EQ(preempted.ending, Ending::requeue);
  EXPECT_EQ(preempted.reason, "Slurm job 7 was PREEMPTED; the job is queued again");

  // Gone from squeue and sacct (accounting off): the marker, else lost.
  auto gone_ok = seen(std::nullopt, 3);
  EXPECT_EQ(gone_ok.ending, Ending::run);
  EXPECT_EQ(gone_ok.exit_code, 3);
  auto lost = seen(std::nullopt, std::nullopt);
  EXPECT_EQ(lost.ending, Ending::failed);
  EXPECT_EQ(lost.scheduler_state, "LOST");
  EXPECT_EQ(lost.reason,
            "Slurm job 7 ended without writing its completion marker, and neither squeue nor "
            "sacct knows it any more");
}

TEST(SlurmBatchScript, RunsTheEngineUnderSrunThenWritesTheMarkerAtomically) {
  SlurmConfig c;
  c.engine = "/opt/rock cal/rockcal-dem";
  c.ranks = 4;
  c.partition = "compute";
  c.time_limit = "2:00:00";
  LaunchRequest r{"/shared/jobs/12",
                  "/shared/jobs/12/log",
                  {"run", "/shared/jobs/12/job.json", "--out", "/shared/jobs/12"}};
  std::string s = batch_script(c, r);
  EXPECT_EQ(s.rfind("#!/bin/bash\n", 0), 0u);
  EXPECT_NE(s.find("#   sbatch --parsable --job-name=rockcal-12 --comment=/shared/jobs/12 "
                   "--chdir=/shared/jobs/12 --output=/shared/jobs/12/log --open-mode=append "
                   "--ntasks=4 --partition=compute --time=2:00:00 /shared/jobs/12/job.sbatch\n"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("\nsrun --mpi='pmix' '/opt/rock cal/rockcal-dem' 'run' "
                   "'/shared/jobs/12/job.json' '--out' '/shared/jobs/12'\nstatus=$?\n"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("printf '%s\\n' \"$status\" > '/shared/jobs/12/exit-status.tmp' && mv -f "
                   "'/shared/jobs/12/exit-status.tmp' '/shared/jobs/12/exit-status'\n"
                   "exit \"$status\"\n"),
            std::string::npos)
      << s;
}

}  // namespace
}  // namespace rockcal::orch::slurm
