// The Harris–Jones quasi-static load distribution of a cylindrical roller bearing: what
// `spall loads` prints, from the library. Options are validated by the solver (InputError).
//
//   example_harris_jones [radial_load_N]
#include "sim/quasistatic/harris_jones.h"

#include <cstdio>
#include <cstdlib>

#include "core/bearing.h"
#include "core/constants.h"

int main(int argc, char** argv) {
  spallkit::sim::LoadDistributionOptions options;
  options.radial_load_n = argc > 1 ? std::atof(argv[1]) : 10000.0;
  options.diametral_clearance_m = 20e-6;

  spallkit::sim::LoadDistributionSummary summary;
  spallkit::sim::SolveLoadDistribution(options, spallkit::CatalogBearing("N205EM"), &summary);
  std::printf("%s\n", summary.BriefReport().c_str());
  if (!summary.IsSolutionUsable()) return 1;

  for (const spallkit::sim::RollerLoad& roller : summary.rollers)
    std::printf("psi %7.2f deg  Q_o %8.1f N\n",
                roller.angle_rad * 180.0 / spallkit::kPi,
                roller.outer_load_n);
  return 0;
}
