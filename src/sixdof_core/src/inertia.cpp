#include "sixdof_core/inertia.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "sixdof_core/mesh_loader.h"

namespace sixdof_core {

namespace {

MassProperties boxProperties(const Eigen::Vector3d& size, double density) {
  MassProperties p;
  p.volume = size.prod();
  p.mass = density * p.volume;
  const Eigen::Vector3d s = size.cwiseProduct(size);
  p.inertia.diagonal() << s.y() + s.z(), s.x() + s.z(), s.x() + s.y();
  p.inertia *= p.mass / 12.0;
  return p;
}

// A closed triangle mesh by signed tetrahedra from the origin: volume, first and second moments.
MassProperties meshProperties(const MeshData& mesh, double density) {
  double volume = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d& b = mesh.vertices[t[1]];
    const Eigen::Vector3d& c = mesh.vertices[t[2]];
    const double det = a.dot(b.cross(c));
    const Eigen::Vector3d sum = a + b + c;
    volume += det / 6.0;
    first += det / 24.0 * sum;
    second += det / 120.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
  }
  if (volume < 0.0) {  // faces wound inwards
    volume = -volume;
    first = -first;
    second = -second;
  }
  Eigen::Vector3d low = mesh.vertices.front();
  Eigen::Vector3d high = low;
  for (const auto& v : mesh.vertices) {
    low = low.cwiseMin(v);
    high = high.cwiseMax(v);
  }
  const Eigen::Vector3d com = volume > 0.0 ? Eigen::Vector3d(first / volume) : Eigen::Vector3d::Zero();
  const bool inside = (com.array() >= low.array() - 1e-9).all() && (com.array() <= high.array() + 1e-9).all();
  if (volume < 0.01 * (high - low).prod() || !inside) {
    MassProperties box = boxProperties(high - low, density);
    box.com = (low + high) / 2.0;
    return box;
  }
  MassProperties p;
  p.volume = volume;
  p.mass = density * volume;
  p.com = com;
  const Eigen::Matrix3d c = density * second;
  const Eigen::Matrix3d about_origin = c.trace() * Eigen::Matrix3d::Identity() - c;
  p.inertia = about_origin - p.mass * (com.squaredNorm() * Eigen::Matrix3d::Identity() - com * com.transpose());
  return p;
}

std::string number(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

}  // namespace

MassProperties shapeMassProperties(const PlacedShape& placed, double density) {
  if (!(density > 0.0) || !std::isfinite(density)) {
    throw std::invalid_argument("density must be > 0 kg/m^3, got " + number(density));
  }
  const Shape& shape = placed.shape;
  MassProperties p;
  switch (shape.type) {
    case ShapeType::kBox:
      p = boxProperties(shape.box_size, density);
      break;
    case ShapeType::kSphere:
      p.volume = 4.0 / 3.0 * M_PI * std::pow(shape.radius, 3);
      p.mass = density * p.volume;
      p.inertia = 0.4 * p.mass * shape.radius * shape.radius * Eigen::Matrix3d::Identity();
      break;
    case ShapeType::kCylinder: {
      p.volume = M_PI * shape.radius * shape.radius * shape.length;
      p.mass = density * p.volume;
      const double across = p.mass * (3.0 * shape.radius * shape.radius + shape.length * shape.length) / 12.0;
      p.inertia.diagonal() << across, across, p.mass * shape.radius * shape.radius / 2.0;
      break;
    }
    case ShapeType::kMesh: {
      const MeshLoadResult loaded = loadMesh(shape.mesh_path, shape.mesh_scale);
      if (!loaded) throw std::invalid_argument(loaded.message);
      p = meshProperties(*loaded.mesh, density);
      break;
    }
  }
  const Eigen::Matrix3d r = placed.origin.linear();
  p.com = placed.origin * p.com;
  p.inertia = r * p.inertia * r.transpose();
  return p;
}

MassProperties combineMassProperties(const std::vector<MassProperties>& parts) {
  MassProperties total;
  for (const auto& part : parts) {
    total.volume += part.volume;
    total.mass += part.mass;
    total.com += part.mass * part.com;
  }
  if (!(total.mass > 0.0)) return total;
  total.com /= total.mass;
  for (const auto& part : parts) {
    const Eigen::Vector3d d = part.com - total.com;
    total.inertia += part.inertia + part.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return total;
}

std::string inertialProblem(const std::optional<LinkInertial>& inertial) {
  if (!inertial) return "no <inertial>";
  if (!std::isfinite(inertial->mass) || !(inertial->mass > 0.0)) {
    return "mass " + number(inertial->mass) + " is not > 0";
  }
  if (!inertial->inertia.allFinite()) return "inertia is not finite";
  if (inertial->inertia.isZero(0.0)) return "inertia is zero";
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(inertial->inertia, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d m = eig.eigenvalues();  // ascending
  if (!(m[0] > 0.0)) return "inertia has a principal moment of " + number(m[0]) + " (not > 0)";
  if (m[2] > 1.01 * (m[0] + m[1])) {
    return "principal moments " + number(m[0]) + ", " + number(m[1]) + ", " + number(m[2]) +
           " break the triangle inequality";
  }
  return "";
}

std::vector<InertiaRepair> inertiaRepairs(const RobotModel& model, double density) {
  if (!(density > 0.0) || !std::isfinite(density)) {
    throw std::invalid_argument("density must be > 0 kg/m^3, got " + number(density));
  }
  std::vector<InertiaRepair> repairs;
  for (const LinkModel& link : model.links()) {
    if (link.parent_joint < 0 || model.joints()[link.parent_joint].type == JointType::kFixed) continue;
    InertiaRepair repair;
    repair.problem = inertialProblem(link.inertial);
    if (repair.problem.empty()) continue;
    repair.link = link.name;
    std::vector<PlacedShape> shapes = link.collision.shapes;
    repair.source = "collision";
    if (shapes.empty()) {
      repair.source = "visual";
      for (const LinkVisual& visual : link.visuals) {
        // A visual mesh the model could not resolve has no file to integrate.
        if (visual.placed.shape.type != ShapeType::kMesh || !visual.placed.shape.mesh_path.empty()) {
          shapes.push_back(visual.placed);
        }
      }
    }
    std::vector<MassProperties> parts;
    for (const PlacedShape& shape : shapes) {
      try {
        parts.push_back(shapeMassProperties(shape, density));
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("link '" + link.name + "': " + e.what());
      }
    }
    const MassProperties total = combineMassProperties(parts);
    if (total.mass > 0.0) {
      repair.density = density;
      repair.inertial.mass = total.mass;
      repair.inertial.origin.translation() = total.com;
      repair.inertial.inertia = total.inertia;
    } else {
      repair.source = "default";
      repair.inertial.mass = kDefaultLinkMass;
      repair.inertial.inertia = kDefaultLinkInertia * Eigen::Matrix3d::Identity();
    }
    repairs.push_back(repair);
  }
  return repairs;
}

}  // namespace sixdof_core
