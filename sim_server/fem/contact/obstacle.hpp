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

// What the closest point of the surface to x says about x.
struct SurfacePoint {
  bool valid = false;          // false: the closest point lies on the rim of an open surface
  double distance = 0.0;       // signed distance phi [m]: negative inside (behind the surface)
  Vec3 point = Vec3::Zero();   // closest point on the surface [m]
  Vec3 normal = Vec3::Zero();  // n = grad phi, unit
  // phi d(n)/dx: zero where the closest point lies inside a triangle (n is that triangle's
  // normal), I - n n^T - t t^T on an edge of unit direction t, I - n n^T at a vertex. The
  // Hessian of phi^2 / 2 is n n^T + this.
  Mat3 curvature = Mat3::Zero();
  int triangle = -1;  // the triangle that holds the closest point
  int edge = -1;      // on an edge of it: the edge, opposite its vertex edge (0, 1, 2)
  int vertex = -1;    // at a vertex: the vertex (an index into the surface's vertices)
};

class Obstacle {
 public:
  // Checks the surface and builds its spatial index. Throws std::invalid_argument when it has no
  // triangle, an index out of range, a degenerate triangle (area below 1e-12 of the squared
  // bounding-box diagonal), an edge shared by more than two triangles, two neighbours with
  // opposite orientations, or, closed, a negative enclosed volume (normals pointing inward).
  Obstacle(std::string name, TriangleSurface surface);
  ~Obstacle();
  Obstacle(const Obstacle&) = delete;
  Obstacle& operator=(const Obstacle&) = delete;

  const std::string& name() const { return name_; }
  const TriangleSurface& surface() const { return surface_; }
  bool closed() const { return closed_; }
  // Corners of the axis-aligned bounding box [m].
  const Vec3& box_min() const { return box_min_; }
  const Vec3& box_max() const { return box_max_; }
  // Distance from x to the bounding box (0 inside it) [m]: a lower bound of |phi(x)|, for
  // skipping the tree query of points far away.
  double box_distance(const Vec3& x) const;

  SurfacePoint closest(const Vec3& x) const;

  // Where the surface folds concavely seen from its free side, by at least min_fold [rad] (the
  // angle between the two facets' normals), a point x behind it lies behind both sides of the
  // fold, the free side there being the intersection of theirs. Its closest point is then on
  // the fold's edge or vertex, and its normal swings round the fold's angle as x moves by less
  // than its depth. So the surface near s (x's closest point, behind it) is cut at its sharp
  // concave folds into sides, and x holds each side on its own: the side's closest point, found
  // as closest() does, except that where it lies on the side's fold the side goes on past it in
  // the plane of its facet there (at a vertex of the fold, of the fold's edge there that x is
  // least far past). Replaces points with a point per side (distance, normal and curvature; a
  // plane's curvature is zero), or with s alone where nothing near s folds that sharply.
  // A side with x in front of it counts nothing (the caller keeps the points behind).
  void fold_points(const Vec3& x, const SurfacePoint& s, double min_fold,
                   std::vector<SurfacePoint>& points) const;
  // The signed distance of x to triangle t's plane [m] (negative behind it) and its normal.
  double plane_distance(int t, const Vec3& x) const {
    return face_normal_[t].dot(x - surface_.vertices[surface_.triangles[t][0]]);
  }
  const Vec3& face_normal(int t) const { return face_normal_[t]; }

 private:
  struct Index;  // the CGAL tree, kept out of this header
  std::string name_;
  TriangleSurface surface_;
  bool closed_ = false;
  Vec3 box_min_, box_max_;
  double on_surface_ = 0.0;  // [m]: closer than this, x counts as on the surface (normal undefined)
  std::vector<Vec3> face_normal_;
  std::vector<std::array<Vec3, 3>> edge_normal_;  // [triangle][edge opposite vertex k]
  std::vector<std::array<bool, 3>> rim_edge_;     // edge of one triangle only
  std::vector<std::array<int, 3>> neighbour_;     // the triangle across each edge, -1 on the rim
  // The angle between the normals of the two triangles at each edge [rad] where the surface
  // folds concavely there seen from its free side (each one's far vertex in front of the
  // other's plane), 0 where it folds convexly or ends.
  std::vector<std::array<double, 3>> concave_fold_;
  std::vector<std::vector<int>> vertex_triangles_;  // the triangles around each vertex
  std::vector<Vec3> vertex_normal_;
  std::vector<bool> rim_vertex_;
  std::unique_ptr<Index> index_;
};

}  // namespace tongue::fem
