#pragma once
// Internal to reduced: an HDF5 file that closes itself and turns failed calls into exceptions
// naming it, with HDF5's own error printing off meanwhile.
#include <hdf5.h>
#include <hdf5_hl.h>  // the Lite API (H5LT*)

#include <stdexcept>
#include <string>
#include <vector>

namespace tongue::reduced::detail {

class Hdf5File {
 public:
  // Opens path read-only (write false) or creates it anew; throws std::runtime_error.
  Hdf5File(const std::string& path, bool write) : path_(path) {
    H5Eget_auto2(H5E_DEFAULT, &print_, &print_data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    if (!write && H5Fis_hdf5(path.c_str()) <= 0) {
      restore();
      throw std::runtime_error(path + ": missing or not an HDF5 file");
    }
    id_ = write ? H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT)
                : H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (id_ < 0) {
      restore();
      throw std::runtime_error(path + ": cannot " + (write ? "create" : "open") + " the file");
    }
  }
  ~Hdf5File() {
    H5Fclose(id_);
    restore();
  }
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;

  hid_t id() const { return id_; }
  const std::string& path() const { return path_; }
  void check(herr_t status, const std::string& what) const {
    if (status < 0) fail(what);
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(path_ + ": " + what);
  }

 private:
  void restore() { H5Eset_auto2(H5E_DEFAULT, print_, print_data_); }
  std::string path_;
  hid_t id_ = H5I_INVALID_HID;
  H5E_auto2_t print_ = nullptr;
  void* print_data_ = nullptr;
};

// Root attributes.
inline void write_text(const Hdf5File& f, const char* name, const std::string& value) {
  f.check(H5LTset_attribute_string(f.id(), "/", name, value.c_str()),
          std::string("cannot write attribute ") + name);
}
inline void write_number(const Hdf5File& f, const char* name, double value) {
  f.check(H5LTset_attribute_double(f.id(), "/", name, &value, 1),
          std::string("cannot write attribute ") + name);
}
inline std::string read_text(const Hdf5File& f, const char* name) {
  hsize_t dims = 0;
  H5T_class_t type_class{};
  size_t size = 0;
  f.check(H5LTget_attribute_info(f.id(), "/", name, &dims, &type_class, &size),
          std::string("no attribute ") + name);
  if (type_class != H5T_STRING) f.fail(std::string("attribute ") + name + " is not text");
  std::vector<char> text(size + 1, '\0');
  f.check(H5LTget_attribute_string(f.id(), "/", name, text.data()),
          std::string("cannot read attribute ") + name);
  return std::string(text.data());
}
inline double read_number(const Hdf5File& f, const char* name) {
  hsize_t dims = 0;
  H5T_class_t type_class{};
  size_t size = 0;
  f.check(H5LTget_attribute_info(f.id(), "/", name, &dims, &type_class, &size),
          std::string("no attribute ") + name);
  if (type_class != H5T_FLOAT || dims != 1)
    f.fail(std::string("attribute ") + name + " is not a number");
  double v = 0.0;
  f.check(H5LTget_attribute_double(f.id(), "/", name, &v),
          std::string("cannot read attribute ") + name);
  return v;
}

// A dataset's dimensions; fails unless it has `rank` of them and holds numbers of class
// `type_class`.
inline std::vector<hsize_t> dataset_shape(const Hdf5File& f, const char* name, int rank,
                                          H5T_class_t type_class = H5T_FLOAT) {
  int found = 0;
  f.check(H5LTget_dataset_ndims(f.id(), name, &found), std::string("no dataset ") + name);
  if (found != rank)
    f.fail(std::string("dataset ") + name + " has " + std::to_string(found) + " dimensions, not " +
           std::to_string(rank));
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5T_class_t found_class{};
  size_t size = 0;
  f.check(H5LTget_dataset_info(f.id(), name, dims.data(), &found_class, &size),
          std::string("cannot read the shape of ") + name);
  if (found_class != type_class) f.fail(std::string("dataset ") + name + " has the wrong type");
  return dims;
}

}  // namespace tongue::reduced::detail
