// Speed of the record readers and the PNG renderers.
//
//   cmake -S . -B build-records -G Ninja -DSPALLKIT_BUILD_BENCHMARKS=ON
//   ninja -C build-records records_benchmark && build-records/bench/records_benchmark
//
// BM_ParseCsvCwruLike parses a CWRU-sized text (144 000 rows, "%.9f,%.17g", about 4.6 MB) held in
// memory, so it measures the parser alone; BM_ReadCsvMeasured reads the real 48 kHz CWRU file
// (skipped when absent) including the file read.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/record_io.h"
#include "plot/plot.h"

namespace {

std::string CwruLikeText(size_t rows) {
  std::string text = "time_s,accel_g\n";
  text.reserve(rows * 34);
  char line[96];
  unsigned state = 12345;
  for (size_t i = 0; i < rows; ++i) {
    state = state * 1664525u + 1013904223u;
    const double noise = (state >> 8) / 16777216.0 - 0.5;
    std::snprintf(
        line, sizeof line, "%.9f,%.17g\n", i / 48000.0, 0.1 * std::sin(0.01 * i) + 0.05 * noise);
    text += line;
  }
  return text;
}

void BM_ParseCsvCwruLike(benchmark::State& state) {
  const std::string text = CwruLikeText(144000);
  for (auto _ : state) {
    spallkit::Record r = spallkit::ParseCsvRecord(text, "bench.csv");
    benchmark::DoNotOptimize(r.samples.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(text.size()));
  state.counters["rows"] = 144000;
}
BENCHMARK(BM_ParseCsvCwruLike)->Unit(benchmark::kMillisecond);

void BM_ReadCsvMeasured(benchmark::State& state) {
  const std::string path = "/work/shared/data/measured/cwru_normal_0hp_rec097_DE_48k.csv";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("CWRU record absent");
    return;
  }
  const auto bytes = std::filesystem::file_size(path);
  for (auto _ : state) {
    spallkit::Record r = spallkit::ReadCsvRecord(path);
    benchmark::DoNotOptimize(r.samples.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(bytes));
}
BENCHMARK(BM_ReadCsvMeasured)->Unit(benchmark::kMillisecond);

void BM_RenderSpectrumPng(benchmark::State& state) {
  spallkit::plot::LinePlot plot;
  plot.title = "Squared envelope spectrum";
  plot.x_label = "frequency (Hz)";
  plot.y_label = "SES ((m/s^2)^2)";
  spallkit::plot::LineSeries s;
  s.color = spallkit::plot::PaletteColor(0);
  s.label = "SES";
  const int n = static_cast<int>(state.range(0));
  for (int i = 0; i < n; ++i) {
    s.x.push_back(i * 0.5);
    s.y.push_back(1.0 + std::sin(i * 0.37) + (i % 230 == 0 ? 20.0 : 0.0));
  }
  plot.series.push_back(s);
  for (int k = 1; k <= 10; ++k) {
    plot.markers.push_back({k * 115.08, std::to_string(k) + "f_b", {214, 39, 40}, true, false});
  }
  for (auto _ : state) {
    std::vector<unsigned char> png = spallkit::plot::RenderLinePlotPng(plot);
    benchmark::DoNotOptimize(png.data());
  }
}
BENCHMARK(BM_RenderSpectrumPng)->Arg(2000)->Arg(200000)->Unit(benchmark::kMillisecond);

void BM_RenderHeatmapPng(benchmark::State& state) {
  spallkit::plot::Heatmap map;
  map.title = "Kurtogram";
  map.rows = 16;
  map.cols = 3 * 256;
  for (int i = 0; i < map.rows * map.cols; ++i) map.values.push_back(std::sin(i * 0.01));
  for (auto _ : state) {
    std::vector<unsigned char> png = spallkit::plot::RenderHeatmapPng(map);
    benchmark::DoNotOptimize(png.data());
  }
}
BENCHMARK(BM_RenderHeatmapPng)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
