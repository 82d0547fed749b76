#include "orchestrator/calibration/nlopt_bridge.hpp"

#include <exception>

namespace rockcal::calibration {
namespace {

struct Context {
  NloptObjective objective;
  std::exception_ptr error;
};

double call(const std::vector<double>& x, std::vector<double>& /*grad: derivative-free*/,
            void* data) {
  auto* context = static_cast<Context*>(data);
  try {
    return context->objective(x);
  } catch (...) {
    context->error = std::current_exception();
    throw nlopt::forced_stop();
  }
}

}  // namespace

void minimise(nlopt::opt& opt, std::vector<double>& x, NloptObjective objective) {
  Context context{std::move(objective), nullptr};
  opt.set_min_objective(call, &context);
  double f = 0.0;
  try {
    opt.optimize(x, f);
  } catch (const nlopt::forced_stop&) {
  } catch (const nlopt::roundoff_limited&) {
    // A converged noisy objective; x holds the best point, which is all the driver needs.
  }
  if (context.error) std::rethrow_exception(context.error);
}

}  // namespace rockcal::calibration
