#include "run_file/run_file_writer.hpp"

#include <hdf5.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <vector>

#include "run_file/hdf5_handles.hpp"
#include "run_file/run_file_layout.hpp"
#include "run_file/xdmf_sidecar.hpp"

namespace tongue::run_file {

namespace {

namespace L = layout;
using detail::Id;
using detail::QuietErrors;

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The datasets that grow by one frame per append.
struct FrameSeries {
  Id time, positions, iterations, residual, wall_time, cuts, reduced_correction;
};
struct MuscleSeries {
  Id activations, length, velocity;
};
struct ContactSeries {
  Id node_force, obstacle_force, max_penetration;
};

}  // namespace

struct RunFileWriter::Handles {
  Id file;
  FrameSeries frames;
  MuscleSeries muscles;   // only with muscles
  ContactSeries contact;  // only with obstacles
};

namespace {

class Writer {
 public:
  explicit Writer(const std::string& path) : path_(path) {}

  Id check(hid_t id, Id::Closer close, const std::string& what) const {
    if (id < 0) fail(what);
    return Id(id, close);
  }
  void check(herr_t status, const std::string& what) const {
    if (status < 0) fail(what);
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw RunFileError(path_, "", "HDF5 failed to " + what);
  }

  void string_attribute(hid_t loc, const std::string& name, const std::string& value) const {
    // Variable-length UTF-8: h5py reads it as str, and its size is not limited by the 64 KiB
    // an attribute's own storage may hold (long scene texts).
    const Id type = check(H5Tcopy(H5T_C_S1), H5Tclose, "copy a string type");
    check(H5Tset_size(type.get(), H5T_VARIABLE), "set a string size");
    check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "set a string encoding");
    const char* data = value.c_str();
    write_attribute(loc, name, type.get(), &data);
  }

  void int_attribute(hid_t loc, const std::string& name, int value) const {
    write_attribute(loc, name, H5T_NATIVE_INT, &value);
  }

  // A fixed-size dataset written at once.
  Id fixed(hid_t loc, const std::string& name, hid_t file_type, hid_t mem_type,
           const std::vector<hsize_t>& dims, const void* data, const std::string& units,
           const std::string& description) const {
    const Id space = check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                           H5Sclose, "create the dataspace of " + name);
    Id ds = check(H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                             H5P_DEFAULT),
                  H5Dclose, "create " + name);
    const bool empty = std::any_of(dims.begin(), dims.end(), [](hsize_t d) { return d == 0; });
    if (!empty)
      check(H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write " + name);
    describe(ds.get(), units, description);
    return ds;
  }

  // A fixed list of variable-length UTF-8 strings (h5py reads them as str).
  void strings(hid_t loc, const std::string& name, const std::vector<std::string>& values,
               const std::string& description) const {
    const Id type = check(H5Tcopy(H5T_C_S1), H5Tclose, "copy a string type");
    check(H5Tset_size(type.get(), H5T_VARIABLE), "set a string size");
    check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "set a string encoding");
    std::vector<const char*> data;
    for (const auto& v : values) data.push_back(v.c_str());
    fixed(loc, name, type.get(), type.get(), {static_cast<hsize_t>(values.size())}, data.data(),
          "1", description);
  }

  Id group(hid_t loc, const std::string& name) const {
    return check(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                 "create group " + name);
  }

  // A dataset of frames [0 x frame_dims...], extendible along time, chunked chunk_frames at a
  // time along it so that one frame is read by decompressing few chunks.
  Id series(hid_t loc, const std::string& name, hid_t file_type,
            const std::vector<hsize_t>& frame_dims, hsize_t chunk_frames, int deflate_level,
            const std::string& units, const std::string& description) const {
    std::vector<hsize_t> dims{0}, max_dims{H5S_UNLIMITED}, chunk{chunk_frames};
    for (hsize_t d : frame_dims) {
      dims.push_back(d);
      max_dims.push_back(d);
      chunk.push_back(std::max<hsize_t>(d, 1));
    }
    const int rank = static_cast<int>(dims.size());
    const Id space = check(H5Screate_simple(rank, dims.data(), max_dims.data()), H5Sclose,
                           "create the dataspace of " + name);
    const Id dcpl = check(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "create a property list");
    check(H5Pset_chunk(dcpl.get(), rank, chunk.data()), "set the chunks of " + name);
    if (deflate_level > 0 && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
      check(H5Pset_shuffle(dcpl.get()), "set the shuffle filter of " + name);
      check(H5Pset_deflate(dcpl.get(), static_cast<unsigned>(std::min(deflate_level, 9))),
            "set the deflate filter of " + name);
    }
    Id ds = check(
        H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
        H5Dclose, "create " + name);
    describe(ds.get(), units, description);
    return ds;
  }

  // Writes frame number `frame` (the dataset grows to frame + 1 frames).
  void append(hid_t ds, hsize_t frame, hid_t mem_type, const void* data,
              const std::string& name) const {
    const Id old_space = check(H5Dget_space(ds), H5Sclose, "read the extent of " + name);
    const int rank = H5Sget_simple_extent_ndims(old_space.get());
    if (rank < 1) fail("read the rank of " + name);
    std::vector<hsize_t> dims(rank);
    H5Sget_simple_extent_dims(old_space.get(), dims.data(), nullptr);
    dims[0] = frame + 1;
    check(H5Dset_extent(ds, dims.data()), "extend " + name);
    const Id space = check(H5Dget_space(ds), H5Sclose, "read the extent of " + name);
    std::vector<hsize_t> start(rank, 0), count = dims;
    start[0] = frame;
    count[0] = 1;
    check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                              nullptr),
          "select a frame of " + name);
    const Id mem =
        check(H5Screate_simple(rank, count.data(), nullptr), H5Sclose, "create a memory dataspace");
    check(H5Dwrite(ds, mem_type, mem.get(), space.get(), H5P_DEFAULT, data), "write " + name);
  }

 private:
  void write_attribute(hid_t loc, const std::string& name, hid_t type, const void* data) const {
    if (H5Aexists(loc, name.c_str()) > 0) check(H5Adelete(loc, name.c_str()), "replace " + name);
    const Id space = check(H5Screate(H5S_SCALAR), H5Sclose, "create a scalar dataspace");
    const Id attr =
        check(H5Acreate2(loc, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "create attribute " + name);
    check(H5Awrite(attr.get(), type, data), "write attribute " + name);
  }

  void describe(hid_t ds, const std::string& units, const std::string& description) const {
    string_attribute(ds, L::kUnitsAttribute, units);
    string_attribute(ds, L::kDescriptionAttribute, description);
  }

  std::string path_;
};

void create_parent_directories(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  if (ec)
    throw RunFileError(path, "",
                       "cannot create directory " + parent.string() + ": " + ec.message());
}

Id create_file(const std::string& path) {
  Id file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (file.get() < 0) throw RunFileError(path, "", "cannot create the HDF5 file");
  return file;
}

void write_root_attributes(const Writer& w, hid_t file, const std::string& time_unit,
                           const std::string& scene_text) {
  w.int_attribute(file, L::kFormatVersionAttribute, L::kFormatVersion);
  w.string_attribute(file, L::kLengthUnitAttribute, "m");
  w.string_attribute(file, L::kTimeUnitAttribute, time_unit);
  w.string_attribute(file, L::kSceneTextAttribute, scene_text);
}

// The reference configuration: rest positions and hex8 connectivity.
void write_mesh(const Writer& w, hid_t file, const MeshDescription& mesh) {
  const auto n = static_cast<hsize_t>(mesh.nodes.size());
  const auto e = static_cast<hsize_t>(mesh.elements.size());
  std::vector<double> rest(3 * n);
  for (hsize_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) rest[3 * i + c] = mesh.nodes[i][c];
  std::vector<int> elements(8 * e);
  for (hsize_t i = 0; i < e; ++i)
    std::copy(mesh.elements[i].begin(), mesh.elements[i].end(), elements.begin() + 8 * i);
  w.fixed(file, L::kRestPositions, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {n, 3}, rest.data(), "m",
          "node positions of the reference configuration");
  w.fixed(file, L::kElements, H5T_STD_I32LE, H5T_NATIVE_INT, {e, 8}, elements.data(), "1",
          "hex8 connectivity: 0-based node indices, ANSYS SOLID185 node order");
}

// Named sets, so that a picture tool can find landmarks and colour muscles without the scene.
void write_mesh_sets(const Writer& w, hid_t file, const MeshDescription& mesh) {
  const Id mesh_group = w.group(file, L::kMesh);
  const Id node_sets = w.group(file, L::kNodeSets);
  for (const auto& [name, nodes] : mesh.node_sets)
    w.fixed(file, L::node_set(name), H5T_STD_I32LE, H5T_NATIVE_INT, {nodes.size()}, nodes.data(),
            "1", "0-based node indices of node set " + name);
  const Id element_sets = w.group(file, L::kElementSets);
  for (const auto& [name, elements] : mesh.element_sets)
    w.fixed(file, L::element_set(name), H5T_STD_I32LE, H5T_NATIVE_INT, {elements.size()},
            elements.data(), "1", "0-based element indices of element set " + name);
  // An imported mesh's own numbering, so that index i can be shown as the user's id.
  if (!mesh.node_ids.empty())
    w.fixed(file, L::kNodeIds, H5T_STD_I64LE, H5T_NATIVE_LONG, {mesh.node_ids.size()},
            mesh.node_ids.data(), "1", "the mesh file's id of each node, by 0-based index");
  if (!mesh.element_ids.empty())
    w.fixed(file, L::kElementIds, H5T_STD_I64LE, H5T_NATIVE_LONG, {mesh.element_ids.size()},
            mesh.element_ids.data(), "1", "the mesh file's id of each element, by 0-based index");
}

// Time, positions and the solver figures, each empty until the first append.
FrameSeries create_frame_series(const Writer& w, hid_t file, hsize_t num_nodes,
                                const RunFileOptions& options) {
  // About 64 KiB of positions per chunk: large enough to compress well, small enough that
  // reading one frame stays cheap; at least one frame, at most 64.
  const hsize_t frame_bytes = std::max<hsize_t>(1, 3 * num_nodes * sizeof(double));
  const hsize_t chunk_frames = std::clamp<hsize_t>(65536 / frame_bytes, 1, 64);
  const hsize_t scalar_chunk = 1024;
  const int z = options.deflate_level;
  FrameSeries s;
  s.time = w.series(
      file, L::kTime, H5T_IEEE_F64LE, {}, scalar_chunk, z, options.time_unit,
      options.time_unit == "s" ? "simulated time of each frame" : "load factor of each frame");
  s.positions = w.series(file, L::kPositions, H5T_IEEE_F64LE, {num_nodes, 3}, chunk_frames, z, "m",
                         "current node positions of each frame");
  const Id solver = w.group(file, L::kSolver);
  s.iterations = w.series(file, L::kIterations, H5T_STD_I32LE, {}, scalar_chunk, z, "1",
                          "Newton iterations since the previous frame, over all substeps");
  s.residual = w.series(file, L::kResidual, H5T_IEEE_F64LE, {}, scalar_chunk, z, "N",
                        "final residual norm of the frame's step");
  s.wall_time = w.series(file, L::kWallTime, H5T_IEEE_F64LE, {}, scalar_chunk, z, "s",
                         "wall-clock time since the previous frame");
  s.cuts = w.series(file, L::kCuts, H5T_STD_I32LE, {}, scalar_chunk, z, "1",
                    "step halvings since the previous frame");
  s.reduced_correction =
      w.series(file, L::kReducedCorrection, H5T_IEEE_F64LE, {}, scalar_chunk, z, "m",
               "a reduced model's error indicator at its last check: the largest nodal "
               "correction the full model would make to the reduced state (0 for the full model)");
  return s;
}

// Every fibre of every muscle, flattened into the columns of /muscles/fibres.
struct FibreTable {
  std::vector<int> muscle, offsets{0}, nodes;
  std::vector<double> weights, origins;
};

FibreTable fibre_table(const std::vector<MuscleDescription>& muscles) {
  FibreTable t;
  for (std::size_t i = 0; i < muscles.size(); ++i) {
    for (const FibreDescription& f : muscles[i].fibres) {
      t.muscle.push_back(static_cast<int>(i));
      t.weights.push_back(f.weight);
      t.origins.insert(t.origins.end(), f.origin.begin(), f.origin.end());
      t.nodes.insert(t.nodes.end(), f.nodes.begin(), f.nodes.end());
      t.offsets.push_back(static_cast<int>(t.nodes.size()));
    }
  }
  return t;
}

// The group /muscles/fibres; none when no muscle has fibres.
void write_fibres(const Writer& w, hid_t file, const std::vector<MuscleDescription>& muscles) {
  const FibreTable t = fibre_table(muscles);
  if (t.muscle.empty()) return;
  const auto f = static_cast<hsize_t>(t.muscle.size());
  const Id fibres = w.group(file, L::kFibres);
  w.fixed(file, L::kFibreMuscle, H5T_STD_I32LE, H5T_NATIVE_INT, {f}, t.muscle.data(), "1",
          "index of the fibre's muscle in /muscles/names");
  w.fixed(file, L::kFibreWeight, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {f}, t.weights.data(), "1",
          "share of the muscle's tension the fibre carries");
  w.fixed(file, L::kFibreOrigin, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {f, 3}, t.origins.data(), "m",
          "fixed bony attachment before the first node; NaN when the fibre has none");
  w.fixed(file, L::kFibreNodeOffsets, H5T_STD_I32LE, H5T_NATIVE_INT, {f + 1}, t.offsets.data(), "1",
          "fibre k's nodes are nodes[node_offsets[k] .. node_offsets[k+1])");
  w.fixed(file, L::kFibreNodes, H5T_STD_I32LE, H5T_NATIVE_INT,
          {static_cast<hsize_t>(t.nodes.size())}, t.nodes.data(), "1",
          "0-based node indices of every fibre, in order, fibre after fibre");
}

// The group /muscles: names, maximum forces and fibres.
void write_muscles(const Writer& w, hid_t file, const std::vector<MuscleDescription>& muscles) {
  const Id group = w.group(file, L::kMuscles);
  std::vector<std::string> names;
  std::vector<double> max_force;
  for (const auto& mu : muscles) {
    names.push_back(mu.name);
    max_force.push_back(mu.max_force);
  }
  w.strings(file, L::kMuscleNames, names, "muscle names, in the order of every muscle dataset");
  w.fixed(file, L::kMaxForce, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {max_force.size()},
          max_force.data(), "N", "tension at full activation");
  write_fibres(w, file, muscles);
}

// Activations, lengths and velocities of the muscles, each empty until the first append.
MuscleSeries create_muscle_series(const Writer& w, hid_t file, hsize_t num_muscles,
                                  int deflate_level) {
  const hsize_t m = num_muscles;
  const int z = deflate_level;
  // Like the positions: about 64 KiB per chunk, at least one frame, at most 1024.
  const hsize_t chunk = std::clamp<hsize_t>(65536 / (m * sizeof(double)), 1, 1024);
  MuscleSeries s;
  s.activations = w.series(file, L::kActivations, H5T_IEEE_F64LE, {m}, chunk, z, "1",
                           "activation level of each muscle, a fraction of max_force");
  s.length = w.series(file, L::kMuscleLength, H5T_IEEE_F64LE, {m}, chunk, z, "m",
                      "weighted mean fibre length of each muscle");
  s.velocity = w.series(file, L::kMuscleVelocity, H5T_IEEE_F64LE, {m}, chunk, z, "m/s",
                        "rate of change of the muscle length, positive when lengthening");
  return s;
}

// The group /obstacles: names, and each obstacle's vertices and triangles.
void write_obstacles(const Writer& w, hid_t file,
                     const std::vector<ObstacleDescription>& obstacles) {
  const Id group = w.group(file, L::kObstacles);
  std::vector<std::string> names;
  for (const ObstacleDescription& o : obstacles) {
    names.push_back(o.name);
    const Id own = w.group(group.get(), o.name);
    w.fixed(file, L::obstacle_vertices(o.name), H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
            {o.vertices.size(), 3}, o.vertices.data(), "m", "vertex positions");
    w.fixed(file, L::obstacle_triangles(o.name), H5T_STD_I32LE, H5T_NATIVE_INT,
            {o.triangles.size(), 3}, o.triangles.data(), "1",
            "0-based vertex indices of each triangle, its normal (right-hand rule) toward the "
            "solid");
  }
  w.strings(file, L::kObstacleNames, names, "obstacle names, in the order of /contact datasets");
}

// The contact forces and penetration, each empty until the first append.
ContactSeries create_contact_series(const Writer& w, hid_t file, hsize_t num_nodes,
                                    hsize_t num_obstacles, int deflate_level) {
  const Id group = w.group(file, L::kContact);
  const hsize_t chunk = std::clamp<hsize_t>(65536 / (3 * num_nodes * sizeof(double)), 1, 1024);
  ContactSeries s;
  s.node_force = w.series(file, L::kContactNodeForce, H5T_IEEE_F64LE, {num_nodes, 3}, chunk,
                          deflate_level, "N", "force of the obstacles on each node");
  s.obstacle_force = w.series(file, L::kContactObstacleForce, H5T_IEEE_F64LE, {num_obstacles, 3},
                              1024, deflate_level, "N", "force of the solid on each obstacle");
  s.max_penetration =
      w.series(file, L::kContactMaxPenetration, H5T_IEEE_F64LE, {}, 1024, deflate_level, "m",
               "deepest penetration of a node into an obstacle");
  return s;
}

}  // namespace

RunFileWriter::RunFileWriter(const std::string& path, const MeshDescription& mesh,
                             const std::string& scene_text, const RunFileOptions& options,
                             const std::vector<MuscleDescription>& muscles,
                             const std::vector<ObstacleDescription>& obstacles)
    : path_(path),
      num_nodes_(static_cast<int>(mesh.nodes.size())),
      num_muscles_(static_cast<int>(muscles.size())),
      num_obstacles_(static_cast<int>(obstacles.size())),
      flush_interval_(options.flush_interval),
      h_(std::make_unique<Handles>()) {
  create_parent_directories(path);
  const QuietErrors quiet;
  const Writer w(path);
  h_->file = create_file(path);
  const hid_t file = h_->file.get();
  write_root_attributes(w, file, options.time_unit, scene_text);
  write_mesh(w, file, mesh);
  write_mesh_sets(w, file, mesh);
  h_->frames = create_frame_series(w, file, static_cast<hsize_t>(num_nodes_), options);
  if (num_muscles_ > 0) {
    write_muscles(w, file, muscles);
    h_->muscles =
        create_muscle_series(w, file, static_cast<hsize_t>(num_muscles_), options.deflate_level);
  }
  if (num_obstacles_ > 0) {
    write_obstacles(w, file, obstacles);
    h_->contact =
        create_contact_series(w, file, static_cast<hsize_t>(num_nodes_),
                              static_cast<hsize_t>(num_obstacles_), options.deflate_level);
  }
  w.check(H5Fflush(file, H5F_SCOPE_LOCAL), "flush");
  last_flush_ = now_seconds();
}

RunFileWriter::~RunFileWriter() {
  const QuietErrors quiet;
  if (h_ && h_->file.get() >= 0) H5Fflush(h_->file.get(), H5F_SCOPE_LOCAL);
  // The XDMF sidecar <run>.xmf for ParaView, written once at close: it lists every frame, so
  // rewriting it at each flush would cost O(frames) per second of a long run.
  try {
    XdmfRun run;
    run.h5_file = std::filesystem::path(path_).filename().string();
    run.num_nodes = num_nodes_;
    run.times.resize(static_cast<std::size_t>(frames_));
    if (frames_ > 0 && H5Dread(h_->frames.time.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL,
                               H5P_DEFAULT, run.times.data()) < 0)
      run.times.clear();
    const Id elements(H5Dopen2(h_->file.get(), L::kElements, H5P_DEFAULT), H5Dclose);
    const Id element_space(H5Dget_space(elements.get()), H5Sclose);
    hsize_t dims[2] = {0, 0};
    if (H5Sget_simple_extent_dims(element_space.get(), dims, nullptr) == 2) {
      run.num_elements = static_cast<long long>(dims[0]);
      write_xdmf_sidecar(xdmf_sidecar_path(path_), run);
    }
  } catch (...) {  // a missing sidecar is no reason to fail a run
  }
  // Datasets close before the file (members destroyed in reverse order of declaration).
}

void RunFileWriter::check_frame(const std::string& path, int num_nodes, int num_muscles,
                                int num_obstacles, const Eigen::VectorXd& positions,
                                const MuscleFrame& muscles, const ContactFrame& contact) {
  if (positions.size() != 3 * num_nodes)
    throw std::invalid_argument(path + ": positions have " + std::to_string(positions.size()) +
                                " entries, expected 3 x " + std::to_string(num_nodes));
  if (num_muscles > 0) {
    for (const Eigen::VectorXd* v : {&muscles.activations, &muscles.lengths, &muscles.velocities})
      if (v->size() != num_muscles)
        throw std::invalid_argument(path + ": a muscle frame has " + std::to_string(v->size()) +
                                    " entries, expected " + std::to_string(num_muscles));
  }
  if (num_obstacles > 0) {
    if (contact.node_forces.size() != 3 * num_nodes ||
        contact.obstacle_forces.size() != 3 * num_obstacles)
      throw std::invalid_argument(path + ": a contact frame has " +
                                  std::to_string(contact.node_forces.size()) + " node and " +
                                  std::to_string(contact.obstacle_forces.size()) +
                                  " obstacle entries, expected 3 x " + std::to_string(num_nodes) +
                                  " and 3 x " + std::to_string(num_obstacles));
  }
}

void RunFileWriter::append(double time, const Eigen::VectorXd& positions,
                           const SolverFigures& figures, const MuscleFrame& muscles,
                           const ContactFrame& contact) {
  check_frame(path_, num_nodes_, num_muscles_, num_obstacles_, positions, muscles, contact);
  const QuietErrors quiet;
  const Writer w(path_);
  const auto frame = static_cast<hsize_t>(frames_);
  // Eigen vectors are contiguous: 3 n + c is exactly the [N x 3] row-major frame layout.
  w.append(h_->frames.positions.get(), frame, H5T_NATIVE_DOUBLE, positions.data(), L::kPositions);
  w.append(h_->frames.iterations.get(), frame, H5T_NATIVE_INT, &figures.iterations, L::kIterations);
  w.append(h_->frames.residual.get(), frame, H5T_NATIVE_DOUBLE, &figures.residual, L::kResidual);
  w.append(h_->frames.wall_time.get(), frame, H5T_NATIVE_DOUBLE, &figures.wall_time, L::kWallTime);
  w.append(h_->frames.cuts.get(), frame, H5T_NATIVE_INT, &figures.cuts, L::kCuts);
  w.append(h_->frames.reduced_correction.get(), frame, H5T_NATIVE_DOUBLE,
           &figures.reduced_correction, L::kReducedCorrection);
  if (num_muscles_ > 0) {
    w.append(h_->muscles.activations.get(), frame, H5T_NATIVE_DOUBLE, muscles.activations.data(),
             L::kActivations);
    w.append(h_->muscles.length.get(), frame, H5T_NATIVE_DOUBLE, muscles.lengths.data(),
             L::kMuscleLength);
    w.append(h_->muscles.velocity.get(), frame, H5T_NATIVE_DOUBLE, muscles.velocities.data(),
             L::kMuscleVelocity);
  }
  if (num_obstacles_ > 0) {
    w.append(h_->contact.node_force.get(), frame, H5T_NATIVE_DOUBLE, contact.node_forces.data(),
             L::kContactNodeForce);
    w.append(h_->contact.obstacle_force.get(), frame, H5T_NATIVE_DOUBLE,
             contact.obstacle_forces.data(), L::kContactObstacleForce);
    w.append(h_->contact.max_penetration.get(), frame, H5T_NATIVE_DOUBLE, &contact.max_penetration,
             L::kContactMaxPenetration);
  }
  // time last: a reader that sees T times finds T frames in every other dataset.
  w.append(h_->frames.time.get(), frame, H5T_NATIVE_DOUBLE, &time, L::kTime);
  ++frames_;
  const double now = now_seconds();
  if (now - last_flush_ >= flush_interval_) flush();
}

void RunFileWriter::set_attribute(const std::string& name, const std::string& value) {
  const QuietErrors quiet;
  Writer(path_).string_attribute(h_->file.get(), name, value);
}

void RunFileWriter::flush() {
  const QuietErrors quiet;
  Writer(path_).check(H5Fflush(h_->file.get(), H5F_SCOPE_LOCAL), "flush");
  last_flush_ = now_seconds();
}

}  // namespace tongue::run_file
