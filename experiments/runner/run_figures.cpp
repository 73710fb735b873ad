#include "run_figures.hpp"

#include <hdf5.h>
#include <lcm/eventlog.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace tongue::runner {
namespace {

// The landmark node sets of the built-in tongue, in the order a summary lists them.
constexpr const char* kLandmarks[] = {"tip",          "blade", "palatal_dorsum",
                                      "velar_dorsum", "root",  "gg_insertion"};

// A read-only HDF5 file: datasets by name, whole.
class H5Reader {
 public:
  explicit H5Reader(const std::filesystem::path& path)
      : path_(path.string()), file_(H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {
    if (file_ < 0) throw std::runtime_error(path_ + ": cannot open as an HDF5 file");
  }
  ~H5Reader() { H5Fclose(file_); }
  H5Reader(const H5Reader&) = delete;
  H5Reader& operator=(const H5Reader&) = delete;

  bool has(const std::string& name) const {
    return H5Lexists(file_, name.c_str(), H5P_DEFAULT) > 0;
  }
  std::vector<double> doubles(const std::string& name) const {
    return read<double>(name, H5T_NATIVE_DOUBLE);
  }
  std::vector<long> longs(const std::string& name) const {
    return read<long>(name, H5T_NATIVE_LONG);
  }

  std::string root_string_attribute(const std::string& name) const {
    if (H5Aexists(file_, name.c_str()) <= 0) return "";
    const hid_t attr = H5Aopen(file_, name.c_str(), H5P_DEFAULT);
    const hid_t type = H5Aget_type(attr);
    std::string value;
    if (H5Tis_variable_str(type) > 0) {
      char* s = nullptr;
      if (H5Aread(attr, type, &s) >= 0 && s) value = s;
      H5free_memory(s);
    } else {
      std::vector<char> buffer(H5Tget_size(type) + 1, '\0');
      if (H5Aread(attr, type, buffer.data()) >= 0) value = buffer.data();
    }
    H5Tclose(type);
    H5Aclose(attr);
    return value;
  }

 private:
  template <typename T>
  std::vector<T> read(const std::string& name, hid_t type) const {
    if (!has(name)) throw std::runtime_error(path_ + ": no dataset " + name);
    const hid_t ds = H5Dopen2(file_, name.c_str(), H5P_DEFAULT);
    const hid_t space = H5Dget_space(ds);
    const hssize_t n = H5Sget_simple_extent_npoints(space);
    std::vector<T> values(static_cast<std::size_t>(std::max<hssize_t>(n, 0)));
    const herr_t rc =
        values.empty() ? 0 : H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    H5Sclose(space);
    H5Dclose(ds);
    if (rc < 0) throw std::runtime_error(path_ + ": cannot read " + name);
    return values;
  }

  std::string path_;
  hid_t file_;
};

}  // namespace

RunFigures read_run_figures(const std::filesystem::path& run_file) {
  const H5Reader h5(run_file);
  const std::vector<double> time = h5.doubles("/time");
  const std::vector<double> positions = h5.doubles("/positions");
  if (time.empty()) throw std::runtime_error(run_file.string() + ": no frames");
  const std::size_t frames = time.size();
  const std::size_t values_per_frame = positions.size() / frames;

  RunFigures f;
  f.steps = static_cast<int>(frames) - 1;
  f.simulated = time.back() - time.front();
  for (const double w : h5.doubles("/solver/wall_time")) f.physics_wall += w;
  for (const long i : h5.longs("/solver/iterations")) f.newton_iterations += i;
  for (const long c : h5.longs("/solver/cuts")) f.step_cuts += c;
  f.status = h5.root_string_attribute("status");

  for (const char* name : kLandmarks) {
    const std::string set = std::string("/mesh/node_sets/") + name;
    if (!h5.has(set)) continue;
    const std::vector<long> nodes = h5.longs(set);
    if (nodes.empty()) continue;
    const std::size_t at = 3 * static_cast<std::size_t>(nodes.front());
    LandmarkMotion m;
    m.name = name;
    for (std::size_t k = 0; k < frames; ++k) {
      std::array<double, 3> d{};
      for (int c = 0; c < 3; ++c) {
        d[c] = 1e3 * (positions[k * values_per_frame + at + c] - positions[at + c]);  // mm
      }
      const double distance = std::hypot(d[0], d[1], d[2]);
      if (distance > m.peak_mm) {
        m.peak_mm = distance;
        m.peak_time = time[k];
      }
      m.final_mm = d;
    }
    f.landmarks.push_back(m);
  }
  return f;
}

std::optional<BusFigures> read_bus_figures(const std::filesystem::path& lcm_log,
                                           const std::string& state_channel,
                                           const std::string& activation_channel) {
  const std::unique_ptr<lcm_eventlog_t, decltype(&lcm_eventlog_destroy)> log(
      lcm_eventlog_create(lcm_log.c_str(), "r"), &lcm_eventlog_destroy);
  if (!log) return std::nullopt;
  BusFigures b;
  std::int64_t first = 0, last = 0;
  while (lcm_eventlog_event_t* event = lcm_eventlog_read_next_event(log.get())) {
    const std::string channel(event->channel, event->channellen);
    if (channel == state_channel) {
      if (b.states++ == 0) first = event->timestamp;
      last = event->timestamp;
    } else if (channel == activation_channel) {
      ++b.activations;
    }
    lcm_eventlog_free_event(event);
  }
  b.state_span = 1e-6 * static_cast<double>(last - first);
  return b;
}

}  // namespace tongue::runner
