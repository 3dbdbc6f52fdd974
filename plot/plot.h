// PNG rendering of line plots (spectra, envelope spectra, waveforms) and heatmaps (kurtograms,
// spectrograms) with OpenCV core/imgproc/imgcodecs.
//
// Why in C++: `spall diagnose` must leave a picture a person can read without Python. The look
// follows the usual scientific defaults: white background, black frame, light grid, ticks at
// "nice" values (1, 2, 5 x 10^k), anti-aliased Hershey Simplex text, a legend box, viridis for
// heatmaps. Nothing from OpenCV appears in this header, so users of the API need no OpenCV flags.
//
// Output is encoded in memory (cv::imencode) and written atomically (core/atomic_file.h); a bad
// path, empty data or inconsistent sizes throw spallkit::InputError with one line.
#pragma once

// One header per concept; this one includes them all.
#include "plot/color.h"      // Rgb, PaletteColor
#include "plot/heatmap.h"    // Heatmap, WriteHeatmap, RenderHeatmapPng
#include "plot/line_plot.h"  // LineSeries, Marker, LinePlot, WriteLinePlot, RenderLinePlotPng
#include "plot/ticks.h"      // NiceTicks, FormatTick
