#include "replay/recorded_activations.hpp"

#include <cmath>

#include "common/number_text.hpp"
#include "controller/input_error.hpp"
#include "run_file/run_file_reader.hpp"

namespace tongue::replay {
namespace {

namespace L = run_file::layout;

RecordedActivations read(const run_file::RunFileReader& r) {
  const auto fail = [&](const std::string& dataset, const std::string& reason) {
    throw controller::InputError(r.path(), dataset, reason);
  };
  RecordedActivations log;
  log.path = r.path();
  if (!r.exists(L::kMuscleNames))
    fail(L::kMuscleNames, "missing (is this a run file of a scene with muscles?)");
  log.time_s = r.doubles(L::kTime);
  log.muscle_names = r.strings(L::kMuscleNames);
  const std::size_t t = log.time_s.size(), m = log.muscle_names.size();
  if (t == 0) fail(L::kTime, "the run file has no frames");
  if (m == 0) fail(L::kMuscleNames, "the run file has no muscles");
  const std::vector<std::size_t> shape = r.shape(L::kActivations);
  if (shape.size() != 2 || shape[0] != t || shape[1] != m)
    fail(L::kActivations, "expected " + std::to_string(t) + " x " + std::to_string(m) +
                              " (frames of /time x muscles of /muscles/names)");
  log.activations = r.doubles(L::kActivations);
  for (std::size_t k = 0; k < t; ++k) {
    for (std::size_t j = 0; j < m; ++j) {
      const double level = log.level(k, j);
      if (!std::isfinite(level) || level < 0.0 || level > 1.0)
        fail(L::kActivations, "frame " + std::to_string(k) + ", " + log.muscle_names[j] + ": " +
                                  common::number_text(level) + " is not a level in [0, 1]");
    }
  }
  if (r.exists(L::kMaxForce)) {
    log.max_forces_n = r.doubles(L::kMaxForce);
    if (log.max_forces_n.size() != m)
      fail(L::kMaxForce, "expected " + std::to_string(m) + " values, one per muscle");
  }
  if (r.has_attribute(L::kRoot, L::kResetsAttribute))
    log.resets = static_cast<int>(
        common::parse_integer(r.string_attribute(L::kRoot, L::kResetsAttribute)).value_or(0));
  return log;
}

}  // namespace

RecordedActivations read_recorded_activations(const std::string& path) {
  try {
    return read(run_file::RunFileReader(path));
  } catch (const run_file::RunFileError& e) {
    // The controllers' input error: the file and the dataset, for the message and the tests.
    throw controller::InputError(e.file(), e.dataset(), e.reason());
  }
}

}  // namespace tongue::replay
