#include "replay/run_log.hpp"

#include <hdf5.h>

#include <cmath>
#include <cstdlib>

#include "controller/input_error.hpp"
#include "controller/number_text.hpp"

namespace tongue::replay {
namespace {

// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = H5I_INVALID_HID; }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle& operator=(Handle&&) = delete;
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  Closer close_;
};

// HDF5 prints its error stack on every failed call by default; failures here become InputErrors.
class QuietHdf5 {
 public:
  QuietHdf5() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

class Reader {
 public:
  explicit Reader(const std::string& path)
      : path_(path), file_(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose) {
    if (!file_.valid()) throw controller::InputError(path, "", "cannot open as an HDF5 run file");
  }

  [[noreturn]] void fail(const std::string& dataset, const std::string& reason) const {
    throw controller::InputError(path_, dataset, reason);
  }

  bool exists(const std::string& name) const {
    return H5Lexists(file_.get(), name.c_str(), H5P_DEFAULT) > 0;
  }

  std::vector<hsize_t> shape(const std::string& name) const {
    const Handle ds = open(name);
    const Handle space(H5Dget_space(ds.get()), H5Sclose);
    const int rank = H5Sget_simple_extent_ndims(space.get());
    if (rank < 0) fail(name, "cannot read its shape");
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
    return dims;
  }

  std::vector<double> doubles(const std::string& name) const {
    std::size_t count = 1;
    for (hsize_t d : shape(name)) count *= d;
    std::vector<double> out(count);
    const Handle ds = open(name);
    if (count > 0 &&
        H5Dread(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
      fail(name, "cannot be read as numbers");
    return out;
  }

  std::vector<std::string> strings(const std::string& name) const {
    const std::vector<hsize_t> dims = shape(name);
    if (dims.size() != 1) fail(name, "expected a list of names");
    const Handle ds = open(name);
    const Handle type(H5Dget_type(ds.get()), H5Tclose);
    if (H5Tis_variable_str(type.get()) <= 0) fail(name, "expected variable-length strings");
    std::vector<char*> raw(dims[0], nullptr);
    // Read with the stored type itself: HDF5 converts no strings between ASCII and UTF-8.
    if (!raw.empty() &&
        H5Dread(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()) < 0)
      fail(name, "cannot be read as names");
    std::vector<std::string> out;
    for (char* s : raw) {
      out.emplace_back(s ? s : "");
      H5free_memory(s);
    }
    return out;
  }

  // A string attribute of the root group, empty when absent.
  std::string root_attribute(const std::string& name) const {
    if (H5Aexists(file_.get(), name.c_str()) <= 0) return {};
    const Handle attr(H5Aopen(file_.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
    const Handle type(H5Aget_type(attr.get()), H5Tclose);
    if (H5Tget_class(type.get()) != H5T_STRING) return {};
    std::string value;
    if (H5Tis_variable_str(type.get()) > 0) {
      char* s = nullptr;
      if (H5Aread(attr.get(), type.get(), &s) >= 0 && s) value = s;
      H5free_memory(s);
    } else {
      std::vector<char> buf(H5Tget_size(type.get()) + 1, '\0');
      if (H5Aread(attr.get(), type.get(), buf.data()) >= 0) value = buf.data();
    }
    return value;
  }

 private:
  Handle open(const std::string& name) const {
    if (!exists(name)) fail(name, "missing (is this a run file of a scene with muscles?)");
    Handle ds(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!ds.valid()) fail(name, "cannot be opened");
    return ds;
  }

  std::string path_;
  Handle file_;
};

}  // namespace

RunLog read_run_log(const std::string& path) {
  const QuietHdf5 quiet;
  const Reader r(path);
  RunLog log;
  log.path = path;
  log.time_s = r.doubles("/time");
  log.muscle_names = r.strings("/muscles/names");
  const std::size_t t = log.time_s.size(), m = log.muscle_names.size();
  if (t == 0) r.fail("/time", "the run file has no frames");
  if (m == 0) r.fail("/muscles/names", "the run file has no muscles");
  const std::vector<hsize_t> shape = r.shape("/activations");
  if (shape.size() != 2 || shape[0] != t || shape[1] != m)
    r.fail("/activations", "expected " + std::to_string(t) + " x " + std::to_string(m) +
                               " (frames of /time x muscles of /muscles/names)");
  log.activations = r.doubles("/activations");
  for (std::size_t k = 0; k < t; ++k) {
    for (std::size_t j = 0; j < m; ++j) {
      const double level = log.level(k, j);
      if (!std::isfinite(level) || level < 0.0 || level > 1.0)
        r.fail("/activations", "frame " + std::to_string(k) + ", " + log.muscle_names[j] + ": " +
                                   controller::number_text(level) + " is not a level in [0, 1]");
    }
  }
  if (r.exists("/muscles/max_force")) {
    log.max_forces_n = r.doubles("/muscles/max_force");
    if (log.max_forces_n.size() != m)
      r.fail("/muscles/max_force", "expected " + std::to_string(m) + " values, one per muscle");
  }
  if (const std::string resets = r.root_attribute("resets"); !resets.empty())
    log.resets = std::atoi(resets.c_str());
  return log;
}

}  // namespace tongue::replay
