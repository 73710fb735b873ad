#pragma once
// Reading a whole input file with a ceiling on its size, so that a wrong path (/dev/zero, a
// device, a log of gigabytes) gives an error instead of reading until memory runs out.
#include <cstddef>
#include <string>

namespace tongue::common {

// The largest YAML input (scene, experiment, motor plan, activation sequence) read [bytes]: the
// project's largest scene is a few kilobytes; the scene's text also travels whole in the model
// message, so this bounds that message too.
inline constexpr std::size_t kMaxInputFileBytes = 16u << 20;

// The bytes of the file at path. Throws KeyPathError naming path when it cannot be opened or
// read, is a directory, or holds more than max_bytes (reading stops there: a file that never
// ends is read no further).
std::string read_bounded_file(const std::string& path, std::size_t max_bytes = kMaxInputFileBytes);

}  // namespace tongue::common
