#include "sixdof_core/grasp_geometry.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "sixdof_core/mesh_loader.h"

namespace sixdof_core {

namespace {

// Finger positions sampled between open and closed for the fingers' reach (a 2 % step of the travel).
constexpr int kTravelSamples = 50;

using Points = std::vector<Eigen::Vector3d>;

// Surface points of a shape in its frame: a box's corners, a cylinder's rims, a sphere's points in 26
// directions, a mesh's vertices.
void addShapePoints(const PlacedShape& placed, Points* out) {
  const Shape& shape = placed.shape;
  Points local;
  switch (shape.type) {
    case ShapeType::kBox:
      for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector3d sign(corner & 1 ? 0.5 : -0.5, corner & 2 ? 0.5 : -0.5, corner & 4 ? 0.5 : -0.5);
        local.push_back(sign.cwiseProduct(shape.box_size));
      }
      break;
    case ShapeType::kCylinder:
      for (int k = 0; k < 16; ++k) {
        const double a = 2.0 * M_PI * k / 16.0;
        for (const double z : {-0.5 * shape.length, 0.5 * shape.length}) {
          local.emplace_back(shape.radius * std::cos(a), shape.radius * std::sin(a), z);
        }
      }
      break;
    case ShapeType::kSphere:
      for (int x = -1; x <= 1; ++x) {
        for (int y = -1; y <= 1; ++y) {
          for (int z = -1; z <= 1; ++z) {
            if (x || y || z) local.push_back(shape.radius * Eigen::Vector3d(x, y, z).normalized());
          }
        }
      }
      break;
    case ShapeType::kMesh: {
      if (shape.mesh_path.empty()) return;  // an unresolved visual mesh
      const MeshLoadResult loaded = loadMesh(shape.mesh_path, shape.mesh_scale);
      if (!loaded) throw std::invalid_argument(loaded.message);
      local = loaded.mesh->vertices;
      break;
    }
  }
  for (const auto& p : local) out->push_back(placed.origin * p);
}

Points linkPoints(const LinkModel& link) {
  Points points;
  for (const auto& shape : link.collision.shapes) addShapePoints(shape, &points);
  if (points.empty()) {
    for (const auto& visual : link.visuals) addShapePoints(visual.placed, &points);
  }
  return points;
}

class Analyzer {
 public:
  Analyzer(const RobotModelConstPtr& model, const GripperQuery& query)
      : model_(*model), query_(query), state_(model), parent_(model->linkIndex(query.parent_link)) {}

  GraspGeometry run();

 private:
  void checkQuery();
  void findFingers();
  void setPositions(const std::map<std::string, double>& values);
  std::map<std::string, double> halfway(const std::map<std::string, double>& a,
                                        const std::map<std::string, double>& b) const;
  Points pointsInParent(int link) const;
  Eigen::Vector3d centroid(int link) const;
  void findAxis();
  void findPads();
  double width() const;
  void findOpenClosed();
  void findTcp();
  void findDepths();

  const RobotModel& model_;
  const GripperQuery& query_;
  RobotState state_;
  int parent_;
  GraspGeometry out_;
  std::vector<std::string> actuated_;
  std::map<int, Points> fingers_;  // finger link -> its points in the link frame
  std::map<std::string, double> lower_, upper_, mid_;
  std::optional<Eigen::Vector3d> axis_;
  int plus_pad_ = -1;  // the pad on the + side of the axis, and the other
  int minus_pad_ = -1;
};

void Analyzer::checkQuery() {
  if (parent_ < 0) throw std::invalid_argument("gripper: no link '" + query_.parent_link + "' (its parent link)");
  std::set<std::string> listed(query_.joints.begin(), query_.joints.end());
  for (const auto& name : query_.joints) {
    const int j = model_.jointIndex(name);
    if (j < 0) throw std::invalid_argument("gripper: no joint '" + name + "'");
    if (model_.joints()[j].type == JointType::kFixed) {
      throw std::invalid_argument("gripper: joint '" + name + "' is fixed");
    }
  }
  for (const auto& joint : model_.joints()) {
    if (listed.count(joint.name) && joint.isActive()) actuated_.push_back(joint.name);
  }
  if (actuated_.empty()) throw std::invalid_argument("gripper: none of its joints is actuated (all mimic joints)");
  for (const auto& name : actuated_) {
    const auto& limits = model_.joint(name).limits;
    lower_[name] = limits.lower;
    upper_[name] = limits.upper;
  }
  for (const auto* given : {&query_.open, &query_.closed}) {
    for (const auto& [name, value] : *given) {
      if (!lower_.count(name)) {
        throw std::invalid_argument("gripper: joint '" + name + "' of a given open/closed state is not an actuated "
                                    "gripper joint");
      }
      if (!(value >= lower_[name] && value <= upper_[name])) {
        throw std::invalid_argument("gripper: " + std::to_string(value) + " for joint '" + name +
                                    "' is outside its limits");
      }
    }
  }
  if (query_.closing_direction && !(query_.closing_direction->norm() > 1e-9)) {
    throw std::invalid_argument("gripper: the given closing direction is zero");
  }
  if (!query_.tcp_parent.empty()) {
    const int frame = model_.linkIndex(query_.tcp_parent);
    if (frame < 0) throw std::invalid_argument("gripper: no link '" + query_.tcp_parent + "' (the tcp's parent)");
    for (const std::string& name : actuated_) {
      // Moving a finger joint must not move the frame the tcp is given in.
      RobotState probe = state_;
      probe.setJointPosition(name, lower_[name]);
      const Eigen::Isometry3d before = probe.linkTransform(parent_).inverse() * probe.linkTransform(frame);
      probe.setJointPosition(name, upper_[name]);
      const Eigen::Isometry3d after = probe.linkTransform(parent_).inverse() * probe.linkTransform(frame);
      if (!before.isApprox(after, 1e-9)) {
        throw std::invalid_argument("gripper: the tcp's parent '" + query_.tcp_parent + "' is moved by joint '" +
                                    name + "'");
      }
    }
  }
  if (query_.tcp && model_.linkIndex(query_.tcp_link) >= 0) {
    throw std::invalid_argument("gripper: a tcp is given but the robot has a link named '" + query_.tcp_link +
                                "', which is the TCP; remove one of them");
  }
}

// Links below the parent that an actuated finger joint (or a joint mimicking one) moves, with their geometry.
void Analyzer::findFingers() {
  const std::set<std::string> actuated(actuated_.begin(), actuated_.end());
  std::vector<int> stack{parent_};
  std::vector<bool> moved(model_.links().size(), false);
  while (!stack.empty()) {
    const int l = stack.back();
    stack.pop_back();
    for (const int j : model_.links()[l].child_joints) {
      const JointModel& joint = model_.joints()[j];
      const int child = model_.linkIndex(joint.child_link);
      moved[child] = moved[l] || actuated.count(joint.name) || (joint.mimic && actuated.count(joint.mimic->joint));
      stack.push_back(child);
    }
  }
  for (size_t l = 0; l < moved.size(); ++l) {
    if (!moved[l]) continue;
    Points points;
    try {
      points = linkPoints(model_.links()[l]);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("gripper link '" + model_.links()[l].name + "': " + e.what());
    }
    if (points.empty()) continue;
    fingers_[static_cast<int>(l)] = points;
    out_.finger_links.push_back(model_.links()[l].name);
  }
}

void Analyzer::setPositions(const std::map<std::string, double>& values) {
  for (const auto& [name, value] : values) state_.setJointPosition(name, value);
}

std::map<std::string, double> Analyzer::halfway(const std::map<std::string, double>& a,
                                                const std::map<std::string, double>& b) const {
  std::map<std::string, double> out;
  for (const auto& [name, value] : a) out[name] = 0.5 * (value + b.at(name));
  return out;
}

Points Analyzer::pointsInParent(int link) const {
  const Eigen::Isometry3d t = state_.linkTransform(parent_).inverse() * state_.linkTransform(link);
  Points out;
  for (const auto& p : fingers_.at(link)) out.push_back(t * p);
  return out;
}

Eigen::Vector3d Analyzer::centroid(int link) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const Points points = pointsInParent(link);
  for (const auto& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

// The closing direction: the main direction in which the finger links move relative to each other (their common
// motion removed) while each finger joint runs through its range.
void Analyzer::findAxis() {
  if (query_.closing_direction) {
    axis_ = query_.closing_direction->normalized();
    return;
  }
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (const auto& name : actuated_) {
    std::map<int, Eigen::Vector3d> start;
    setPositions(mid_);
    state_.setJointPosition(name, lower_[name]);
    for (const auto& [link, points] : fingers_) start[link] = centroid(link);
    state_.setJointPosition(name, upper_[name]);
    std::vector<Eigen::Vector3d> moves;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& [link, points] : fingers_) {
      moves.push_back(centroid(link) - start[link]);
      mean += moves.back();
    }
    if (moves.empty()) break;
    mean /= static_cast<double>(moves.size());
    for (const auto& m : moves) spread += (m - mean) * (m - mean).transpose();
  }
  if (spread.trace() < 1e-12) {
    out_.warnings.push_back("the finger joints move no two finger links apart: no closing direction");
    return;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(spread);
  axis_ = eig.eigenvectors().col(2).normalized();
}

void Analyzer::findPads() {
  if (!axis_) return;
  setPositions(mid_);
  const Eigen::Vector3d axis = *axis_;
  std::vector<int> candidates;
  if (!query_.pad_links.empty()) {
    if (query_.pad_links.size() != 2 || query_.pad_links[0] == query_.pad_links[1]) {
      throw std::invalid_argument("gripper: give two different pad links");
    }
    for (const auto& name : query_.pad_links) {
      const int l = model_.linkIndex(name);
      if (l < 0) throw std::invalid_argument("gripper: no pad link '" + name + "'");
      if (!fingers_.count(l)) {
        const Points points = linkPoints(model_.links()[l]);
        if (points.empty()) throw std::invalid_argument("gripper: pad link '" + name + "' has no geometry");
        fingers_[l] = points;
      }
      candidates.push_back(l);
    }
    const bool first_plus = centroid(candidates[0]).dot(axis) > centroid(candidates[1]).dot(axis);
    plus_pad_ = candidates[first_plus ? 0 : 1];
    minus_pad_ = candidates[first_plus ? 1 : 0];
  } else {
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    std::map<int, double> along;
    for (const auto& [link, points] : fingers_) {
      along[link] = centroid(link).dot(axis);
      low = std::min(low, along[link]);
      high = std::max(high, along[link]);
    }
    const double centre = 0.5 * (low + high);
    double best_plus = std::numeric_limits<double>::infinity();
    double best_minus = -best_plus;
    // Model order: of two links equally far in, the later (more distal) one.
    for (const auto& [link, points] : fingers_) {
      const Points in_parent = pointsInParent(link);
      if (along[link] > centre + 1e-4) {
        double inner = std::numeric_limits<double>::infinity();
        for (const auto& p : in_parent) inner = std::min(inner, p.dot(axis));
        if (inner <= best_plus + 1e-4) {
          best_plus = std::min(best_plus, inner);
          plus_pad_ = link;
        }
      } else if (along[link] < centre - 1e-4) {
        double inner = -std::numeric_limits<double>::infinity();
        for (const auto& p : in_parent) inner = std::max(inner, p.dot(axis));
        if (inner >= best_minus - 1e-4) {
          best_minus = std::max(best_minus, inner);
          minus_pad_ = link;
        }
      }
    }
    if (plus_pad_ < 0 || minus_pad_ < 0) {
      plus_pad_ = minus_pad_ = -1;
      out_.warnings.push_back("no finger links on both sides of the closing direction: no pads");
      return;
    }
  }
  for (const int l : {minus_pad_, plus_pad_}) out_.pad_links.push_back(model_.links()[l].name);
}

double Analyzer::width() const {
  double plus = std::numeric_limits<double>::infinity();
  double minus = -plus;
  for (const auto& p : pointsInParent(plus_pad_)) plus = std::min(plus, p.dot(*axis_));
  for (const auto& p : pointsInParent(minus_pad_)) minus = std::max(minus, p.dot(*axis_));
  return plus - minus;
}

void Analyzer::findOpenClosed() {
  for (const auto& name : actuated_) {
    FingerJoint finger{name, 0.0, 0.0, upper_[name], lower_[name]};
    if (plus_pad_ >= 0) {
      setPositions(mid_);
      state_.setJointPosition(name, lower_[name]);
      finger.width_at_lower = width();
      state_.setJointPosition(name, upper_[name]);
      finger.width_at_upper = width();
      if (std::abs(finger.width_at_upper - finger.width_at_lower) < 1e-6) {
        const double rest = model_.defaultPositions()[model_.joint(name).variable_index];
        finger.open = finger.closed = rest;
        out_.warnings.push_back("joint '" + name + "' does not move the pads: open and closed at " +
                                std::to_string(rest));
      } else if (finger.width_at_lower > finger.width_at_upper) {
        finger.open = lower_[name];
        finger.closed = upper_[name];
      }
    }
    if (query_.open.count(name)) finger.open = query_.open.at(name);
    if (query_.closed.count(name)) finger.closed = query_.closed.at(name);
    out_.open[name] = finger.open;
    out_.closed[name] = finger.closed;
    out_.finger_joints.push_back(finger);
  }
  if (plus_pad_ < 0) {
    out_.warnings.push_back("without pads, open = the finger joints' upper limits and closed = their lower limits");
    return;
  }
  setPositions(out_.open);
  out_.open_width = width();
  setPositions(out_.closed);
  out_.closed_width = width();
}

void Analyzer::findTcp() {
  setPositions(halfway(out_.open, out_.closed));
  const int link = model_.linkIndex(query_.tcp_link);
  if (link >= 0) {
    out_.tcp = state_.linkTransform(parent_).inverse() * state_.linkTransform(link);
    out_.tcp_source = "link '" + query_.tcp_link + "'";
  } else if (query_.tcp) {
    const int frame = query_.tcp_parent.empty() ? parent_ : model_.linkIndex(query_.tcp_parent);
    out_.tcp = state_.linkTransform(parent_).inverse() * state_.linkTransform(frame) * *query_.tcp;
    out_.tcp_source = "given";
  } else if (plus_pad_ >= 0) {
    const Eigen::Vector3d y = *axis_;
    // Each pad's contact surface: its points within kPadSurfaceTolerance of its innermost one.
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    Eigen::Vector3d base = Eigen::Vector3d::Zero();
    int bases = 0;
    for (const int pad : {plus_pad_, minus_pad_}) {
      const double sign = pad == plus_pad_ ? 1.0 : -1.0;
      const Points points = pointsInParent(pad);
      double inner = std::numeric_limits<double>::infinity();
      for (const auto& p : points) inner = std::min(inner, sign * p.dot(y));
      Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
      Eigen::Vector3d high = -low;
      for (const auto& p : points) {
        if (sign * p.dot(y) > inner + kPadSurfaceTolerance) continue;
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
      }
      centre += 0.25 * (low + high);
      // Where the pad's finger is jointed: the first joint below the parent that moves it.
      for (const int j : model_.chainJoints(query_.parent_link, model_.links()[pad].name)) {
        if (model_.joints()[j].type == JointType::kFixed) continue;
        const int above = model_.linkIndex(model_.joints()[j].parent_link);
        base += (state_.linkTransform(parent_).inverse() * state_.linkTransform(above) * model_.joints()[j].origin)
                    .translation();
        ++bases;
        break;
      }
    }
    if (bases > 0) base /= bases;
    Eigen::Vector3d z = centre - base;
    z -= z.dot(y) * y;
    // Grippers are mounted square to their flange, but their finger joints need not lie on the flange's axis:
    // an approach within kApproachSnap of one of the parent's axes (made perpendicular to y) is that axis.
    const bool level = z.norm() < 1e-4;
    const Eigen::Vector3d raw = level ? Eigen::Vector3d::Zero() : Eigen::Vector3d(z.normalized());
    double best = level ? -2.0 : std::cos(kApproachSnap);
    for (const int axis : {2, 0, 1, 5, 3, 4}) {  // +z, +x, +y, -z, -x, -y: without a direction, the first that fits
      Eigen::Vector3d candidate = (axis < 3 ? 1.0 : -1.0) * Eigen::Vector3d::Unit(axis % 3);
      candidate -= candidate.dot(y) * y;
      if (candidate.norm() < 0.5) continue;
      candidate.normalize();
      const double agreement = level ? 0.0 : raw.dot(candidate);
      if (agreement > best) {
        best = agreement;
        z = candidate;
      }
    }
    if (level) {
      out_.warnings.push_back("the pads lie level with their finger joints: approach along the parent's first axis "
                              "across the closing direction");
    }
    z.normalize();
    Eigen::Matrix3d r;
    r.col(0) = y.cross(z);
    r.col(1) = y;
    r.col(2) = z;
    if (r(0, 0) + r(1, 1) < 0.0) r.leftCols<2>() *= -1.0;  // the least rotation from the parent frame
    out_.tcp.linear() = r;
    out_.tcp.translation() = centre;
    out_.tcp_source = "pads";
  } else {
    out_.tcp_source = "parent link";
    out_.warnings.push_back("no pads: the TCP is the parent link's frame; give it in the answers (tcp)");
  }
  out_.approach_direction = out_.tcp.linear().col(2);
}

void Analyzer::findDepths() {
  // Over the whole travel, not only its ends: a revolute linkage's fingertips swing out beyond both on their way.
  out_.reach = -std::numeric_limits<double>::infinity();
  for (int step = 0; step <= kTravelSamples; ++step) {
    const double s = static_cast<double>(step) / kTravelSamples;
    for (const auto& [name, open] : out_.open) state_.setJointPosition(name, open + s * (out_.closed.at(name) - open));
    for (const auto& [finger, points] : fingers_) {
      for (const auto& p : pointsInParent(finger)) {
        out_.reach = std::max(out_.reach, (p - out_.tcp.translation()).dot(out_.approach_direction));
      }
    }
  }
  if (fingers_.empty()) out_.reach = 0.0;
  // The palm: shapes of the parent and of the links fixed below it, each as a box in the TCP frame.
  out_.palm_depth = std::numeric_limits<double>::infinity();
  const Eigen::Isometry3d to_tcp = out_.tcp.inverse() * state_.linkTransform(parent_).inverse();
  const double half_gap = std::max(out_.open_width, 0.0) / 2.0;
  std::vector<int> palm{parent_};
  for (size_t i = 0; i < palm.size(); ++i) {
    for (const int j : model_.links()[palm[i]].child_joints) {
      if (model_.joints()[j].type == JointType::kFixed) palm.push_back(model_.linkIndex(model_.joints()[j].child_link));
    }
  }
  for (const int link : palm) {
    for (const auto& shape : model_.links()[link].collision.shapes) {
      Points points;
      addShapePoints(shape, &points);
      Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
      Eigen::Vector3d high = -low;
      for (const auto& p : points) {
        const Eigen::Vector3d q = to_tcp * (state_.linkTransform(link) * p);
        low = low.cwiseMin(q);
        high = high.cwiseMax(q);
      }
      if (high.z() < 0.0 && low.y() < half_gap && high.y() > -half_gap) {
        out_.palm_depth = std::min(out_.palm_depth, -high.z());
      }
    }
  }
  if (axis_) {
    out_.closing_direction = axis_->dot(out_.tcp.linear().col(1)) < 0.0 ? Eigen::Vector3d(-*axis_) : *axis_;
  } else {
    out_.closing_direction = out_.tcp.linear().col(1);
  }
}

GraspGeometry Analyzer::run() {
  checkQuery();
  out_.parent_link = query_.parent_link;
  findFingers();
  for (const auto& name : actuated_) mid_[name] = 0.5 * (lower_[name] + upper_[name]);
  findAxis();
  findPads();
  findOpenClosed();
  findTcp();
  findDepths();
  return out_;
}

}  // namespace

GraspGeometry analyzeGripper(const RobotModelConstPtr& model, const GripperQuery& query) {
  if (!model) throw std::invalid_argument("analyzeGripper: no robot model");
  return Analyzer(model, query).run();
}

}  // namespace sixdof_core
