#include "orchestrator/inference/emulator/two_level.hpp"

#include <stdexcept>

namespace rockcal::inference {

Gp fit_two_level(const Gp& coarse, GpData fine, const TwoLevelOptions& options) {
  if (fine.x.cols() != coarse.data.x.cols())
    throw std::invalid_argument("emulator: the fine and coarse data differ in dimension");
  if (fine.y.size() != fine.x.rows() || fine.noise_var.size() != fine.x.rows())
    throw std::invalid_argument("emulator: x, y and noise_var differ in length");
  Eigen::VectorXd base_mean, base_var;
  predict_many(coarse, fine.x, base_mean, base_var);
  fine.y -= base_mean;
  fine.noise_var += base_var;
  GpOptions o;
  o.min_length = options.min_length;
  o.max_length = options.max_length;
  o.linear_trend = false;
  o.replicate_spread = true;
  Gp gp = fit_gp(std::move(fine), o);
  gp.base = std::make_shared<const Gp>(coarse);
  return gp;
}

}  // namespace rockcal::inference
