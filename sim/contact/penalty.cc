#include "sim/contact/penalty.h"

namespace spallkit::sim::contact {

std::string PenaltyLawToString(PenaltyLaw law) {
  switch (law) {
    case PenaltyLaw::kBulkModulus:
      return "bulk_modulus";
    case PenaltyLaw::kMassTimeStep:
      return "mass_time_step";
    case PenaltyLaw::kConstant:
      return "constant";
  }
  return "unknown";
}

bool StringToPenaltyLaw(const std::string& text, PenaltyLaw* law) {
  if (text == "bulk_modulus") {
    *law = PenaltyLaw::kBulkModulus;
  } else if (text == "mass_time_step") {
    *law = PenaltyLaw::kMassTimeStep;
  } else if (text == "constant") {
    *law = PenaltyLaw::kConstant;
  } else {
    return false;
  }
  return true;
}

}  // namespace spallkit::sim::contact
