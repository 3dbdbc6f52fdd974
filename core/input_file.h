// Reading a whole input file (scene, sweep, record, manifest) with the checks every reader needs.
#pragma once

#include <cstddef>
#include <string>

namespace spallkit {

// What a non-regular input (a pipe, a device such as /dev/zero) may hold at most: such a file
// has no size to check up front and may never end.
inline constexpr std::size_t kMaxStreamedInputBytes = std::size_t{256} << 20;

// The contents of `path`. Throws InputError naming the path and `what` (e.g. "a scene file
// (TOML)") when it is a folder, cannot be opened or read, or is not a regular file and holds
// more than kMaxStreamedInputBytes. /dev/null reads as empty.
std::string ReadInputFile(const std::string& path, const std::string& what);

}  // namespace spallkit
