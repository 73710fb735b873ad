#include "reduced/reduced_basis_file.hpp"

#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include "reduced/hdf5_lite.hpp"

namespace tongue::reduced {
namespace {

using detail::Hdf5File;

constexpr char kFormat[] = "tongue-reduced-basis-2";
// The format before the element sample was part of the basis.
constexpr char kFormatWithoutSample[] = "tongue-reduced-basis-1";

std::uint64_t fnv1a(const void* data, std::size_t bytes, std::uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

std::string mesh_signature(const fem::Mesh& mesh) {
  std::uint64_t h = 14695981039346656037ull;
  for (const fem::Vec3& x : mesh.nodes) h = fnv1a(x.data(), 3 * sizeof(double), h);
  for (const fem::Hex8& e : mesh.elements) h = fnv1a(e.data(), sizeof(e), h);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return std::to_string(mesh.num_nodes()) + " nodes, " + std::to_string(mesh.num_elements()) +
         " hex8, " + hex;
}

void write_reduced_basis(const std::string& path, const ReducedBasis& b) {
  if (b.modes.rows() != b.origin.size())
    throw std::invalid_argument("reduced basis: modes and origin differ in size");
  if (static_cast<Eigen::Index>(b.sample_elements.size()) != b.sample_weights.size())
    throw std::invalid_argument("reduced basis: the sample's elements and weights differ in size");
  const Hdf5File f(path, true);
  const hsize_t n = static_cast<hsize_t>(b.origin.size());
  const hsize_t s = static_cast<hsize_t>(b.singular_values.size());
  // A column-major 3N x k matrix is, in memory, the row-major k x 3N one.
  const hsize_t modes_dims[2] = {static_cast<hsize_t>(b.modes.cols()), n};
  f.check(H5LTmake_dataset_double(f.id(), "/origin", 1, &n, b.origin.data()),
          "cannot write /origin");
  f.check(H5LTmake_dataset_double(f.id(), "/modes", 2, modes_dims, b.modes.data()),
          "cannot write /modes");
  f.check(H5LTmake_dataset_double(f.id(), "/singular_values", 1, &s, b.singular_values.data()),
          "cannot write /singular_values");
  const hsize_t m = b.sample_elements.size();
  f.check(H5LTmake_dataset_int(f.id(), "/sample_elements", 1, &m, b.sample_elements.data()),
          "cannot write /sample_elements");
  f.check(H5LTmake_dataset_double(f.id(), "/sample_weights", 1, &m, b.sample_weights.data()),
          "cannot write /sample_weights");
  detail::write_text(f, "format", kFormat);
  detail::write_text(f, "mesh_signature", b.mesh_signature);
  detail::write_text(f, "material", b.material);
  detail::write_text(f, "scene", b.scene);
  detail::write_number(f, "energy_fraction", b.energy_fraction);
  detail::write_number(f, "captured", b.captured);
  detail::write_number(f, "snapshots", b.snapshots);
  detail::write_number(f, "runs", b.runs);
  detail::write_number(f, "sample_tolerance", b.sample_tolerance);
  detail::write_number(f, "sample_error", b.sample_error);
}

ReducedBasis read_reduced_basis(const std::string& path) {
  const Hdf5File f(path, false);
  const std::string format = detail::read_text(f, "format");
  if (format == kFormatWithoutSample)
    f.fail(
        "a reduced basis without an element sample (made before hyper-reduction): make it "
        "again with build_reduced_model");
  if (format != kFormat)
    f.fail(std::string("not a reduced-basis file (format is not ") + kFormat + ")");
  ReducedBasis b;
  const hsize_t n = detail::dataset_shape(f, "/origin", 1)[0];
  const std::vector<hsize_t> m = detail::dataset_shape(f, "/modes", 2);
  if (m[1] != n || m[0] == 0)
    f.fail("/modes is " + std::to_string(m[0]) + " x " + std::to_string(m[1]) + ", not k x " +
           std::to_string(n) + " (k > 0)");
  const hsize_t s = detail::dataset_shape(f, "/singular_values", 1)[0];
  b.origin.resize(static_cast<Eigen::Index>(n));
  b.modes.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(m[0]));
  b.singular_values.resize(static_cast<Eigen::Index>(s));
  f.check(H5LTread_dataset_double(f.id(), "/origin", b.origin.data()), "cannot read /origin");
  f.check(H5LTread_dataset_double(f.id(), "/modes", b.modes.data()), "cannot read /modes");
  f.check(H5LTread_dataset_double(f.id(), "/singular_values", b.singular_values.data()),
          "cannot read /singular_values");
  if (!b.origin.allFinite() || !b.modes.allFinite()) f.fail("the basis holds non-finite values");
  const hsize_t m_elements = detail::dataset_shape(f, "/sample_elements", 1, H5T_INTEGER)[0];
  if (detail::dataset_shape(f, "/sample_weights", 1)[0] != m_elements || m_elements == 0)
    f.fail("/sample_elements and /sample_weights differ in length or are empty");
  b.sample_elements.resize(m_elements);
  b.sample_weights.resize(static_cast<Eigen::Index>(m_elements));
  f.check(H5LTread_dataset_int(f.id(), "/sample_elements", b.sample_elements.data()),
          "cannot read /sample_elements");
  f.check(H5LTread_dataset_double(f.id(), "/sample_weights", b.sample_weights.data()),
          "cannot read /sample_weights");
  if (!(b.sample_weights.array() > 0.0).all() || !b.sample_weights.allFinite())
    f.fail("/sample_weights holds a weight that is not a finite positive number");
  b.mesh_signature = detail::read_text(f, "mesh_signature");
  b.material = detail::read_text(f, "material");
  b.scene = detail::read_text(f, "scene");
  b.energy_fraction = detail::read_number(f, "energy_fraction");
  b.captured = detail::read_number(f, "captured");
  b.snapshots = static_cast<int>(detail::read_number(f, "snapshots"));
  b.runs = static_cast<int>(detail::read_number(f, "runs"));
  b.sample_tolerance = detail::read_number(f, "sample_tolerance");
  b.sample_error = detail::read_number(f, "sample_error");
  return b;
}

void check_fits(const ReducedBasis& b, const std::string& path, const fem::Mesh& mesh,
                const std::string& material) {
  const std::string signature = mesh_signature(mesh);
  if (b.mesh_signature != signature)
    throw std::invalid_argument(path + ": made for another mesh (" + b.mesh_signature +
                                "; this one: " + signature + ")");
  if (b.material != material)
    throw std::invalid_argument(path + ": made for another material (" + b.material +
                                "; this one: " + material + ")");
  if (b.origin.size() != 3 * mesh.num_nodes())
    throw std::invalid_argument(path + ": its origin has " + std::to_string(b.origin.size()) +
                                " values, not 3 per node");
  for (const int e : b.sample_elements)
    if (e < 0 || e >= mesh.num_elements())
      throw std::invalid_argument(path + ": sampled element " + std::to_string(e) +
                                  " is not in the mesh (" + std::to_string(mesh.num_elements()) +
                                  " elements)");
}

}  // namespace tongue::reduced
