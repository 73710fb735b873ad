#include "fem/assembly/solid_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>
#include <span>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

namespace tongue::fem {

SolidModel::SolidModel(Mesh mesh, std::shared_ptr<const Material> material, Formulation formulation,
                       double density, const std::vector<PrescribedDof>& prescribed,
                       const std::vector<std::pair<int, int>>& extra_node_pairs)
    : mesh_(std::move(mesh)),
      material_(std::move(material)),
      formulation_(formulation),
      density_(density),
      dofs_(mesh_.num_nodes(), prescribed) {
  if (!material_) throw std::invalid_argument("solid model needs a material");
  if (!(density_ > 0.0)) throw std::invalid_argument("density must be positive [kg/m^3]");
  if (formulation_ == Formulation::mean_dilatation && material_->as_uncoupled() == nullptr) {
    throw std::invalid_argument("material '" + material_->name() +
                                "' has no isochoric/volumetric split: use the standard "
                                "formulation");
  }
  rest_positions_.resize(3 * mesh_.num_nodes());
  for (int n = 0; n < mesh_.num_nodes(); ++n) rest_positions_.segment<3>(3 * n) = mesh_.nodes[n];

  boundary_ = boundary_faces(mesh_);
  geometry_.reserve(mesh_.elements.size());
  rest_coords_.reserve(mesh_.elements.size());
  for (int e = 0; e < mesh_.num_elements(); ++e) {
    try {
      rest_coords_.push_back(element_coords(e, rest_positions_));
      geometry_.push_back(make_element_geometry(rest_coords_.back()));
    } catch (const std::invalid_argument& err) {
      throw std::invalid_argument("element " + std::to_string(e) + ": " + err.what());
    }
    reference_volume_ += geometry_.back().volume;
  }
  if (material_->as_uncoupled() != nullptr) {
    std::vector<int> all(mesh_.elements.size());
    std::iota(all.begin(), all.end(), 0);
    all_batches_ = std::make_shared<const BatchLayout>(make_layout(std::move(all)));
  }
  AssemblyPattern assembly = build_assembly_pattern(mesh_, dofs_, extra_node_pairs);
  pattern_ = std::make_shared<const SparsityPattern>(std::move(assembly.pattern));
  element_scatter_ = std::move(assembly.element_scatter);
  if (all_batches_) {
    tangent_begin_.reserve(mesh_.elements.size() + 1);
    tangent_begin_.push_back(0);
    for (const auto& map : element_scatter_) {
      for (int j = 0; j < 24; ++j) {
        for (int i = 0; i < 24; ++i) {
          const int k = map[24 * i + j];
          if (k < 0) continue;
          // K(i, j) of the whole element matrix, from an upper node block.
          const int a = i / 3, b = j / 3;
          const int source = a <= b ? 9 * upper_block(a, b) + 3 * (i % 3) + j % 3
                                    : 9 * upper_block(b, a) + 3 * (j % 3) + i % 3;
          tangent_value_.push_back(k);
          tangent_source_.push_back(static_cast<std::uint16_t>(source));
        }
      }
      tangent_begin_.push_back(static_cast<int>(tangent_value_.size()));
    }
  }
}

hex8::ElementCoords SolidModel::element_coords(int e, const Vector& positions) const {
  hex8::ElementCoords X;
  const Hex8& nodes = mesh_.elements[e];
  for (int a = 0; a < 8; ++a) X.row(a) = positions.segment<3>(3 * nodes[a]).transpose();
  return X;
}

AssemblyStatus SolidModel::assemble(const Vector& u, Vector& internal_force,
                                    SymmetricMatrix* stiffness, double* strain_energy) const {
  internal_force.setZero(num_dofs());
  if (stiffness) stiffness->set_zero();
  if (strain_energy) *strain_energy = 0.0;
  return add_weighted(u, {}, internal_force, stiffness, strain_energy);
}

namespace {
// Elements evaluated in parallel before their results are summed in element order: bounds the
// workspace (forces and, for the tangent, 24 x 24 matrices) to a few MB at any mesh size.
constexpr int kBlockElements = 1024;
}  // namespace

// Results of one block of elements, filled in parallel and summed by the calling thread.
struct SolidModel::Workspace {
  std::mutex mutex;  // one assembly at a time uses it
  std::vector<int> elements;
  std::vector<int> batches;
  std::vector<ElementBatchResponse> batch_results;
  std::vector<ElementBatchTangent> batch_tangents;
  std::vector<ElementVector> force;
  std::vector<ElementMatrix> stiffness;
  std::vector<double> energy, min_J;
  std::vector<char> ok;
};

SolidModel::~SolidModel() = default;

void SolidModel::set_threads(int threads) {
  if (threads < 1) {
    throw std::invalid_argument("solid model: threads must be at least 1, got " +
                                std::to_string(threads));
  }
  if (threads == this->threads()) return;
  pool_ = threads > 1 ? std::make_unique<WorkerPool>(threads) : nullptr;
  workspace_ = threads > 1 ? std::make_unique<Workspace>() : nullptr;
}

hex8::ElementCoords SolidModel::current_coords(int e, const Vector& u) const {
  hex8::ElementCoords x = rest_coords_[e];
  const Hex8& nodes = mesh_.elements[e];
  for (int a = 0; a < 8; ++a) x.row(a) += u.segment<3>(3 * nodes[a]).transpose();
  return x;
}

void SolidModel::scatter(int e, double w, const ElementVector& force,
                         const ElementMatrix* stiffness, Vector& internal_force,
                         SymmetricMatrix* K) const {
  const Hex8& nodes = mesh_.elements[e];
  for (int a = 0; a < 8; ++a)
    internal_force.segment<3>(3 * nodes[a]) += w * force.segment<3>(3 * a);
  if (stiffness == nullptr) return;
  double* values = K->values().data();
  const auto& map = element_scatter_[e];
  for (int j = 0; j < 24; ++j) {  // column-major: K(i, j) runs down a contiguous column
    for (int i = 0; i < 24; ++i) {
      const int k = map[24 * i + j];
      if (k >= 0) values[k] += w * (*stiffness)(i, j);
    }
  }
}

bool SolidModel::element_force(int e, const Vector& u, ElementVector& force) const {
  ElementResponse r;
  if (!evaluate_element(geometry_.at(e), current_coords(e, u), *material_, formulation_, false, r))
    return false;
  force = r.force;
  return true;
}

AssemblyStatus SolidModel::add_weighted(const Vector& u, const std::vector<double>& weights,
                                        Vector& internal_force, SymmetricMatrix* stiffness,
                                        double* strain_energy) const {
  if (!weights.empty() && static_cast<int>(weights.size()) != mesh_.num_elements()) {
    throw std::invalid_argument("element weights: one per element expected");
  }
  if (all_batches_) return add_batches(u, weights, internal_force, stiffness, strain_energy);
  const bool want_stiffness = stiffness != nullptr;
  const auto weight = [&](int e) { return weights.empty() ? 1.0 : weights[e]; };
  AssemblyStatus status;
  status.min_J = std::numeric_limits<double>::infinity();

  if (!pool_) {
    ElementResponse r;
    for (int e = 0; e < mesh_.num_elements(); ++e) {
      const double w = weight(e);
      if (w == 0.0) continue;
      const bool ok = evaluate_element(geometry_[e], current_coords(e, u), *material_, formulation_,
                                       want_stiffness, r);
      status.min_J = std::min(status.min_J, r.min_J);
      if (!ok) {
        status.ok = false;
        status.inverted_element = e;
        return status;
      }
      if (strain_energy) *strain_energy += w * r.energy;
      scatter(e, w, r.force, want_stiffness ? &r.stiffness : nullptr, internal_force, stiffness);
    }
    return status;
  }

  // Several threads: each block's elements are evaluated in parallel into the workspace, then
  // summed here in element order, exactly as the loop above sums them.
  Workspace& ws = *workspace_;
  const std::lock_guard lock(ws.mutex);
  ws.elements.clear();
  for (int e = 0; e < mesh_.num_elements(); ++e)
    if (weight(e) != 0.0) ws.elements.push_back(e);
  const int total = static_cast<int>(ws.elements.size());
  const int block = std::min(total, kBlockElements);
  ws.force.resize(block);
  ws.energy.resize(block);
  ws.min_J.resize(block);
  ws.ok.resize(block);
  if (want_stiffness) ws.stiffness.resize(block);
  for (int first = 0; first < total; first += block) {
    const int count = std::min(block, total - first);
    pool_->parallel_for(count, [&](int begin, int end) {
      ElementResponse r;
      for (int i = begin; i < end; ++i) {
        const int e = ws.elements[first + i];
        ws.ok[i] = evaluate_element(geometry_[e], current_coords(e, u), *material_, formulation_,
                                    want_stiffness, r);
        ws.min_J[i] = r.min_J;
        if (!ws.ok[i]) continue;
        ws.energy[i] = r.energy;
        ws.force[i] = r.force;
        if (want_stiffness) ws.stiffness[i] = r.stiffness;
      }
    });
    for (int i = 0; i < count; ++i) {
      const int e = ws.elements[first + i];
      const double w = weight(e);
      status.min_J = std::min(status.min_J, ws.min_J[i]);
      if (!ws.ok[i]) {
        status.ok = false;
        status.inverted_element = e;
        return status;
      }
      if (strain_energy) *strain_energy += w * ws.energy[i];
      scatter(e, w, ws.force[i], want_stiffness ? &ws.stiffness[i] : nullptr, internal_force,
              stiffness);
    }
  }
  return status;
}

SolidModel::BatchLayout SolidModel::make_layout(std::vector<int> elements) const {
  BatchLayout layout;
  std::vector<ElementGeometry> lanes;
  for (std::size_t first = 0; first < elements.size(); first += kBatchLanes) {
    lanes.clear();
    for (std::size_t i = first; i < std::min(elements.size(), first + kBatchLanes); ++i)
      lanes.push_back(geometry_[elements[i]]);
    layout.batches.push_back(make_batch_geometry(lanes));
  }
  layout.elements = std::move(elements);
  return layout;
}

std::shared_ptr<const SolidModel::BatchLayout> SolidModel::layout_for(
    const std::vector<double>& weights) const {
  if (weights.empty()) return all_batches_;
  std::vector<int> weighted;
  int touched = 0;
  for (int first = 0; first < mesh_.num_elements(); first += kBatchLanes) {
    const std::size_t before = weighted.size();
    for (int e = first; e < std::min(mesh_.num_elements(), first + kBatchLanes); ++e)
      if (weights[e] != 0.0) weighted.push_back(e);
    touched += weighted.size() > before ? 1 : 0;
  }
  const int packed_count = static_cast<int>((weighted.size() + kBatchLanes - 1) / kBatchLanes);
  if (packed_count >= touched) return all_batches_;
  const std::lock_guard lock(packed_mutex_);
  if (!packed_ || packed_->elements != weighted)
    packed_ = std::make_shared<const BatchLayout>(make_layout(std::move(weighted)));
  return packed_;
}

BatchCoords SolidModel::batch_coords(const BatchLayout& layout, int b, const Vector& u) const {
  BatchCoords x;
  const int count = layout.batches[b].count;
  for (int l = 0; l < kBatchLanes; ++l) {
    // Lanes past count repeat the batch's first element, as its geometry does.
    const int e = layout.elements[kBatchLanes * b + (l < count ? l : 0)];
    const hex8::ElementCoords& X = rest_coords_[e];
    const Hex8& nodes = mesh_.elements[e];
    for (int a = 0; a < 8; ++a)
      for (int i = 0; i < 3; ++i) x[3 * a + i].lane[l] = X(a, i) + u[3 * nodes[a] + i];
  }
  return x;
}

bool SolidModel::add_batch_result(const BatchLayout& layout, int b, const ElementBatchResponse& r,
                                  const ElementBatchTangent* tangent,
                                  const std::vector<double>& weights, Vector& internal_force,
                                  SymmetricMatrix* K, double* strain_energy,
                                  AssemblyStatus& status) const {
  double* values = K ? K->values().data() : nullptr;
  for (int l = 0; l < layout.batches[b].count; ++l) {
    const int e = layout.elements[kBatchLanes * b + l];
    const double w = weights.empty() ? 1.0 : weights[e];
    if (w == 0.0) continue;
    status.min_J = std::min(status.min_J, r.min_J.lane[l]);
    if (!r.ok[l]) {
      status.ok = false;
      status.inverted_element = e;
      return false;
    }
    if (strain_energy) *strain_energy += w * r.energy.lane[l];
    const Hex8& nodes = mesh_.elements[e];
    for (int a = 0; a < 8; ++a)
      for (int i = 0; i < 3; ++i)
        internal_force[3 * nodes[a] + i] += w * r.force[3 * a + i].lane[l];
    if (values == nullptr) continue;
    for (int i = tangent_begin_[e]; i < tangent_begin_[e + 1]; ++i)
      values[tangent_value_[i]] += w * tangent->stiffness[tangent_source_[i]].lane[l];
  }
  return true;
}

namespace {

// The several-thread side of add_batches: the batches evaluated in parallel, a block at a time,
// into results (evaluate(b, result)), then added by the calling thread in batch order (add(b,
// result); false stops), exactly as one thread adds them.
template <class Result, class Evaluate, class Add>
void in_parallel_blocks(WorkerPool& pool, const std::vector<int>& batches,
                        std::vector<Result>& results, const Evaluate& evaluate, const Add& add) {
  const int total = static_cast<int>(batches.size());
  const int block = std::min(total, kBlockElements / kBatchLanes);
  results.resize(block);
  for (int first = 0; first < total; first += block) {
    const int count = std::min(block, total - first);
    pool.parallel_for(count, [&](int begin, int end) {
      for (int i = begin; i < end; ++i) evaluate(batches[first + i], results[i]);
    });
    for (int i = 0; i < count; ++i)
      if (!add(batches[first + i], results[i])) return;
  }
}

}  // namespace

AssemblyStatus SolidModel::add_batches(const Vector& u, const std::vector<double>& weights,
                                       Vector& internal_force, SymmetricMatrix* K,
                                       double* strain_energy) const {
  const UncoupledMaterial& material = *material_->as_uncoupled();
  AssemblyStatus status;
  status.min_J = std::numeric_limits<double>::infinity();
  const std::shared_ptr<const BatchLayout> held = layout_for(weights);
  const BatchLayout& layout = *held;
  // A batch whose elements all have weight 0 is skipped, as the element loop skips them.
  const auto active = [&](int b) {
    if (weights.empty()) return true;
    for (int l = 0; l < layout.batches[b].count; ++l)
      if (weights[layout.elements[kBatchLanes * b + l]] != 0.0) return true;
    return false;
  };
  const auto force = [&](int b, ElementBatchResponse& r) {
    evaluate_batch_force(layout.batches[b], batch_coords(layout, b, u), material, formulation_, r);
  };
  const auto tangent = [&](int b, ElementBatchTangent& t) {
    evaluate_batch_tangent(layout.batches[b], batch_coords(layout, b, u), material, formulation_,
                           t);
  };
  const auto add_force = [&](int b, const ElementBatchResponse& r) {
    return add_batch_result(layout, b, r, nullptr, weights, internal_force, nullptr, strain_energy,
                            status);
  };
  const auto add_tangent = [&](int b, const ElementBatchTangent& t) {
    return add_batch_result(layout, b, t.response, &t, weights, internal_force, K, strain_energy,
                            status);
  };
  const int num_batches = static_cast<int>(layout.batches.size());

  if (!pool_) {
    if (K == nullptr) {
      ElementBatchResponse r;
      for (int b = 0; b < num_batches; ++b) {
        if (!active(b)) continue;
        force(b, r);
        if (!add_force(b, r)) break;
      }
    } else {
      ElementBatchTangent t;
      for (int b = 0; b < num_batches; ++b) {
        if (!active(b)) continue;
        tangent(b, t);
        if (!add_tangent(b, t)) break;
      }
    }
    return status;
  }

  // Several threads: as in add_weighted, batches evaluated in parallel, summed here in order.
  Workspace& ws = *workspace_;
  const std::lock_guard lock(ws.mutex);
  ws.batches.clear();
  for (int b = 0; b < num_batches; ++b)
    if (active(b)) ws.batches.push_back(b);
  if (K == nullptr)
    in_parallel_blocks(*pool_, ws.batches, ws.batch_results, force, add_force);
  else
    in_parallel_blocks(*pool_, ws.batches, ws.batch_tangents, tangent, add_tangent);
  return status;
}

SymmetricMatrix SolidModel::mass_matrix(bool lumped) const {
  SymmetricMatrix M(pattern_);
  std::vector<double>& values = M.values();
  for (int e = 0; e < mesh_.num_elements(); ++e) {
    Eigen::Matrix<double, 8, 8> m =
        density_ * element_mass_pattern(element_coords(e, rest_positions_));
    if (lumped) {
      const Eigen::Matrix<double, 8, 1> row_sums = m.rowwise().sum();
      m = row_sums.asDiagonal();
    }
    const auto& scatter = element_scatter_[e];
    for (int a = 0; a < 8; ++a) {
      for (int b = 0; b < 8; ++b) {
        for (int c = 0; c < 3; ++c) {
          const int k = scatter[24 * (3 * a + c) + (3 * b + c)];
          if (k >= 0) values[k] += m(a, b);
        }
      }
    }
  }
  return M;
}

Vector SolidModel::body_force(const Vec3& acceleration) const {
  Vector f = Vector::Zero(num_dofs());
  for (int e = 0; e < mesh_.num_elements(); ++e) {
    const Eigen::Matrix<double, 8, 1> s = element_shape_integrals(geometry_[e]);
    const Hex8& nodes = mesh_.elements[e];
    for (int a = 0; a < 8; ++a) f.segment<3>(3 * nodes[a]) += density_ * s(a) * acceleration;
  }
  return f;
}


double SolidModel::total_mass() const {
  return density_ * reference_volume();
}

double SolidModel::current_volume(const Vector& u) const {
  // A boundary face x(s, t), bilinear over [0, 1]^2 in its corners a, b, c, d (cyclic), adds
  // int x . (x_s x x_t) ds dt, a polynomial in the corners that works out (expanded and
  // integrated term by term) to [a, b, c] + [a, b, d] + [a, c, d] + [b, c, d] over 4, the
  // brackets triple products: a . (b x (c + d)) + (a + b) . (c x d), over 4. The volume is a
  // third of the faces' sum (the divergence theorem with div x = 3). Positions are taken
  // relative to the first node's rest position, so that the face terms stay of the size of the
  // volume's and their sum loses little to cancellation.
  if (boundary_.empty()) return 0.0;
  const Vec3 origin = mesh_.nodes.front();
  double sum = 0.0;
  for (const Quad4& face : boundary_) {
    Vec3 x[4];
    for (int k = 0; k < 4; ++k) x[k] = mesh_.nodes[face[k]] - origin + u.segment<3>(3 * face[k]);
    sum += x[0].dot(x[1].cross(x[2] + x[3])) + (x[0] + x[1]).dot(x[2].cross(x[3]));
  }
  return sum / 12.0;
}

}  // namespace tongue::fem
