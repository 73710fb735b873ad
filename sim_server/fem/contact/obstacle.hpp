#pragma once
// A rigid obstacle: a triangle surface that the solid's nodes may not pass. Its triangles'
// normals (right-hand rule on the vertex order) point to the free side, the side the solid is on.
// A closed surface (every edge shared by two triangles) bounds a solid with outward normals; an
// open one (a palate, a wall) is a sheet whose back side counts as inside only where the
// closest point lies within the sheet, not on its rim.
//
// The signed distance phi(x) and its gradient, the outward unit normal n, come from the closest
// point on the surface, found with an AABB tree (CGAL). The sign of a point whose closest point
// is an edge or a vertex comes from the angle-weighted pseudo-normal there (Baerentzen & Aanaes
// 2005, IEEE TVCG 11(3)), which gives the right sign at every feature of a closed, consistently
// oriented surface.
#include <Eigen/Geometry>  // cross products, unitOrthogonal
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "fem/types.hpp"

namespace tongue::fem {

struct TriangleSurface {
  std::vector<Vec3> vertices;                 // m
  std::vector<std::array<int, 3>> triangles;  // vertex indices, counter-clockwise seen from outside
};

// How an obstacle's surface turns its normal. Faceted: n is the gradient of the distance to the
// triangles, constant over a triangle and turning about an edge or a vertex as fast as 1/|phi|.
// Smooth: n is the vertex normals interpolated over the triangle at the closest point (Phong
// normals), for a surface that samples a smooth one (a palate), so that the direction of a
// node's contact force turns as slowly as the sampled surface does.
enum class Normals { faceted, smooth };

// What the closest point of the surface to x says about x.
struct SurfacePoint {
  bool valid = false;  // false: the closest point lies on the rim of an open surface
  // Signed distance phi [m]: negative inside (behind the surface). Not valid: the distance to the
  // rim, negative on the back side of the rim's pseudo-normal.
  double distance = 0.0;
  Vec3 point = Vec3::Zero();   // closest point on the surface [m]
  Vec3 normal = Vec3::Zero();  // n, unit: grad phi (faceted), the interpolated normal (smooth)
  // g = (x - point) . n [m], the gap a contact force acts on: phi faceted; smooth, within a
  // triangle phi (n . n_face), which differs from phi by the angle between the two normals.
  double gap = 0.0;
  // Faceted: phi d(n)/dx, zero where the closest point lies inside a triangle (n is that
  // triangle's normal), I - n n^T - t t^T on an edge of unit direction t, I - n n^T at a vertex.
  // The Hessian of phi^2 / 2 is n n^T + this. Zero when smooth.
  Mat3 curvature = Mat3::Zero();
  int triangle = -1;  // the triangle that holds the closest point
};

class Obstacle {
 public:
  // Checks the surface and builds its spatial index. Throws std::invalid_argument when it has no
  // triangle, an index out of range, a degenerate triangle (area below 1e-12 of the squared
  // bounding-box diagonal), an edge shared by more than two triangles, two neighbours with
  // opposite orientations, or, closed, a negative enclosed volume (normals pointing inward).
  Obstacle(std::string name, TriangleSurface surface, Normals normals = Normals::faceted);
  ~Obstacle();
  Obstacle(const Obstacle&) = delete;
  Obstacle& operator=(const Obstacle&) = delete;

  const std::string& name() const { return name_; }
  const TriangleSurface& surface() const { return surface_; }
  bool closed() const { return closed_; }
  Normals normals() const { return normals_; }
  // Corners of the axis-aligned bounding box [m].
  const Vec3& box_min() const { return box_min_; }
  const Vec3& box_max() const { return box_max_; }
  // Distance from x to the bounding box (0 inside it) [m]: a lower bound of |phi(x)|, for
  // skipping the tree query of points far away.
  double box_distance(const Vec3& x) const;

  // hint: a triangle near x (its index, -1 for none) and a point on it; the closer it is to the
  // closest point, the less of the tree the query visits. The result does not depend on it.
  SurfacePoint closest(const Vec3& x, int hint_triangle = -1,
                       const Vec3& hint_point = Vec3::Zero()) const;

  // What the closest point of x on triangle t says about x: closest(x) when t is the triangle
  // nearest to x.
  SurfacePoint closest_on(const Vec3& x, int t) const;
  // The triangles that meet the cube of half-width `half_width` round `center`, from the tree.
  // Every other triangle is at least half_width from center.
  std::vector<int> triangles_near(const Vec3& center, double half_width) const;
  // The nearest of `triangles` to x, its distance and the next nearest one's [m] (infinity when
  // there is none).
  struct Nearest {
    int triangle = -1;
    double distance = 0.0, next = 0.0;
  };
  Nearest nearest_among(const Vec3& x, const std::vector<int>& triangles) const;

 private:
  struct Index;  // the CGAL tree, kept out of this header
  // The smooth normal at s.point of triangle t, and the gap of x along it, into s.
  void smooth_normal(int t, const Vec3& x, SurfacePoint& s) const;
  std::string name_;
  TriangleSurface surface_;
  bool closed_ = false;
  Normals normals_ = Normals::faceted;
  Vec3 box_min_, box_max_;
  double on_surface_ = 0.0;  // [m]: closer than this, x counts as on the surface (normal undefined)
  std::vector<Vec3> face_normal_;
  std::vector<std::array<Vec3, 3>> edge_normal_;  // [triangle][edge opposite vertex k]
  std::vector<std::array<bool, 3>> rim_edge_;     // edge of one triangle only
  std::vector<Vec3> vertex_normal_;
  std::vector<bool> rim_vertex_;
  std::unique_ptr<Index> index_;
};

}  // namespace tongue::fem
