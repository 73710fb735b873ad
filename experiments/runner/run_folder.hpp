#pragma once
// The folder one run leaves its results in: <root>/<name>-<UTC time>/, with <root>/<name>-latest
// pointing at the newest, so that no run overwrites another.
#include <filesystem>
#include <string>

namespace tongue::runner {

// Creates the folder (and root); a second run within the same second gets a suffix -2, -3, ...
// Throws std::runtime_error when it cannot be created.
std::filesystem::path make_run_folder(const std::filesystem::path& root, const std::string& name);

}  // namespace tongue::runner
