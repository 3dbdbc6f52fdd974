// Reading and writing single-channel vibration records (core/record.h) as CSV/text or HDF5.
//
// A Record is the input of every diagnosis stage: uniformly sampled samples of one channel, its
// sample rate, and where it came from. Readers validate everything a later stage would silently
// get wrong (non-uniform time, NaN, a missing cell) and throw spallkit::InputError with ONE line
// that names the file, the line (and field) and what was expected, e.g.
//   "run.csv:17: field 2 ('accel_g'): expected a number, found 'abc'"
// Line numbers count every line of the file from 1 (comments and blank lines included); "field k"
// counts the cells of a line from 1, as text editors and spreadsheets do. (The channel INDEX
// below is different: 0-based over signal columns.)
//
// ---------------------------------------------------------------------------------------------
// CSV / text rules (ReadCsvRecord)
// ---------------------------------------------------------------------------------------------
//  * Lines starting with '#' (after optional blanks) are comments; blank lines are skipped.
//    A comment "# fs=48000" (also "# fs: 48000 Hz", "# sample_rate_hz = 48000") states the
//    sample rate.
//  * Separator: detected on the first non-comment line: tab if it has a tab, else ';' if it has a
//    semicolon, else ',' if it has a comma, else runs of blanks. Cells are trimmed; surrounding
//    double quotes are removed; a separator at the end of a line is ignored. Decimal commas
//    are not supported.
//  * Header: the first non-comment line is a header when any of its cells is not a number.
//    Every data cell must be a finite number (no NaN/Inf, no empty cell), and every row must have
//    as many cells as the header (or as the first data row).
//  * Time column, with a header: a column whose name (lower-cased, unit in "(...)" or "[...]"
//    split off) is one of t, time, times, timestamp, sec, secs, seconds, optionally followed by
//    _s, _sec, _ms or _us ("time_s", "Time (s)", "t [ms]", "time_ms"). Units ms and us are
//    scaled to seconds. Without a header: column 0 is taken as time when the file has at least
//    2 columns and 3 rows and column 0 is strictly increasing and uniform (rule below). A ramp
//    signal in column 0 would therefore be taken as time; give a header to avoid that.
//  * Uniform time: the step is dt = (t_last - t_first)/(n - 1); time must strictly increase and
//    every time must lie within
//        tol_i = 1e-4 * dt + q_i + max(q_first, q_last)
//    of t_first + i*dt. q_i is the writer's rounding of t_i, estimated from the printed digits
//    (half a unit of the finest last digit seen in the column, or of the most significant digits
//    seen, whichever is larger at t_i) and capped at 0.05*dt. So "%.9f" times at 48 kHz (rounding
//    2.4e-5 step) and "%g" times pass, real jitter above 1e-4 step in exactly printed times is
//    reported, and a gap of a whole step is always caught. A time that does not increase is
//    reported as "does not increase" at its line; one off the grid as "non-uniform time".
//  * Sample rate, first match wins: RecordOptions::sample_rate_hz (> 0; the time column is then
//    not checked), the "# fs=" comment (checked against the time column if both exist: they must
//    agree within 1e-4), 1/dt from the time column. None of them: InputError asking for fs.
//  * Channel (RecordOptions::channel): empty = the first non-time column; a header name
//    (exact, else case-insensitive); or a non-negative integer = a 0-BASED INDEX COUNTING DATA
//    COLUMNS ONLY (the time column is not counted), so "0" is the first signal column whether or
//    not the file has a time column.
//  * Record::units: from the channel header, "(...)" or "[...]" ("Accel (g)" -> "g"), else a
//    known suffix (_g -> g, _m_s2 -> m/s^2, _mm_s -> mm/s, _m_s -> m/s, _v -> V), else "".
//  * Speed: the file is read at once and parsed with std::from_chars (a 5 MB CWRU csv in a few
//    tens of milliseconds).
//
// ---------------------------------------------------------------------------------------------
// HDF5 rules (ReadHdf5Record)
// ---------------------------------------------------------------------------------------------
//  * channel = dataset path ("/signals/accel_z"; a missing leading '/' is added). Default:
//    /signals/accel_y if present, else the only 1-D dataset that has a sample_rate_hz attribute.
//  * The dataset must be 1-D and numeric (read as double), finite, with >= 2 samples.
//  * Sample rate: RecordOptions::sample_rate_hz if > 0, else the dataset's sample_rate_hz
//    attribute (> 0). Units: the dataset's `units` string attribute.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/record.h"

namespace spallkit {

// The highest sample rate a record may state (1 GHz: above any vibration measurement; record
// lengths in samples and seconds stay representable).
inline constexpr double kMaxSampleRateHz = 1e9;

struct RecordOptions {
  // > 0: use this sample rate and ignore the time column / attributes. 0: infer (see above).
  // < 0, NaN or above kMaxSampleRateHz: InputError.
  double sample_rate_hz = 0;
  // CSV: a column name or a 0-based index counting data columns; HDF5: a dataset path.
  // Empty: the default channel (first non-time column; /signals/accel_y).
  std::string channel;
};

// Dispatches by extension (case-insensitive): .h5 .hdf5 .he5 -> HDF5; .csv .txt .tsv .dat (or
// anything else) -> CSV/text.
Record ReadRecord(const std::string& path, const RecordOptions& options = {});
Record ReadCsvRecord(const std::string& path, const RecordOptions& options = {});
Record ReadHdf5Record(const std::string& path, const RecordOptions& options = {});

// Parses CSV text already in memory; `name` stands in for the file name in messages. Same rules
// as ReadCsvRecord (which reads the file and calls this).
Record ParseCsvRecord(std::string_view text,
                      const std::string& name,
                      const RecordOptions& options = {});

// Writes columns as a comma-separated file with a header line (the names), atomically. Values
// are written in the shortest form that reads back bit-exactly. All columns must have the same
// length; names must be non-empty and contain no comma, quote or newline. Throws InputError.
void WriteCsvRecord(const std::string& path,
                    const std::vector<std::pair<std::string, std::vector<double>>>& columns);

}  // namespace spallkit
