#include "run_folder.hpp"

#include <ctime>
#include <stdexcept>
#include <system_error>

namespace tongue::runner {

std::filesystem::path make_run_folder(const std::filesystem::path& root, const std::string& name) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(root, ec);
  if (ec) throw std::runtime_error("cannot create " + root.string() + ": " + ec.message());
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", &utc);
  const std::string base = name + "-" + stamp;
  fs::path folder = root / base;
  for (int n = 2; !fs::create_directory(folder, ec); ++n) {
    if (ec || n > 1000)
      throw std::runtime_error("cannot create a run folder under " + root.string());
    folder = root / (base + "-" + std::to_string(n));
  }
  const fs::path latest = root / (name + "-latest");
  fs::remove(latest, ec);
  fs::create_directory_symlink(folder.filename(), latest,
                               ec);  // a convenience: failure is harmless
  return folder;
}

}  // namespace tongue::runner
