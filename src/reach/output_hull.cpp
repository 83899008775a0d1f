/// \file output_hull.cpp
/// Convex hulls of output sets as half-spaces (Bullet in 3-D, monotone chain in 2-D).

#include "reach_trajopt/reach/output_hull.h"

#include <LinearMath/btConvexHullComputer.h>

#include <Eigen/Geometry>
#include <cmath>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/reach/boundary_selection.h"

namespace reach_trajopt {

OutputHull::OutputHull(const Eigen::Ref<const Eigen::MatrixXd>& pts) {
  const int d = static_cast<int>(pts.rows());
  const int n = static_cast<int>(pts.cols());
  if (d < 1 || d > 3) throw ReachError("OutputHull: points must have 1-3 rows");
  requireFinite("OutputHull: points", pts);
  normals_.resize(d, 0);
  if (n < d + 1) return;
  const double scale = 1e-12 * (1.0 + pts.cwiseAbs().maxCoeff());
  if (d == 1) {
    const double lo = pts.minCoeff(), hi = pts.maxCoeff();
    if (hi - lo <= scale) return;
    normals_.resize(1, 2);
    normals_ << 1.0, -1.0;
    offsets_.resize(2);
    offsets_ << hi, -lo;
    return;
  }
  if (d == 2) {
    const std::vector<int> h = convexHull2d(pts);
    if (h.size() < 3) return;
    normals_.resize(2, h.size());
    offsets_.resize(h.size());
    for (std::size_t k = 0; k < h.size(); ++k) {
      const Eigen::Vector2d a = pts.col(h[k]), b = pts.col(h[(k + 1) % h.size()]);
      const Eigen::Vector2d e = b - a;
      const Eigen::Vector2d nrm = Eigen::Vector2d(e.y(), -e.x()).normalized();  // CCW: outward
      normals_.col(k) = nrm;
      offsets_[k] = nrm.dot(a);
    }
    return;
  }
  // 3-D: Bullet's hull (double coordinates, no shrink); faces walked edge by edge.
  const Eigen::Matrix3Xd P = pts;
  btConvexHullComputer hull;
  hull.compute(P.data(), 3 * static_cast<int>(sizeof(double)), n, 0.0, 0.0);
  const int faces = hull.faces.size();
  if (faces < 4) return;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int i = 0; i < hull.vertices.size(); ++i)
    c += Eigen::Vector3d(hull.vertices[i].x(), hull.vertices[i].y(), hull.vertices[i].z());
  c /= hull.vertices.size();
  std::vector<Eigen::Vector3d> nrm;
  std::vector<double> off;
  for (int f = 0; f < faces; ++f) {
    const btConvexHullComputer::Edge* e0 = &hull.edges[hull.faces[f]];
    std::vector<Eigen::Vector3d> v;
    const btConvexHullComputer::Edge* e = e0;
    do {
      const btVector3& p = hull.vertices[e->getSourceVertex()];
      v.emplace_back(p.x(), p.y(), p.z());
      e = e->getNextEdgeOfFace();
    } while (e != e0 && v.size() < 1000);
    if (v.size() < 3) continue;
    // Newell's normal of the (planar) face polygon.
    Eigen::Vector3d nn = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < v.size(); ++k) nn += v[k].cross(v[(k + 1) % v.size()]);
    if (nn.norm() <= scale * scale) continue;
    nn.normalize();
    double o = 0.0;
    for (const auto& p : v) o += nn.dot(p);
    o /= v.size();
    if (nn.dot(c) > o) {  // point outward, away from the centroid
      nn = -nn;
      o = -o;
    }
    nrm.push_back(nn);
    off.push_back(o);
  }
  if (nrm.size() < 4) return;
  normals_.resize(3, nrm.size());
  offsets_.resize(nrm.size());
  for (std::size_t k = 0; k < nrm.size(); ++k) {
    normals_.col(k) = nrm[k];
    offsets_[k] = off[k];
  }
}

bool OutputHull::contains(const Eigen::Ref<const Eigen::VectorXd>& y, double tolerance) const {
  if (degenerate() || y.size() != normals_.rows()) return false;
  for (int k = 0; k < normals_.cols(); ++k)
    if (normals_.col(k).dot(y) > offsets_[k] + tolerance) return false;
  return true;
}

int OutputHull::countInside(const Eigen::Ref<const Eigen::MatrixXd>& points,
                            double tolerance) const {
  int count = 0;
  for (int i = 0; i < points.cols(); ++i) count += contains(points.col(i), tolerance) ? 1 : 0;
  return count;
}

}  // namespace reach_trajopt
