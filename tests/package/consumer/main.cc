// Uses the installed headers and spallkit::sim: the Harris–Jones load distribution of an N205EM
// under 10 kN. Prints "spallkit <version>: Q_max <N> N".
#include <cstdio>

#include "core/bearing.h"
#include "sim/quasistatic/harris_jones.h"

int main() {
  spallkit::sim::LoadDistributionOptions options;
  options.radial_load_n = 10000.0;
  spallkit::sim::LoadDistributionSummary summary;
  spallkit::sim::SolveLoadDistribution(options, spallkit::CatalogBearing("N205EM"), &summary);
  if (!summary.IsSolutionUsable()) {
    std::fprintf(stderr, "%s\n", summary.BriefReport().c_str());
    return 1;
  }
  std::printf("spallkit %s: Q_max %.1f N\n", SPALLKIT_VERSION, summary.q_max_n);
  return 0;
}
