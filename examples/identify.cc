// Identify a roller spall from a vibration record: what `spall identify FILE --bearing N205EM
// --rpm 1200` does (docs/IDENTIFY.md): diagnose the record, then count the defective rollers,
// place them in the cage and, where the record allows, measure the spall width.
//
//   example_identify [record.csv] [rpm]
// Defaults: datasets/samples/n205em_roller_defect_1200rpm.csv (one spalled roller) at 1200 rpm.
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
  try {
    const sk::Record record = sk::ReadRecord(path);
    const sk::BearingGeometry bearing = sk::CatalogBearing("N205EM");
    const sk::dsp::Diagnosis diagnosis = sk::dsp::Diagnose(record, bearing, shaft_hz);
    const sk::identify::Identification id =
        sk::identify::Identify(record, bearing, shaft_hz, diagnosis);
    std::printf("%s\n", id.BriefReport().c_str());
  } catch (const std::exception& e) {  // InputError: the file, or a bad record
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
