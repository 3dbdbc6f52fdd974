// Identify a roller spall from a vibration record: what `spall identify FILE --bearing N205EM
// --rpm 1200 --load-n 10000` does (docs/IDENTIFY.md): diagnose the record, then count the
// defective rollers, place them in the cage and, where the record allows, measure the spall width
// (which needs the radial load: it sets where a loaded roller is released).
//
//   example_identify [record.csv] [rpm] [radial load, N]
// Defaults: datasets/samples/n205em_roller_defect_1200rpm.csv (one spalled roller) at 1200 rpm and
// 10 kN.
#include "identify/identify.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "core/bearing.h"
#include "core/record_io.h"
#include "dsp/diagnose.h"

int main(int argc, char** argv) {
  namespace sk = spallkit;
  const std::string path = argc > 1 ? argv[1] : "datasets/samples/n205em_roller_defect_1200rpm.csv";
  const double shaft_hz = (argc > 2 ? std::atof(argv[2]) : 1200.0) / 60.0;
  sk::identify::IdentifyOptions options;
  options.radial_load_n = argc > 3 ? std::atof(argv[3]) : 10000.0;
  try {
    const sk::Record record = sk::ReadRecord(path);
    const sk::BearingGeometry bearing = sk::CatalogBearing("N205EM");
    const sk::dsp::Diagnosis diagnosis = sk::dsp::Diagnose(record, bearing, shaft_hz);
    const sk::identify::Identification id =
        sk::identify::Identify(record, bearing, shaft_hz, diagnosis, options);
    std::printf("%s\n", id.BriefReport().c_str());
  } catch (const std::exception& e) {  // InputError: the file, or a bad record
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
