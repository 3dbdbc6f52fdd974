// The record, bearing and speed options shared by `spall diagnose` and `spall identify`: the
// record file and its channel / sample rate, the start it leaves out, the bearing
// (apps/bearing_options.h) and --rpm.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

#include "apps/bearing_options.h"
#include "apps/cli_guard.h"
#include "core/error.h"
#include "core/record_io.h"

namespace spallkit::apps {

struct RecordInputOptions {
  std::string record;
  BearingOptions bearing;
  double rpm = 0.0;
  double fs = 0.0;
  CLI::Option* fs_option = nullptr;
  std::string channel;
  double from_s = 0.0;

  void Add(CLI::App& sub) {
    sub.add_option("record", record, "record file (.csv/.txt or .h5)")->required();
    bearing.Add(sub);
    sub.add_option("--rpm", rpm, "nominal shaft speed, rpm")->required();
    fs_option = sub.add_option("--fs", fs, "sample rate, Hz (overrides the file)");
    sub.add_option("--channel",
                   channel,
                   "column name (its unit may be left off: accel_z for 'accel_z (m/s^2)') / "
                   "0-based data column, or HDF5 path");
    sub.add_option("--from-s",
                   from_s,
                   "leave out the record's first seconds (a simulation's start-up: spall "
                   "simulate's ramps and settling), s")
        ->capture_default_str();
  }

  // Throws InputError for a speed or sample rate that is not a positive finite number.
  void Check() const {
    if (!(rpm > 0.0) || !std::isfinite(rpm))
      throw InputError("--rpm must be > 0 (got " + Number(rpm) + ")");
    if (fs_option && fs_option->count() > 0 && (!(fs > 0.0) || !std::isfinite(fs)))
      throw InputError("--fs must be > 0 Hz (got " + std::to_string(fs) + ")");
    if (!(from_s >= 0.0) || !std::isfinite(from_s))
      throw InputError("--from-s must be >= 0 s (got " + Number(from_s) + ")");
  }

  double ShaftHz() const { return rpm / 60.0; }

  // The record, read with the given channel and sample rate (core/record_io.h).
  Record Read() const {
    RecordOptions ro;
    ro.sample_rate_hz = fs;
    ro.channel = channel;
    Record r = ReadRecord(record, ro);
    if (!DropStart(&r, from_s))
      throw InputError(record + ": --from-s " + Number(from_s) +
                       " s leaves no samples (the record is " + Number(r.duration_s()) + " s)");
    return r;
  }
};

}  // namespace spallkit::apps
