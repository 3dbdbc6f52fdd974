// Limits of a scene beyond the per-key ranges of scene.cc: physics the models do not describe,
// and runs too large for the machine. ParseScene applies them, so a scene outside is rejected up
// front with one line naming the key and the reason (docs/RELIABILITY.md, "Scene limits").
//
//  - contact stress: the Hertz line-contact pressure at the most loaded roller (Harris-Jones
//    load distribution, sim/quasistatic) must stay below 4 GPa, the stress ISO 76 takes for the
//    static load rating C0 of roller bearings: above it the races deform plastically and the
//    elastic models no longer apply (N205EM: about 32 kN of radial load applied slowly). A load
//    applied faster than the inner ring's radial period overshoots: the stress is taken at the
//    dynamic peak, DynamicLoadFactor() x the load (a step: twice the load, about 16 kN);
//  - duration: run.duration_s <= 60 s of simulated time;
//  - output rate: at most what the mesh resolves (wave speed / element size);
//  - results in memory: samples (duration x output rate) x recorded columns x 8 bytes must fit in
//    half of the machine's memory, and the estimated element count within max_elements.
#pragma once

#include <optional>
#include <string>

#include "sim/bearing/scene.h"
#include "sim/quasistatic/harris_jones.h"

namespace spallkit::sim {

struct SceneLimits {
  double max_contact_stress_pa = kStaticCapacityStressPa;  // ISO 76, roller bearings
  double max_duration_s = 60.0;
  double max_elements = 2.0e7;  // estimated from the meshed area and the element size
  // Bytes the results may take; 0: half of the physical memory.
  double max_result_bytes = 0.0;
};

struct SceneLimitViolation {
  std::string key;     // dotted scene key, e.g. "operation.radial_load_n"
  std::string reason;  // what is wrong and what is allowed, one line
};

// The first limit the scene breaks, or nullopt.
std::optional<SceneLimitViolation> FindSceneLimitViolation(const Scene& scene,
                                                           const SceneLimits& limits = {});

// Hertz peak pressure of the most loaded roller-inner race contact (Pa) for the scene's
// bearing, speed and clearance under the radial load `load_n` (default: the scene's); roller
// length = bearing.thickness_mm.
double PeakContactStress(const Scene& scene);
double PeakContactStress(const Scene& scene, double load_n);

// Radial period of the loaded inner ring, s: the ring (mass m, the rigid models' shaft) on the
// bearing's radial stiffness K at the scene's load (Harris-Jones), T = 2 pi sqrt(m / K); 0 when
// the load distribution has no solution.
double InnerRingRadialPeriod(const Scene& scene);

// Peak over static load of the scene's radial load applied over operation.load_ramp_s: on the
// oscillator of period T above, a load ramped linearly over t_r overshoots by the envelope of
// its response spectrum, 1 + T / (pi t_r), and a step (t_r = 0) by 2.
double DynamicLoadFactor(const Scene& scene);

// Rough element count of the scene's mesh (meshed area / element area).
double EstimatedElements(const Scene& scene);

// The highest output rate the mesh resolves, Hz: the slowest bar wave speed of the meshed
// parts over the largest element size (the explicit step is of that order or shorter).
double ResolvedRateHz(const Scene& scene);

// Bytes of the recorded results (all samples of every requested output).
double EstimatedResultBytes(const Scene& scene);

}  // namespace spallkit::sim
