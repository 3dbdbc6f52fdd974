// The weighted misfit both identification fits minimise and compare.
#pragma once

#include <cstddef>
#include <span>

namespace spallkit::identify {

// sum_i ((mean_i - model_i) / sigma_i)^2 over the model's points (mean and sigma at least as
// long): the chi-square of a model against averaged data with standard errors.
inline double ChiSquare(std::span<const double> mean,
                        std::span<const double> sigma,
                        std::span<const double> model) {
  double c = 0.0;
  for (std::size_t i = 0; i < model.size(); ++i) {
    const double r = (mean[i] - model[i]) / sigma[i];
    c += r * r;
  }
  return c;
}

}  // namespace spallkit::identify
