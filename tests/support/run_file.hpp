#pragma once
// Read-only access to an HDF5 run file (the layout of sim_server/run_file), for end-to-end tests.
#include <hdf5.h>

#include <filesystem>
#include <string>
#include <vector>

namespace tongue::testing {

namespace fs = std::filesystem;

class RunFile {
 public:
  explicit RunFile(const fs::path& p) : file_(H5Fopen(p.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
  ~RunFile() {
    if (file_ >= 0) H5Fclose(file_);
  }
  bool ok() const { return file_ >= 0; }

  std::vector<hsize_t> shape(const std::string& name) const {
    const hid_t ds = H5Dopen2(file_, name.c_str(), H5P_DEFAULT);
    if (ds < 0) return {};
    const hid_t space = H5Dget_space(ds);
    std::vector<hsize_t> dims(H5Sget_simple_extent_ndims(space));
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    H5Sclose(space);
    H5Dclose(ds);
    return dims;
  }

  std::vector<double> doubles(const std::string& name) const {
    return read<double>(name, H5T_NATIVE_DOUBLE);
  }
  std::vector<int> ints(const std::string& name) const { return read<int>(name, H5T_NATIVE_INT); }

  // A string attribute of the root group (loc "/") or of a dataset.
  std::string string_attribute(const std::string& loc, const std::string& name) const {
    const hid_t attr = H5Aopen_by_name(file_, loc.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (attr < 0) return "<missing>";
    const hid_t type = H5Aget_type(attr);
    std::string value;
    if (H5Tis_variable_str(type) > 0) {
      // Read with the stored type itself: HDF5 converts no strings between ASCII and UTF-8.
      char* s = nullptr;
      H5Aread(attr, type, &s);
      value = s ? s : "";
      H5free_memory(s);
    } else {
      std::vector<char> buf(H5Tget_size(type) + 1, '\0');
      H5Aread(attr, type, buf.data());
      value = buf.data();
    }
    H5Tclose(type);
    H5Aclose(attr);
    return value;
  }

  // A dataset of variable-length strings.
  std::vector<std::string> strings(const std::string& name) const {
    const hid_t ds = H5Dopen2(file_, name.c_str(), H5P_DEFAULT);
    if (ds < 0) return {};
    const hid_t type = H5Dget_type(ds);
    std::vector<std::string> out;
    if (H5Tis_variable_str(type) > 0) {
      std::vector<hsize_t> dims = shape(name);
      std::vector<char*> raw(dims.empty() ? 0 : dims[0], nullptr);
      if (!raw.empty() && H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()) >= 0) {
        for (char* s : raw) {
          out.emplace_back(s ? s : "");
          H5free_memory(s);
        }
      }
    }
    H5Tclose(type);
    H5Dclose(ds);
    return out;
  }

  bool exists(const std::string& name) const {
    return H5Lexists(file_, name.c_str(), H5P_DEFAULT) > 0;
  }

  int int_attribute(const std::string& name) const {
    int v = -1;
    const hid_t attr = H5Aopen_by_name(file_, "/", name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (attr < 0) return v;
    H5Aread(attr, H5T_NATIVE_INT, &v);
    H5Aclose(attr);
    return v;
  }

 private:
  template <typename T>
  std::vector<T> read(const std::string& name, hid_t mem_type) const {
    std::size_t count = 1;
    for (hsize_t d : shape(name)) count *= d;
    std::vector<T> v(count);
    const hid_t ds = H5Dopen2(file_, name.c_str(), H5P_DEFAULT);
    if (ds < 0) return {};
    if (count > 0) H5Dread(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    H5Dclose(ds);
    return v;
  }

  hid_t file_;
};

}  // namespace tongue::testing
