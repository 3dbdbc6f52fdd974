// Output recording of a bearing run: what `spall simulate` writes to HDF5 (layout in
// docs/BEARING_MODEL.md, "Output file").
//
// The recorder is called after EVERY solver step (solver output_every_steps = 1) and at t = 0:
//  - acceleration: each sensor channel's velocity is interpolated linearly between the solver's
//    half-step velocities onto a uniform fine grid (fine_factor x output rate, at the half points
//    (i + 1/2) h), differenced (the exact mean acceleration over [(i-1/2) h, (i+1/2) h], centred on
//    i h), low-pass filtered and decimated to the output rate (spallkit::StreamingDecimator), so
//    sample k is centred on t_k = k / output_rate like every other channel;
//  - everything else is sampled at the first step with t >= t_k (at most one solver step, tens
//    of ns, late): contact forces per roller, cage and roller rigid motion, energies. Outputs not
//    listed in the scene's [run] outputs are neither computed nor written;
//  - the stress field ("field"): the von Mises stress of every element of the stepped mesh at
//    the first step with t >= k / field_rate_hz, in /field/von_mises (snapshots x elements, Pa)
//    with /field/time; the mesh it lives on is written once: /field/nodes (x, y at rest, m),
//    /field/elements (four node indices per element, counter-clockwise) and /field/part (part
//    index per element; names in the attribute part_names, comma-separated).
// The series are kept in memory (a few MB for 0.2 s at 20 kHz) and written at the end; the whole
// recorder state round-trips through SaveState/LoadState for checkpoints.
#pragma once

#include <string>
#include <vector>

#include "core/decimator.h"
#include "sim/bearing/bearing_model.h"

namespace spallkit::h5 {
class File;
}

namespace spallkit::sim {

struct RecorderOptions {
  double output_rate_hz = 20000.0;
  double field_rate_hz = 1000.0;  // "field" snapshots; at most output_rate_hz
  double duration_s = 0.2;
  int fine_factor = 8;  // fine grid rate / output rate for the acceleration
  std::vector<Output> outputs = {Output::kContactForces,
                                 Output::kAcceleration,
                                 Output::kCage,
                                 Output::kRollers,
                                 Output::kEnergy};
};

class Recorder {
 public:
  // A series: dataset path, columns (1 or rollers), units, data (row-major samples x cols).
  struct Series {
    std::string path;
    int cols = 1;
    std::string units;
    bool is_signal = false;  // gets sample_rate_hz too
    std::vector<double> data;
  };

  Recorder(const BearingModel& model, const RecorderOptions& options);

  // Call at t = 0 and after every step of the model (BearingModel::SetObserver).
  void Observe();
  // Completes the acceleration channels (the FIR look-ahead at the end holds the last value).
  void Finish();
  // Writes every series and its attributes (not the root attributes).
  void Write(h5::File* file) const;

  int num_samples() const { return num_samples_; }       // planned
  int recorded_samples() const { return next_sample_; }  // so far
  const std::vector<Series>& series() const { return series_; }
  // nullptr when that output is not recorded.
  const Series* Find(const std::string& path) const;
  // Acceleration channels by (sensor, direction) in model.sensor_channels() order.
  const std::vector<double>& Acceleration(int channel) const { return accel_out_[channel]; }
  bool records_acceleration() const { return accel_; }
  double output_rate_hz() const { return options_.output_rate_hz; }

  std::string SaveState() const;
  void LoadState(const std::string& bytes);

 private:
  void Sample();
  void SampleField();
  void PushFine(int channel, double accel);
  bool Wants(Output output) const;

  const BearingModel& model_;
  RecorderOptions options_;
  int num_samples_ = 0, next_sample_ = 0;
  int num_field_samples_ = 0, next_field_sample_ = 0;
  int idx_field_time_ = -1, idx_field_ = -1;
  std::vector<Series> series_;
  int idx_time_ = -1, idx_outer_ = -1, idx_inner_ = -1, idx_cage_force_ = -1, idx_omega_ = -1,
      idx_slip_ = -1, idx_cage_centre_ = -1, idx_spin_ = -1, idx_orbit_ = -1, idx_energy_ = -1;
  // Acceleration.
  bool accel_ = false;
  double fine_h_ = 0.0;
  long long fine_index_ = 0;  // next half point (i + 1/2) h to produce
  long long fine_needed_ = 0;
  double prev_t_ = 0.0;
  std::vector<double> prev_v_, last_fine_v_, last_fine_a_;
  std::vector<spallkit::StreamingDecimator> decimators_;
  std::vector<std::vector<double>> accel_out_;
  std::vector<double> last_orbit_;
};

}  // namespace spallkit::sim
