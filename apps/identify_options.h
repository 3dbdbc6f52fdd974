// When `spall identify` and `spall identify-check` state a count and a width
// (IdentifyOptions::min_count_probability, width_max_count) and how sure the count is
// (CountFitOptions::temperature_cage / _sidebands; docs/IDENTIFY.md): the defaults are the
// calibrated ones, the options let a user be stricter or reproduce the documented experiments.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "apps/cli_guard.h"
#include "core/error.h"
#include "identify/identify.h"

namespace spallkit::apps {

struct IdentifyStatementOptions {
  double min_count_probability = identify::IdentifyOptions().min_count_probability;
  int width_max_count = identify::IdentifyOptions().width_max_count;
  CLI::Option* probability_option = nullptr;
  CLI::Option* width_count_option = nullptr;
  std::vector<double> temperatures;
  CLI::Option* temperatures_option = nullptr;
  bool pattern_per_parity = false;
  bool second_pattern = false;
  int sideband_spin_step = identify::IdentifyOptions().sideband_spin_step;
  CLI::Option* spin_step_option = nullptr;
  bool width_needs_count = false;
  bool width_shared_ring_down = false;
  double width_load_fraction = identify::IdentifyOptions().width_contact_load_fraction;
  CLI::Option* load_fraction_option = nullptr;
  double max_pair_power_ratio = identify::IdentifyOptions().max_pair_power_ratio;
  CLI::Option* pair_ratio_option = nullptr;
  bool count_without_cage_hump = false;
  bool count_with_extreme_hump = false;
  bool combine_per_count = false;

  void Add(CLI::App& sub) {
    probability_option =
        sub.add_option("--min-count-probability",
                       min_count_probability,
                       "state the count only when its probability reaches this (default " +
                           Number(min_count_probability) + ")");
    width_count_option =
        sub.add_option("--width-max-count",
                       width_max_count,
                       "state the width only for at most this many defective rollers (default " +
                           std::to_string(width_max_count) + ")");
    const identify::CountFitOptions count;
    temperatures_option =
        sub.add_option("--temperatures",
                       temperatures,
                       "the count's evidence temperatures T_A,T_B (cage average, sidebands; "
                       "default " +
                           Number(count.temperature_cage) + "," +
                           Number(count.temperature_sidebands) + ")")
            ->expected(2)
            ->delimiter(',');
    CLI::Option* per_parity_flag = sub.add_flag(
        "--sideband-pattern-per-parity",
        pattern_per_parity,
        "the count's sideband feature with one cage-angle pattern for the odd and one for "
        "the even spin harmonics (measured, not the default: docs/IDENTIFY.md)");
    sub.add_flag("--sideband-second-pattern",
                 second_pattern,
                 "the count's sideband feature with a second, fitted cage-angle pattern per roller "
                 "(measured, not the default: docs/IDENTIFY.md)")
        ->excludes(per_parity_flag);
    spin_step_option = sub.add_option(
        "--sideband-spin-step",
        sideband_spin_step,
        "the count's sideband feature on the harmonics of this many times the spin rate: 2 "
        "(default), those of f_b; 1, every spin harmonic (docs/IDENTIFY.md)");
    sub.add_flag("--width-needs-count",
                 width_needs_count,
                 "state the width only with a stated count (by default also when every likely "
                 "count's configuration gives the same entry-exit pair: docs/IDENTIFY.md)");
    pair_ratio_option = sub.add_option(
        "--max-pair-power-ratio",
        max_pair_power_ratio,
        "state no width whose second event correlates above this fraction of the zero-lag power "
        "(default: no such bound; 1 reproduces the measured alternative, docs/IDENTIFY.md)");
    load_fraction_option = sub.add_option(
        "--width-load-fraction",
        width_load_fraction,
        "the width relation's passage load as a fraction of the load-line roller load (default " +
            Number(width_load_fraction) + ", the calibration: docs/IDENTIFY.md)");
    sub.add_flag("--width-shared-ring-down",
                 width_shared_ring_down,
                 "the width fit's pair peak with the zero-lag peak's ring-down instead of its own "
                 "(measured, not the default: docs/IDENTIFY.md)");
    sub.add_flag("--combine-per-count",
                 combine_per_count,
                 "combine the count's two features per K, as the temperatures were chosen "
                 "(measured, not the default: docs/IDENTIFY.md)");
    sub.add_flag("--count-without-cage-hump",
                 count_without_cage_hump,
                 "state a count also where the cage average by itself ranks no defective roller "
                 "first (by default the sideband pattern alone states no count: docs/IDENTIFY.md)");
    sub.add_flag("--count-with-extreme-hump",
                 count_with_extreme_hump,
                 "state a count also where its load-zone hump is as flat or as narrow as the fit "
                 "allows (by default refused: merged or split humps, docs/IDENTIFY.md)");
  }

  // Throws InputError naming the option when a given value is out of range. The ranges are the
  // library's (IdentifyOptions::IsValid), checked on the defaults with only this option changed,
  // so that another option's bad value is not blamed on this one.
  void Apply(identify::IdentifyOptions* o) const {
    auto apply = [&](const std::string& flag,
                     const std::string& got,
                     const std::function<void(identify::IdentifyOptions*)>& set) {
      identify::IdentifyOptions probe;
      set(&probe);
      std::string error;
      if (!probe.IsValid(&error)) throw InputError(flag + ": " + error + " (got " + got + ")");
      set(o);
    };
    if (probability_option && probability_option->count() > 0)
      apply("--min-count-probability", Number(min_count_probability), [&](auto* t) {
        t->min_count_probability = min_count_probability;
      });
    if (width_count_option && width_count_option->count() > 0)
      apply("--width-max-count", std::to_string(width_max_count), [&](auto* t) {
        t->width_max_count = width_max_count;
      });
    if (temperatures_option && temperatures_option->count() > 0)
      apply("--temperatures",
            Number(temperatures.at(0)) + "," + Number(temperatures.at(1)),
            [&](auto* t) {
              t->count.temperature_cage = temperatures[0];
              t->count.temperature_sidebands = temperatures[1];
            });
    if (spin_step_option && spin_step_option->count() > 0)
      apply("--sideband-spin-step", std::to_string(sideband_spin_step), [&](auto* t) {
        t->sideband_spin_step = sideband_spin_step;
      });
    if (pair_ratio_option && pair_ratio_option->count() > 0)
      apply("--max-pair-power-ratio", Number(max_pair_power_ratio), [&](auto* t) {
        t->max_pair_power_ratio = max_pair_power_ratio;
      });
    if (load_fraction_option && load_fraction_option->count() > 0)
      apply("--width-load-fraction", Number(width_load_fraction), [&](auto* t) {
        t->width_contact_load_fraction = width_load_fraction;
      });
    if (pattern_per_parity) o->count.sideband_pattern_per_parity = true;
    if (second_pattern) o->count.sideband_second_pattern = true;
    if (width_needs_count) o->width_over_uncertain_count = false;
    if (width_shared_ring_down) o->width.shared_ring_down = true;
    if (count_without_cage_hump) o->count_needs_cage_hump = false;
    if (count_with_extreme_hump) {
      o->min_count_hump_exponent = 0.0;
      o->max_count_hump_exponent = identify::kHumpMaxExponent;
    }
    if (combine_per_count) o->count.combine_per_count = true;
  }
};

}  // namespace spallkit::apps
