#include "model/tongue_muscles.hpp"

#include <algorithm>
#include <cmath>

namespace tongue::model {

const std::vector<MuscleGroup>& muscle_groups() {
  static const std::vector<MuscleGroup> groups = {
      {"GGp", 37.0, true}, {"GGm", 12.0, true}, {"GGa", 18.0, true}, {"HG", 65.0, true},
      {"SG", 24.0, true},  {"SL", 19.0, false}, {"IL", 9.0, true},   {"T", 50.0, true},
      {"V", 20.0, true},   {"MH", 39.0, true}};
  return groups;
}

namespace {

enum class Side { left, right, both };

// Grid index ranges are given on the base grid (12 x 6 x 5 per side) and scaled by the
// refinement, so that every muscle keeps its anatomical place at any resolution.
class Placer {
 public:
  Placer(const TongueGrid& grid, const BonyAttachments& bones) : g_(grid), bones_(bones) {}

  int m() const { return g_.refinement; }

  // Lateral node index `offset_fine` node layers (fine grid) from the midline on a side.
  int lateral(Side side, int offset_fine) const {
    return side == Side::right ? g_.midline() - offset_fine : g_.midline() + offset_fine;
  }
  fem::Vec3 mirrored(fem::Vec3 p, Side side) const {
    if (side == Side::right) p.z() = -p.z();
    return p;
  }

  // Elements with i in [i0, i1), j in [j0, j1) and lateral layers [l0, l1) from the midline on
  // the given side (both: the two sides), all in base-grid units.
  std::vector<int> elements(int i0, int i1, int j0, int j1, int l0, int l1, Side side) const {
    std::vector<int> out;
    for (int layer = l0 * m(); layer < l1 * m(); ++layer) {
      std::vector<int> ks;
      if (side != Side::right) ks.push_back(g_.midline() + layer);
      if (side != Side::left) ks.push_back(g_.midline() - layer - 1);
      for (int k : ks)
        for (int j = j0 * m(); j < j1 * m(); ++j)
          for (int i = i0 * m(); i < i1 * m(); ++i) out.push_back(g_.element(i, j, k));
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  // Node polylines along one grid direction between fine-grid indices (inclusive, either order).
  std::vector<int> along_i(int from, int to, int j, int k) const {
    return line(from, to, [&](int i) { return g_.node(i, j, k); });
  }
  std::vector<int> along_j(int from, int to, int i, int k) const {
    return line(from, to, [&](int j) { return g_.node(i, j, k); });
  }
  std::vector<int> along_k(int from, int to, int i, int j) const {
    return line(from, to, [&](int k) { return g_.node(i, j, k); });
  }

  // Nodes stepping along i from (i_from, j_from) to (i_to, j_to) with j interpolated: a path
  // across the fan's arcs, nearer a straight line than a grid line is.
  std::vector<int> diagonal(int i_from, int j_from, int i_to, int j_to, int k) const {
    std::vector<int> out;
    const int n = std::abs(i_to - i_from), step = i_to >= i_from ? 1 : -1;
    for (int t = 0; t <= n; ++t) {
      const int j = static_cast<int>(std::lround(j_from + (j_to - j_from) * double(t) / n));
      out.push_back(g_.node(i_from + step * t, j, k));
    }
    return out;
  }

  const BonyAttachments& bones() const { return bones_; }
  fem::Vec3 rest_position(int node) const { return g_.mesh.nodes[node]; }

 private:
  template <class F>
  static std::vector<int> line(int from, int to, F node) {
    std::vector<int> out;
    const int step = to >= from ? 1 : -1;
    for (int t = from;; t += step) {
      out.push_back(node(t));
      if (t == to) break;
    }
    return out;
  }
  const TongueGrid& g_;
  const BonyAttachments& bones_;
};

std::string half_name(const std::string& group, Side side) {
  if (side == Side::both) return group;
  return group + (side == Side::left ? "_left" : "_right");
}

// Genioglossus part: radial fibres from the mandibular insertion through the fan, in the
// midline layer, for the angular node lines [i0, i1) (base grid), below the SL layer.
void genioglossus(const Placer& p, Muscle& mu, int i0, int i1, Side side) {
  mu.elements = p.elements(i0, i1, 0, 5, 0, 1, side);
  for (int i = i0 * p.m(); i < i1 * p.m(); ++i)
    for (int off = 0; off <= p.m(); ++off)
      mu.fibres.push_back({p.along_j(1, 5 * p.m(), i, p.lateral(side, off)),
                           p.mirrored(p.bones().mandible_insertion, side), 1.0});
}

void place(const Placer& p, const std::string& group, Side side, Muscle& mu) {
  const int m = p.m();
  if (group == "GGa") return genioglossus(p, mu, 1, 4, side);
  if (group == "GGm") return genioglossus(p, mu, 4, 7, side);
  if (group == "GGp") return genioglossus(p, mu, 7, 12, side);
  if (group == "HG") {
    // Up the side of the back of the tongue from the hyoid's greater horn (sec. II.2.2).
    mu.elements = p.elements(9, 12, 2, 5, 3, 5, side);
    for (int j = 3 * m; j <= 4 * m; ++j)
      for (int off = 4 * m; off <= 5 * m; ++off)
        mu.fibres.push_back({p.along_i(12 * m, 9 * m, j, p.lateral(side, off)),
                             p.mirrored(p.bones().hyoid_greater_horn, side), 1.0});
    return;
  }
  if (group == "SG") {
    // From the styloid process into the side of the tongue at the back; one group runs forward
    // along the side to the tip, one inward to the midline (sec. II.2.3).
    mu.elements = p.elements(0, 9, 0, 6, 3, 5, side);
    const auto inward = p.elements(7, 9, 4, 6, 0, 5, side);
    mu.elements.insert(mu.elements.end(), inward.begin(), inward.end());
    std::sort(mu.elements.begin(), mu.elements.end());
    mu.elements.erase(std::unique(mu.elements.begin(), mu.elements.end()), mu.elements.end());
    const fem::Vec3 styloid = p.mirrored(p.bones().styloid_process, side);
    // The forward group follows the lateral margin: fairly straight paths from the entry high at
    // the back to the side of the tip, not the dorsum's arc. Each fibre enters at its own node so
    // that the pull of the styloid is spread, not concentrated on one node.
    for (int j = 3 * m; j <= 5 * m; ++j)
      for (int off = 3 * m; off <= 5 * m; ++off)
        mu.fibres.push_back(
            {p.diagonal(8 * m, j, 1 * m, j - 3 * m, p.lateral(side, off)), styloid, 1.0});
    for (int j = 4 * m; j <= 5 * m; ++j)
      mu.fibres.push_back(
          {p.along_k(p.lateral(side, 5 * m), p.lateral(side, 0), 8 * m, j), styloid, 1.0});
    return;
  }
  if (group == "SL") {
    // Under the dorsum from the low pharynx to the tip, across the whole width (sec. II.2.4).
    mu.elements = p.elements(0, 11, 5, 6, 0, 5, Side::both);
    for (int off = -5 * m; off <= 5 * m; ++off)
      mu.fibres.push_back({p.along_i(11 * m, 0, 6 * m, p.lateral(Side::left, off)), {}, 1.0});
    return;
  }
  if (group == "IL") {
    // Low in the body, from the underside of the tip back to the root and on to the hyoid,
    // beside the genioglossus (sec. II.2.5); kept away from the small elements at the insertion.
    mu.elements = p.elements(0, 12, 2, 4, 1, 3, side);
    // Nine fibres ending at distinct nodes under the tip: the pull spread over the insertion.
    for (int j = 2 * m; j <= 4 * m; ++j)
      for (int off = 1 * m; off <= 3 * m; ++off)
        mu.fibres.push_back({p.along_i(12 * m, 0, j, p.lateral(side, off)),
                             p.mirrored(p.bones().hyoid_body, side), 1.0});
    return;
  }
  if (group == "T") {
    // From the midline septum out to the margins, through the tongue body (sec. II.2.6).
    mu.elements = p.elements(1, 10, 1, 5, 0, 5, side);
    for (int i = 1 * m; i <= 10 * m; ++i)
      for (int j = 1 * m; j <= 5 * m; ++j)
        mu.fibres.push_back({p.along_k(p.lateral(side, 0), p.lateral(side, 5 * m), i, j), {}, 1.0});
    return;
  }
  if (group == "V") {
    // From the underside up to the dorsum, tip to mid-tongue, none near the midline
    // (sec. II.2.7); radial lines within about 40 degrees of vertical.
    mu.elements = p.elements(0, 6, 1, 6, 2, 5, side);
    for (int i = 0; i <= 6 * m; ++i)
      for (int off = 2 * m; off <= 5 * m; ++off)
        mu.fibres.push_back({p.along_j(1 * m, 6 * m, i, p.lateral(side, off)), {}, 1.0});
    return;
  }
  if (group == "MH") {
    // The floor behind the insertion, fibres from the mandible's inner side to the midline
    // (sec. II.2.8; Netter 1989): the floor hangs between the two mandible attachments, which lie
    // beside and a little above it, so the muscle lifts the floor as it shortens.
    mu.elements = p.elements(11, 12, 0, 4, 0, 5, side);
    for (int j = 1 * m; j <= 4 * m; ++j) {
      const std::vector<int> nodes =
          p.along_k(p.lateral(side, 5 * m), p.lateral(side, 0), 12 * m, j);
      fem::Vec3 attachment = p.rest_position(nodes.front());
      attachment.y() += p.bones().mylohyoid_line_rise;
      attachment.z() += (side == Side::right ? -1.0 : 1.0) * p.bones().mylohyoid_line_offset;
      mu.fibres.push_back({nodes, attachment, 1.0});
    }
    return;
  }
}

}  // namespace

std::vector<Muscle> place_muscles(const TongueGrid& grid, const BonyAttachments& bones) {
  const Placer placer(grid, bones);
  std::vector<Muscle> muscles;
  for (const MuscleGroup& group : muscle_groups()) {
    const std::vector<Side> sides =
        group.paired ? std::vector<Side>{Side::left, Side::right} : std::vector<Side>{Side::both};
    for (Side side : sides) {
      Muscle mu;
      mu.name = half_name(group.name, side);
      mu.max_force = group.paired ? 0.5 * group.max_force : group.max_force;
      place(placer, group.name, side, mu);
      normalize_weights(mu);
      validate(mu, grid.mesh.num_nodes(), grid.mesh.num_elements());
      muscles.push_back(std::move(mu));
    }
  }
  return muscles;
}

}  // namespace tongue::model
