// spall bench <what>: the benchmark group. Each benchmark is its own file,
// apps/cmd_bench_<what>.cc, registered as "bench <what>".
#include "apps/command.h"

namespace {

spallkit::apps::RegisterGroup group("bench",
                                    "Benchmarks: run time and accuracy on standard problems");

}  // namespace
