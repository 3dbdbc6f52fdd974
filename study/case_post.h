// Post-processing of a sweep case's file before it is committed ([post] in the sweep file):
// measurement noise on the acceleration channels and the envelope diagnosis's verdict.
#pragma once

#include <nlohmann/json.hpp>

#include "core/hdf5.h"
#include "study/sweep.h"

namespace spallkit::study {

// Adds white Gaussian noise to every /signals/* dataset at sweep.post.noise_snr_db (signal RMS,
// mean removed, over noise RMS), the same noise on datasets of one sensor direction (accel_y and
// its sensor's channel stay equal), seeded by (sweep seed, case index): reproducible. The
// datasets get a `noise_snr_db` attribute. With sweep.post.diagnose, runs dsp::Diagnose on
// /signals/accel_y (one thread, the scene's bearing and speed) and adds the labels `verdict`
// ("not_diagnosed" when the record is too short or the diagnosis refuses it) and
// `diagnosed_f_b_hz` (NaN when not measured) and `diagnose_note` (why a record was not diagnosed,
// e.g. too short for the cage rate; empty otherwise). Labels are appended to *labels.
void PostProcessCase(const Sweep& sweep,
                     const SweepCase& c,
                     const sim::Scene& scene,
                     h5::File* file,
                     nlohmann::ordered_json* labels);

}  // namespace spallkit::study
