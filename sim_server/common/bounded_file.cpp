#include "common/bounded_file.hpp"

#include <filesystem>
#include <fstream>
#include <vector>

#include "common/key_path_error.hpp"

namespace tongue::common {

std::string read_bounded_file(const std::string& path, std::size_t max_bytes) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw KeyPathError(path, "", "cannot read the file: is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw KeyPathError(path, "", "cannot open the file");
  std::string text;
  std::vector<char> chunk(1u << 16);
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes)
      throw KeyPathError(path, "",
                         "the file is larger than " + std::to_string(max_bytes) +
                             " bytes (the limit of an input file; is it the right path?)");
  }
  if (in.bad()) throw KeyPathError(path, "", "cannot read the file");
  return text;
}

}  // namespace tongue::common
