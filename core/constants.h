// Mathematical constants shared by every module (one definition, so no file carries its own).
#pragma once

#include <numbers>

namespace spallkit {

inline constexpr double kPi = std::numbers::pi;

}  // namespace spallkit
