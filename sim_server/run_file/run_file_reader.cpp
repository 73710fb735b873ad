#include "run_file/run_file_reader.hpp"

#include <hdf5.h>

#include "run_file/hdf5_handles.hpp"

namespace tongue::run_file {

using detail::Id;
using detail::QuietErrors;

struct RunFileReader::File {
  Id id;
};

namespace {

// The dataset of name in file, opened; RunFileError naming it when missing.
Id open_dataset(hid_t file, const std::string& path, const std::string& name) {
  if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0) throw RunFileError(path, name, "missing");
  Id ds(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) throw RunFileError(path, name, "cannot be opened as a dataset");
  return ds;
}

std::vector<std::size_t> extent(hid_t ds, const std::string& path, const std::string& name) {
  const Id space(H5Dget_space(ds), H5Sclose);
  const int rank = space.valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
  if (rank < 0) throw RunFileError(path, name, "cannot read its shape");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return std::vector<std::size_t>(dims.begin(), dims.end());
}

template <typename T>
std::vector<T> read_all(hid_t file, const std::string& path, const std::string& name,
                        hid_t mem_type, const char* what) {
  const QuietErrors quiet;
  const Id ds = open_dataset(file, path, name);
  std::size_t count = 1;
  for (const std::size_t d : extent(ds.get(), path, name)) count *= d;
  std::vector<T> out(count);
  if (count > 0 && H5Dread(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw RunFileError(path, name, std::string("cannot be read as ") + what);
  return out;
}

// The attribute name of object ("/" or a dataset) opened, where set to the text errors name it
// by ("status", "/time units"); RunFileError when it is missing.
Id open_attribute(const RunFileReader& reader, hid_t file, const std::string& object,
                  const std::string& name, std::string& where) {
  where = object == layout::kRoot ? name : object + " " + name;
  if (!reader.has_attribute(object, name))
    throw RunFileError(reader.path(), where, "missing attribute");
  return Id(H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
            H5Aclose);
}

}  // namespace

RunFileReader::RunFileReader(const std::string& path)
    : path_(path), file_(std::make_unique<File>()) {
  const QuietErrors quiet;
  file_->id = Id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file_->id.valid()) throw RunFileError(path, "", "cannot open as an HDF5 run file");
}

RunFileReader::~RunFileReader() = default;
RunFileReader::RunFileReader(RunFileReader&&) noexcept = default;
RunFileReader& RunFileReader::operator=(RunFileReader&&) noexcept = default;

bool RunFileReader::exists(const std::string& name) const {
  const QuietErrors quiet;
  if (name == layout::kRoot) return true;
  // A missing group on the way makes H5Lexists fail (< 0) rather than answer 0.
  return H5Lexists(file_->id.get(), name.c_str(), H5P_DEFAULT) > 0;
}

std::vector<std::size_t> RunFileReader::shape(const std::string& dataset) const {
  const QuietErrors quiet;
  const Id ds = open_dataset(file_->id.get(), path_, dataset);
  return extent(ds.get(), path_, dataset);
}

std::vector<double> RunFileReader::doubles(const std::string& dataset) const {
  return read_all<double>(file_->id.get(), path_, dataset, H5T_NATIVE_DOUBLE, "numbers");
}

std::vector<int> RunFileReader::ints(const std::string& dataset) const {
  return read_all<int>(file_->id.get(), path_, dataset, H5T_NATIVE_INT, "integers");
}

std::vector<std::string> RunFileReader::strings(const std::string& dataset) const {
  const QuietErrors quiet;
  const Id ds = open_dataset(file_->id.get(), path_, dataset);
  const std::vector<std::size_t> dims = extent(ds.get(), path_, dataset);
  if (dims.size() != 1) throw RunFileError(path_, dataset, "expected a list of strings");
  const Id type(H5Dget_type(ds.get()), H5Tclose);
  if (!type.valid() || H5Tget_class(type.get()) != H5T_STRING)
    throw RunFileError(path_, dataset, "expected strings");
  std::vector<std::string> out;
  if (dims[0] == 0) return out;
  // Read with the stored type itself: HDF5 converts no strings between ASCII and UTF-8.
  if (H5Tis_variable_str(type.get()) > 0) {
    std::vector<char*> raw(dims[0], nullptr);
    if (H5Dread(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()) < 0)
      throw RunFileError(path_, dataset, "cannot be read as strings");
    for (char* s : raw) {
      out.emplace_back(s ? s : "");
      H5free_memory(s);
    }
  } else {
    const std::size_t size = H5Tget_size(type.get());
    std::vector<char> raw(dims[0] * size);
    if (H5Dread(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()) < 0)
      throw RunFileError(path_, dataset, "cannot be read as strings");
    for (std::size_t k = 0; k < dims[0]; ++k) {
      const char* begin = raw.data() + k * size;
      std::size_t n = 0;
      while (n < size && begin[n] != '\0') ++n;
      out.emplace_back(begin, n);
    }
  }
  return out;
}

bool RunFileReader::has_attribute(const std::string& object, const std::string& name) const {
  const QuietErrors quiet;
  if (!exists(object)) return false;
  return H5Aexists_by_name(file_->id.get(), object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

std::string RunFileReader::string_attribute(const std::string& object,
                                            const std::string& name) const {
  const QuietErrors quiet;
  std::string where;
  const Id attr = open_attribute(*this, file_->id.get(), object, name, where);
  const Id type(attr.valid() ? H5Aget_type(attr.get()) : H5I_INVALID_HID, H5Tclose);
  if (!type.valid() || H5Tget_class(type.get()) != H5T_STRING)
    throw RunFileError(path_, where, "expected a string attribute");
  if (H5Tis_variable_str(type.get()) > 0) {
    char* s = nullptr;
    if (H5Aread(attr.get(), type.get(), &s) < 0)
      throw RunFileError(path_, where, "cannot be read as a string");
    std::string value = s ? s : "";
    H5free_memory(s);
    return value;
  }
  std::vector<char> buffer(H5Tget_size(type.get()) + 1, '\0');
  if (H5Aread(attr.get(), type.get(), buffer.data()) < 0)
    throw RunFileError(path_, where, "cannot be read as a string");
  return std::string(buffer.data());
}

int RunFileReader::int_attribute(const std::string& object, const std::string& name) const {
  const QuietErrors quiet;
  std::string where;
  const Id attr = open_attribute(*this, file_->id.get(), object, name, where);
  int value = 0;
  if (!attr.valid() || H5Aread(attr.get(), H5T_NATIVE_INT, &value) < 0)
    throw RunFileError(path_, where, "cannot be read as an integer");
  return value;
}

}  // namespace tongue::run_file
