#include "fem/contact/obstacle.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

namespace tongue::fem {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
}  // namespace

struct Obstacle::Index {
  using Triangles = std::vector<Kernel::Triangle_3>;
  using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

  Triangles triangles;  // must outlive the tree, which holds iterators into it
  Tree tree;
};

namespace {

Kernel::Point_3 to_point(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

std::string where(const std::string& name) {
  return "obstacle '" + name + "': ";
}

// The closest point of triangle (a, b, c) to p and the feature that holds it, found by testing
// p against the Voronoi regions of the vertices, then the edges, then the face (Ericson 2005,
// Real-Time Collision Detection, sec. 5.1.5).
struct TrianglePoint {
  enum class Feature { face, edge, vertex };
  Feature feature = Feature::face;
  int index = 0;  // the vertex (0, 1, 2), or the edge opposite vertex index
  Vec3 point;
};

TrianglePoint closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  using F = TrianglePoint::Feature;
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {F::vertex, 0, a};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {F::vertex, 1, b};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return {F::edge, 2, a + (d1 / (d1 - d3)) * ab};
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {F::vertex, 2, c};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return {F::edge, 1, a + (d2 / (d2 - d6)) * ac};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
    return {F::edge, 0, b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b)};
  const double denominator = 1.0 / (va + vb + vc);
  return {F::face, 0, a + ab * (vb * denominator) + ac * (vc * denominator)};
}

}  // namespace

Obstacle::Obstacle(std::string name, TriangleSurface surface, Normals normals)
    : name_(std::move(name)), surface_(std::move(surface)), normals_(normals) {
  const auto& V = surface_.vertices;
  const auto& T = surface_.triangles;
  const int nv = static_cast<int>(V.size()), nt = static_cast<int>(T.size());
  if (nt == 0) throw std::invalid_argument(where(name_) + "no triangles");
  for (int t = 0; t < nt; ++t)
    for (int k : T[t])
      if (k < 0 || k >= nv) {
        throw std::invalid_argument(where(name_) + "triangle " + std::to_string(t) +
                                    " has vertex index " + std::to_string(k) + " out of 0.." +
                                    std::to_string(nv - 1));
      }
  box_min_ = box_max_ = V[T[0][0]];
  for (const auto& tri : T)
    for (int k : tri) {
      box_min_ = box_min_.cwiseMin(V[k]);
      box_max_ = box_max_.cwiseMax(V[k]);
    }
  const double diagonal2 = (box_max_ - box_min_).squaredNorm();
  on_surface_ = 1e-12 * std::sqrt(diagonal2);

  // Face normals; a degenerate triangle has none.
  face_normal_.resize(nt);
  for (int t = 0; t < nt; ++t) {
    const Vec3 twice_area = (V[T[t][1]] - V[T[t][0]]).cross(V[T[t][2]] - V[T[t][0]]);
    if (!(0.5 * twice_area.norm() > 1e-12 * diagonal2)) {
      throw std::invalid_argument(where(name_) + "triangle " + std::to_string(t) +
                                  " is degenerate (zero area, or vertices on one line)");
    }
    face_normal_[t] = twice_area.normalized();
  }

  // Edges: each undirected edge with the triangles that use it, and in which direction.
  struct EdgeUse {
    int triangle, opposite;  // the triangle and its vertex opposite the edge
    bool forward;            // traversed from the smaller to the larger vertex index
  };
  std::map<std::pair<int, int>, std::vector<EdgeUse>> edges;
  for (int t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = T[t][(k + 1) % 3], b = T[t][(k + 2) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back({t, k, a < b});
    }
  }
  closed_ = true;
  edge_normal_.resize(nt);
  rim_edge_.assign(nt, {false, false, false});
  rim_vertex_.assign(nv, false);
  for (const auto& [edge, uses] : edges) {
    const std::string edge_name = "the edge between vertices " + std::to_string(edge.first) +
                                  " and " + std::to_string(edge.second);
    if (uses.size() > 2) {
      throw std::invalid_argument(where(name_) + std::to_string(uses.size()) + " triangles share " +
                                  edge_name + " (not a surface)");
    }
    if (uses.size() == 2 && uses[0].forward == uses[1].forward) {
      throw std::invalid_argument(where(name_) + "triangles " + std::to_string(uses[0].triangle) +
                                  " and " + std::to_string(uses[1].triangle) +
                                  " are oriented oppositely across " + edge_name);
    }
    Vec3 n = Vec3::Zero();
    for (const EdgeUse& u : uses) n += face_normal_[u.triangle];
    for (const EdgeUse& u : uses) {
      edge_normal_[u.triangle][u.opposite] = n.normalized();
      rim_edge_[u.triangle][u.opposite] = uses.size() == 1;
    }
    if (uses.size() == 1) {
      closed_ = false;
      rim_vertex_[edge.first] = rim_vertex_[edge.second] = true;
    }
  }

  // Vertex pseudo-normals: incident face normals weighted by the incident angles.
  vertex_normal_.assign(nv, Vec3::Zero());
  for (int t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = V[T[t][k]];
      const Vec3 e1 = V[T[t][(k + 1) % 3]] - p, e2 = V[T[t][(k + 2) % 3]] - p;
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      vertex_normal_[T[t][k]] += angle * face_normal_[t];
    }
  }
  for (Vec3& n : vertex_normal_)
    if (n.norm() > 0.0) n.normalize();

  if (closed_) {
    double volume = 0.0;  // divergence theorem: sum of a . (b x c) / 6
    for (const auto& tri : T) volume += V[tri[0]].dot(V[tri[1]].cross(V[tri[2]])) / 6.0;
    if (volume < 0.0) {
      throw std::invalid_argument(
          where(name_) + "closed surface with inward normals (enclosed volume " +
          std::to_string(volume * 1e6) + " cm^3 < 0): reverse the triangles' vertex order");
    }
  }

  index_ = std::make_unique<Index>();
  index_->triangles.reserve(nt);
  for (const auto& tri : T)
    index_->triangles.emplace_back(to_point(V[tri[0]]), to_point(V[tri[1]]), to_point(V[tri[2]]));
  index_->tree.insert(index_->triangles.cbegin(), index_->triangles.cend());
  index_->tree.build();
  index_->tree.accelerate_distance_queries();
}

Obstacle::~Obstacle() = default;

double Obstacle::box_distance(const Vec3& x) const {
  const Vec3 outside = (box_min_ - x).cwiseMax(x - box_max_).cwiseMax(0.0);
  return outside.norm();
}

void Obstacle::smooth_normal(int t, const Vec3& x, SurfacePoint& s) const {
  // n = sum_i l_i N_i normalized, N_i the triangle's vertex normals and l_i the barycentric
  // coordinates of the closest point: l_i = (a x e_i) . (point - v_{i+1}) / |a|^2, with a the
  // triangle's area vector and e_i = v_{i+2} - v_{i+1} its edge opposite vertex i.
  const auto& tri = surface_.triangles[t];
  const auto& V = surface_.vertices;
  const Vec3 area = (V[tri[1]] - V[tri[0]]).cross(V[tri[2]] - V[tri[0]]);
  Vec3 n = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    const Vec3 edge = V[tri[(i + 2) % 3]] - V[tri[(i + 1) % 3]];
    n += area.cross(edge).dot(s.point - V[tri[(i + 1) % 3]]) * vertex_normal_[tri[i]];
  }
  // Vertex normals that cancel (a surface folded back on itself) leave the faceted normal.
  if (!(n.norm() > 1e-6 * area.squaredNorm())) return;
  s.normal = n.normalized();
  s.gap = (x - s.point).dot(s.normal);
  s.curvature = Mat3::Zero();
}

SurfacePoint Obstacle::closest(const Vec3& x, int hint_triangle, const Vec3& hint_point) const {
  const auto hit =
      hint_triangle < 0
          ? index_->tree.closest_point_and_primitive(to_point(x))
          : index_->tree.closest_point_and_primitive(
                to_point(x), {to_point(hint_point), index_->triangles.cbegin() + hint_triangle});
  return closest_on(x, static_cast<int>(hit.second - index_->triangles.cbegin()));
}

std::vector<int> Obstacle::triangles_near(const Vec3& center, double half_width) const {
  const Vec3 low = center.array() - half_width, high = center.array() + half_width;
  std::vector<Index::Primitive::Id> hits;
  index_->tree.all_intersected_primitives(
      CGAL::Bbox_3(low.x(), low.y(), low.z(), high.x(), high.y(), high.z()),
      std::back_inserter(hits));
  std::vector<int> triangles;
  triangles.reserve(hits.size());
  for (const auto& id : hits)
    triangles.push_back(static_cast<int>(id - index_->triangles.cbegin()));
  return triangles;
}

Obstacle::Nearest Obstacle::nearest_among(const Vec3& x, const std::vector<int>& triangles) const {
  const auto& V = surface_.vertices;
  Nearest n{-1, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  for (int t : triangles) {
    const auto& tri = surface_.triangles[t];
    const double d = (x - closest_on_triangle(x, V[tri[0]], V[tri[1]], V[tri[2]]).point).norm();
    if (d < n.distance) {
      n.next = n.distance;
      n.distance = d;
      n.triangle = t;
    } else {
      n.next = std::min(n.next, d);
    }
  }
  return n;
}

SurfacePoint Obstacle::closest_on(const Vec3& x, int t) const {
  const auto& tri = surface_.triangles[t];
  const auto& V = surface_.vertices;
  const TrianglePoint on = closest_on_triangle(x, V[tri[0]], V[tri[1]], V[tri[2]]);
  const bool smooth = normals_ == Normals::smooth;

  SurfacePoint s;
  s.triangle = t;
  s.point = on.point;
  const Vec3 offset = x - on.point;
  if (on.feature == TrianglePoint::Feature::face) {
    // Inside the triangle x - point is along the normal, which is constant there.
    s.valid = true;
    s.normal = face_normal_[t];
    s.distance = s.gap = offset.dot(s.normal);
    if (smooth) smooth_normal(t, x, s);
    return s;
  }
  const bool edge = on.feature == TrianglePoint::Feature::edge;
  const bool rim = edge ? rim_edge_[t][on.index] : static_cast<bool>(rim_vertex_[tri[on.index]]);
  const Vec3& pseudo = edge ? edge_normal_[t][on.index] : vertex_normal_[tri[on.index]];
  const double d = offset.norm();
  const double sign = offset.dot(pseudo) < 0.0 ? -1.0 : 1.0;
  s.distance = sign * d;
  if (rim && !closed_) return s;  // beyond the rim of a sheet: neither in front nor behind it
  s.valid = true;
  s.gap = s.distance;
  // On the surface itself the direction of x - point is undefined; the pseudo-normal stands in.
  s.normal = d > on_surface_ ? (sign / d) * offset : pseudo;
  s.curvature = Mat3::Identity() - s.normal * s.normal.transpose();
  if (edge) {
    const Vec3 along = (V[tri[(on.index + 2) % 3]] - V[tri[(on.index + 1) % 3]]).normalized();
    s.curvature -= along * along.transpose();
  }
  if (smooth) smooth_normal(t, x, s);
  return s;
}

}  // namespace tongue::fem
