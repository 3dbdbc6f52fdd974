// Diagnose a vibration record from a CSV file: what `spall diagnose FILE --bearing N205EM
// --rpm 1200` does, in a few lines of library code.
//
//   example_diagnose_csv [record.csv] [rpm]
// Defaults: datasets/samples/n205em_roller_defect_1200rpm.csv at 1200 rpm.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/bearing.h"
#include "core/error.h"
#include "core/record_io.h"
#include "dsp/diagnose.h"

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "datasets/samples/n205em_roller_defect_1200rpm.csv";
  const double rpm = argc > 2 ? std::atof(argv[2]) : 1200.0;

  try {
    const spallkit::Record record = spallkit::ReadRecord(path);  // CSV or HDF5, by extension
    const spallkit::BearingGeometry bearing = spallkit::CatalogBearing("N205EM");
    const spallkit::dsp::Diagnosis diagnosis = spallkit::dsp::Diagnose(record, bearing, rpm / 60.0);
    std::printf("%s\n", diagnosis.BriefReport().c_str());
  } catch (const spallkit::InputError& e) {  // one line naming the file, line and what was wrong
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
