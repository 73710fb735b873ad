#include "model/vocal_tract.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "model/tongue_geometry.hpp"

namespace tongue::model {

namespace {

using fem::Vec3;

// Outward unit normals at the grid's boundary nodes: the sum of the normals of the boundary faces
// around each node, each pointing away from its element's centre, weighted by face area.
std::vector<Vec3> outward_normals(const TongueGrid& grid) {
  const fem::Mesh& mesh = grid.mesh;
  const GridSize& g = grid.size;
  std::vector<Vec3> normal(mesh.nodes.size(), Vec3::Zero());
  for (int k = 0; k < g.lateral; ++k)
    for (int j = 0; j < g.radial; ++j)
      for (int i = 0; i < g.angular; ++i) {
        Vec3 centre = Vec3::Zero();
        for (int n : mesh.elements[grid.element(i, j, k)]) centre += mesh.nodes[n] / 8.0;
        // The element's faces on the boundary, each as four corners in cyclic order.
        std::vector<std::array<int, 4>> faces;
        const auto quad = [&](std::array<std::array<int, 3>, 4> c) {
          faces.push_back(
              {grid.node(c[0][0], c[0][1], c[0][2]), grid.node(c[1][0], c[1][1], c[1][2]),
               grid.node(c[2][0], c[2][1], c[2][2]), grid.node(c[3][0], c[3][1], c[3][2])});
        };
        for (int side : {0, 1}) {
          const int ii = i + side, jj = j + side, kk = k + side;
          if ((side == 0 && i == 0) || (side == 1 && i + 1 == g.angular))
            quad({{{ii, j, k}, {ii, j + 1, k}, {ii, j + 1, k + 1}, {ii, j, k + 1}}});
          if ((side == 0 && j == 0) || (side == 1 && j + 1 == g.radial))
            quad({{{i, jj, k}, {i + 1, jj, k}, {i + 1, jj, k + 1}, {i, jj, k + 1}}});
          if ((side == 0 && k == 0) || (side == 1 && k + 1 == g.lateral))
            quad({{{i, j, kk}, {i + 1, j, kk}, {i + 1, j + 1, kk}, {i, j + 1, kk}}});
        }
        for (const auto& f : faces) {
          Vec3 area =
              (mesh.nodes[f[2]] - mesh.nodes[f[0]]).cross(mesh.nodes[f[3]] - mesh.nodes[f[1]]);
          Vec3 face_centre = Vec3::Zero();
          for (int n : f) face_centre += mesh.nodes[n] / 4.0;
          if (area.dot(face_centre - centre) < 0.0) area = -area;
          for (int n : f) normal[n] += area;
        }
      }
  for (Vec3& n : normal)
    if (n.norm() > 0.0) n.normalize();
  return normal;
}

// A rows x cols grid of points on a sheet, each with the tongue's outward normal where it was
// taken from (the sheet faces the other way, toward the tongue).
struct SheetGrid {
  struct Point {
    Vec3 at, outward;
  };
  int rows = 0, cols = 0;
  std::vector<Point> points;  // row-major
  int id(int r, int c) const { return r * cols + c; }
  const Point& operator()(int r, int c) const { return points[id(r, c)]; }
};

// The grid over a rows x cols patch of boundary nodes, each moved out along its normal by the gap
// of its row.
SheetGrid offset_grid(const TongueGrid& grid, const std::vector<Vec3>& normal, int rows, int cols,
                      const std::function<int(int, int)>& node,
                      const std::function<double(int)>& gap) {
  SheetGrid s{rows, cols, {}};
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int n = node(r, c);
      s.points.push_back({grid.mesh.nodes[n] + gap(r) * normal[n], normal[n]});
    }
  return s;
}

// s with a skirt: a column added before the first (first) or after the last (last), each point
// carried on by length along the line its row's last two points make. Where two sheets meet at
// their rims (the palate's lateral edge is the teeth's upper one), their skirts cross, so that a
// node cannot pass between them: beyond a rim an open sheet has no inside.
SheetGrid with_skirt(const SheetGrid& s, bool first, bool last, double length) {
  SheetGrid out{s.rows, s.cols + (first ? 1 : 0) + (last ? 1 : 0), {}};
  const auto carried = [&](int r, int edge, int inner) {
    SheetGrid::Point p = s(r, edge);
    p.at += length * (p.at - s(r, inner).at).normalized();
    return p;
  };
  for (int r = 0; r < s.rows; ++r) {
    if (first) out.points.push_back(carried(r, 0, 1));
    for (int c = 0; c < s.cols; ++c) out.points.push_back(s(r, c));
    if (last) out.points.push_back(carried(r, s.cols - 1, s.cols - 2));
  }
  return out;
}

// s with rows and columns swapped.
SheetGrid transposed(const SheetGrid& s) {
  SheetGrid out{s.cols, s.rows, {}};
  for (int c = 0; c < s.cols; ++c)
    for (int r = 0; r < s.rows; ++r) out.points.push_back(s(r, c));
  return out;
}

// The grid's quads split into triangles, all wound alike, turned so that most of them face the
// tongue. (One turn for the whole sheet: a skirt's quad, bent away from the tongue's normals it
// carries, could otherwise be turned alone and disagree with its neighbours.)
fem::TriangleSurface triangulate(const SheetGrid& s) {
  fem::TriangleSurface out;
  for (const SheetGrid::Point& p : s.points) out.vertices.push_back(p.at);
  int away = 0;  // triangles facing away from the tongue, less those facing it
  for (int r = 0; r + 1 < s.rows; ++r)
    for (int c = 0; c + 1 < s.cols; ++c) {
      out.triangles.push_back({s.id(r, c), s.id(r + 1, c), s.id(r + 1, c + 1)});
      out.triangles.push_back({s.id(r, c), s.id(r + 1, c + 1), s.id(r, c + 1)});
      const Vec3 n = (s(r + 1, c + 1).at - s(r, c).at).cross(s(r, c + 1).at - s(r, c).at);
      away += n.dot(s(r, c).outward + s(r + 1, c + 1).outward) > 0.0 ? 1 : -1;
    }
  if (away > 0)
    for (auto& t : out.triangles) std::swap(t[1], t[2]);
  return out;
}

// A sheet over a rows x cols patch of boundary nodes (offset_grid), triangulated.
fem::TriangleSurface offset_sheet(const TongueGrid& grid, const std::vector<Vec3>& normal, int rows,
                                  int cols, const std::function<int(int, int)>& node,
                                  const std::function<double(int)>& gap) {
  return triangulate(offset_grid(grid, normal, rows, cols, node, gap));
}

fem::TriangleSurface join(fem::TriangleSurface a, const fem::TriangleSurface& b) {
  const int offset = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto t : b.triangles) a.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  return a;
}

}  // namespace

std::vector<std::shared_ptr<const fem::Obstacle>> make_vocal_tract(const VocalTractGaps& gaps) {
  constexpr int kRefinement = 4;
  // How far the palate and the teeth go on past the edge where they meet [m]: beyond the other
  // sheet (3 mm from the tongue there), so that the two cross.
  constexpr double kSkirt = 0.003;
  const TongueGrid grid = make_tongue_grid(default_tongue_shape(), kRefinement);
  const std::vector<Vec3> normal = outward_normals(grid);
  const GridSize& g = grid.size;
  const int R = g.radial, K = g.lateral, mid = grid.midline();
  // Fractions of the angular range (tip 0 .. root 1) and of the radius, as grid indices.
  const auto at = [](double fraction, int count) {
    return static_cast<int>(std::lround(fraction * count));
  };

  // Hard palate and alveolar ridge: up the front face from 55 % of the radius to the tip, then
  // back over the dorsum to 40 % of the angular range; every lateral layer. The ridge (the front
  // face and the first 8 % of the dorsum) at its own gap, the vault behind it at the palate's,
  // blended over the next 8 %.
  const int front_rows = R - at(0.55, R);
  const int palate_end = at(0.40, g.angular);
  const double ridge_end = front_rows + 0.08 * g.angular, blend = 0.08 * g.angular;
  // Skirted on both lateral edges, where it meets the teeth.
  auto palate = triangulate(
      with_skirt(offset_grid(
                     grid, normal, front_rows + palate_end + 1, K + 1,
                     [&](int r, int c) {
                       return r < front_rows ? grid.node(0, at(0.55, R) + r, c)
                                             : grid.node(r - front_rows, R, c);
                     },
                     [&](int r) {
                       const double t = std::clamp((r - ridge_end) / blend, 0.0, 1.0);
                       return gaps.alveolar_ridge + t * (gaps.hard_palate - gaps.alveolar_ridge);
                     }),
                 true, true, kSkirt));

  // Upper teeth: both sides of the front 40 %, from half the radius to the dorsum, skirted on
  // the upper edge and the front one, where they meet the palate (over the dorsum and down the
  // front face).
  const int teeth_rows = palate_end + 1, teeth_cols = R - at(0.5, R) + 1;
  const auto side = [&](int k) {
    const SheetGrid teeth = offset_grid(
        grid, normal, teeth_rows, teeth_cols,
        [&, k](int r, int c) { return grid.node(r, at(0.5, R) + c, k); },
        [&](int) { return gaps.upper_teeth; });
    return triangulate(
        with_skirt(transposed(with_skirt(teeth, false, true, kSkirt)), true, false, kSkirt));
  };
  auto teeth = join(side(0), side(K));

  // Velum: the dorsum from 36 % to 62 % of the angular range, the middle 60 % of the width.
  const int velum_begin = at(0.36, g.angular), velum_end = at(0.62, g.angular);
  const int half = at(0.3, K);
  auto velum = offset_sheet(
      grid, normal, velum_end - velum_begin + 1, 2 * half + 1,
      [&](int r, int c) { return grid.node(velum_begin + r, R, mid - half + c); },
      [&](int) { return gaps.velum; });

  // Pharyngeal wall: the dorsum from 66 % of the angular range to the root's end, full width.
  const int wall_begin = at(0.66, g.angular);
  auto wall = offset_sheet(
      grid, normal, g.angular - wall_begin + 1, K + 1,
      [&](int r, int c) { return grid.node(wall_begin + r, R, c); },
      [&](int) { return gaps.pharyngeal_wall; });

  // Offsets of the tongue's smooth rest surface: their normals are interpolated (fem::Normals).
  const fem::Normals smooth = fem::Normals::smooth;
  return {std::make_shared<const fem::Obstacle>("hard_palate", std::move(palate), smooth),
          std::make_shared<const fem::Obstacle>("upper_teeth", std::move(teeth), smooth),
          std::make_shared<const fem::Obstacle>("velum", std::move(velum), smooth),
          std::make_shared<const fem::Obstacle>("pharyngeal_wall", std::move(wall), smooth)};
}

}  // namespace tongue::model
