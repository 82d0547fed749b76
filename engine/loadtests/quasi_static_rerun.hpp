// A run that came too fast runs again, slower (loading.quasi_static_rerun, "auto" speed only).
//
// Why: the auto speed closes the bonds' failure strain in auto_transits wave transits, but how many
// failure strains a specimen takes to its peak depends on the strengths. Where F_s0 is well below
// F_r0 it fails after a few bond failures, so its peak comes in fewer transits than the
// quasi-static measure asks (loading_speed.hpp). Loading every run slower costs every run; running
// again the few that came too fast costs those.
#pragma once

#include "engine/loadtests/driver.hpp"
#include "engine/loadtests/result.hpp"

namespace rockcal {

// The rerun's auto_transits: the first's times the factor that would bring its peak to this
// multiple of the quasi-static threshold, were the peak to come at the same strain.
inline constexpr double kRerunMargin = 1.25;
// At most this factor slower: a peak a handful of transits in is not the loading rate's to fix.
inline constexpr double kMaxRerunFactor = 8.0;

// The UCT, BTT or triaxial as run_compression_test; with loading.quasi_static_rerun, a peak that
// was not quasi-static is followed by one run at auto_transits x min(kMaxRerunFactor,
// kRerunMargin x threshold / peak transits), whose result is returned with the first's peak and
// transits in loading_rate.rerun and both runs' wall time. The first is returned, not
// quasi-static, as it is when the slower run would exceed the step limit or ended without a peak.
// `run` is the test itself (run_compression_test; a test injects the runs' outcomes there).
using CompressionRun = TestResult (*)(const JobSpec&, const RunHooks&);
TestResult run_with_quasi_static_rerun(const JobSpec& spec, const RunHooks& hooks,
                                       CompressionRun run = run_compression_test);

}  // namespace rockcal
