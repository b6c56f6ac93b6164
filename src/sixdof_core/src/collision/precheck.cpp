// The collision pre-check (CollisionScene::precheckMotion): how much of a motion the robot bodies' covering spheres
// prove free. Every robot body's sphere tree is walked against the world's AABB tree and shapes and, for the self
// pairs, against the other body's tree, pruning any branch that cannot lower the best fraction so far.

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "scene_impl.h"

namespace sixdof_core {

using detail::ClearanceShape;
using detail::SphereNode;
using detail::WorldShapeTag;

namespace {

// Clearance (m) kept on top of the motion: rounding in the transforms, FCL's own tolerances.
constexpr double kMargin = 1e-4;
// A node proving at least this share of the pair's best so far is not opened: it stands in for its leaves, and the
// proof may be that much shorter than the best the spheres allow (but opens far fewer of them).
constexpr double kSlack = 0.75;

// Over a fraction w of the motion, a point moves at most speed * w + growth * w^2 / 2 (LinkMotionBound).
struct Reach {
  double speed = 0.0;
  double growth = 0.0;
};

Reach operator+(const Reach& a, const Reach& b) { return Reach{a.speed + b.speed, a.growth + b.growth}; }

// The fraction of the motion that points moving as `reach` says need to move a distance (> 0), at least.
double fractionToMove(double distance, const Reach& reach) {
  if (reach.growth <= 0.0) {
    return reach.speed > 0.0 ? distance / reach.speed : std::numeric_limits<double>::infinity();
  }
  return 2.0 * distance / (reach.speed + std::sqrt(reach.speed * reach.speed + 2.0 * reach.growth * distance));
}

// The largest fraction of the motion that a clearance proves free for points moving as `reach` says.
double provenFraction(double clearance, const Reach& reach) {
  return clearance > kMargin ? fractionToMove(clearance - kMargin, reach) : 0.0;
}

double boxDistance(const fcl::AABBd& box, const Eigen::Vector3d& p) {
  return (box.min_ - p).cwiseMax(p - box.max_).cwiseMax(0.0).norm();
}

// A link's terms summed: how a point at distance `reach` from its origin moves.
struct Motion {
  double linear = 0.0;
  double angular = 0.0;
  double growth = 0.0;

  Reach at(double reach) const { return Reach{linear + angular * reach, growth}; }
};

// The terms of `terms` whose joint is not among `others`' (the motion relative to a link moving with `others`).
Motion unshared(const std::vector<LinkMotionBound::Term>& terms, const std::vector<LinkMotionBound::Term>& others) {
  Motion m;
  for (const LinkMotionBound::Term& t : terms) {
    bool shared = false;
    for (const LinkMotionBound::Term& o : others) shared |= o.joint == t.joint;
    if (!shared) {
      m.linear += t.linear;
      m.angular += t.angular;
      m.growth += t.growth;
    }
  }
  return m;
}

}  // namespace

class CollisionScene::Impl::Certifier {
 public:
  Certifier(const CollisionScene::Impl& scene, const std::vector<Eigen::Isometry3d>& poses,
            const LinkMotionBound& bound, double cap, double tolerance)
      : s_(scene),
        poses_(poses),
        bound_(bound),
        tolerance_(tolerance),
        best_(cap),
        link_motion_(scratch().link_motion),
        root_centers_(scratch().root_centers) {
    link_motion_.resize(bound.links.size());
    for (std::size_t i = 0; i < bound.links.size(); ++i) link_motion_[i] = unshared(bound.links[i], {});
  }

  SphereCertificate run() {
    const auto* world_root = s_.world.empty() ? nullptr : s_.manager->getTree().getRoot();
    const int n = s_.robotCount();
    root_centers_.resize(n);
    for (int r = 0; r < n; ++r) {
      if (!s_.sphere_trees[r].empty()) root_centers_[r] = worldCenter(r, s_.sphere_trees[r][0]);
    }
    for (int r = 0; r < n && best_ > 0.0; ++r) {
      if (s_.sphere_trees[r].empty()) continue;
      const SphereNode& root = s_.sphere_trees[r][0];
      if (world_root && s_.robot_has_world_pair[r]) {
        bodyVsWorld(r, root_centers_[r], root.radius, motion(r, root.reach), world_root);
      }
      if (s_.octree && best_ > 0.0) worldPair(r, s_.octree_box);
    }
    for (const auto& [a, b] : s_.self_pairs) {
      if (best_ <= 0.0) break;
      if (s_.sphere_trees[a].empty() || s_.sphere_trees[b].empty()) continue;
      const int la = s_.robot(a).link, lb = s_.robot(b).link;
      // The roots with all of both motions first: the shared terms are worth sorting out only for a close pair.
      const SphereNode& ra = s_.sphere_trees[a][0];
      const SphereNode& rb = s_.sphere_trees[b][0];
      const double gap = (root_centers_[a] - root_centers_[b]).norm() - ra.radius - rb.radius;
      if (provenFraction(gap, link_motion_[la].at(ra.reach) + link_motion_[lb].at(rb.reach)) >= best_) continue;
      selfPair(Pair{a, b, unshared(bound_.links[la], bound_.links[lb]), unshared(bound_.links[lb], bound_.links[la])});
    }
    return SphereCertificate{std::max(0.0, best_), unprovable_};
  }

 private:
  // Two bodies of a self pair, each with its motion relative to what moves them together.
  struct Pair {
    int a, b;
    Motion ma, mb;
  };

  Reach motion(int r, double reach) const { return link_motion_[s_.robot(r).link].at(reach); }

  Eigen::Vector3d worldCenter(int r, const SphereNode& node) const { return poses_[s_.robot(r).link] * node.center; }

  double shapeFraction(int r, const SphereNode& node, const ClearanceShape& shape) const {
    return provenFraction(detail::pointDistance(shape, worldCenter(r, node)) - node.radius, motion(r, node.reach));
  }

  // Both bodies move: their spheres close in by at most the sum of their motions.
  double pairFraction(const Pair& p, int ia, int ib) const {
    const SphereNode& na = s_.sphere_trees[p.a][ia];
    const SphereNode& nb = s_.sphere_trees[p.b][ib];
    const double gap = (worldCenter(p.a, na) - worldCenter(p.b, nb)).norm() - na.radius - nb.radius;
    return provenFraction(gap, p.ma.at(na.reach) + p.mb.at(nb.reach));
  }

  // --- One pair at a time (a body and a world shape, or a self pair), pruned against what the query proves so far.

  // Whether a node whose leaves can prove no more than f must be opened. One within the tolerance of the pair's best
  // is not: f stands in for its leaves.
  bool open(double f) {
    if (f >= pair_best_) return false;
    if (f >= pair_best_ * kSlack - tolerance_) {
      pair_pruned_ = std::min(pair_pruned_, f);
      return false;
    }
    return true;
  }

  void leaf(double f, double gap, const Reach& reach) {
    pair_best_ = f;
    // Leaf spheres within the margin stay that close until they have moved the difference.
    if (f <= 0.0) pair_unprovable_ = fractionToMove(kMargin - gap, reach);
  }

  // Ends a pair: what its spheres prove bounds what the query proves.
  void finishPair() {
    const double f = std::min(pair_best_, pair_pruned_);
    if (f >= best_) return;
    best_ = f;
    if (f <= 0.0) unprovable_ = std::max(unprovable_, pair_unprovable_);
  }

  void beginPair() {
    pair_best_ = best_;
    pair_pruned_ = std::numeric_limits<double>::infinity();
    pair_unprovable_ = 0.0;
  }

  // Robot body r against one world shape.
  void worldPair(int r, const ClearanceShape& shape) {
    const SphereNode& root = s_.sphere_trees[r][0];
    const double f = shapeFraction(r, root, shape);
    if (f >= best_) return;
    beginPair();
    bodyVsShape(r, 0, shape, f);
    finishPair();
  }

  void selfPair(const Pair& p) {
    beginPair();
    bodyVsBody(p, 0, 0, pairFraction(p, 0, 0));
    finishPair();
  }

  // Node `index` of body r's tree (fraction f) against a world shape, nearer child first.
  void bodyVsShape(int r, int index, const ClearanceShape& shape, double f) {
    if (!open(f)) return;
    const SphereNode& node = s_.sphere_trees[r][index];
    if (node.left < 0) {
      leaf(f, detail::pointDistance(shape, worldCenter(r, node)) - node.radius, motion(r, node.reach));
      return;
    }
    const double fl = shapeFraction(r, s_.sphere_trees[r][node.left], shape);
    const double fr = shapeFraction(r, s_.sphere_trees[r][node.right], shape);
    bodyVsShape(r, fl <= fr ? node.left : node.right, shape, std::min(fl, fr));
    if (pair_best_ > 0.0) bodyVsShape(r, fl <= fr ? node.right : node.left, shape, std::max(fl, fr));
  }

  // The body's root sphere (world centre, radius, motion) against the world's AABB tree, down to the shapes.
  void bodyVsWorld(int r, const Eigen::Vector3d& center, double radius, const Reach& root_motion,
                   const fcl::detail::NodeBase<fcl::AABBd>* node) {
    if (node == nullptr || best_ <= 0.0) return;
    if (provenFraction(boxDistance(node->bv, center) - radius, root_motion) >= best_) return;
    if (node->isLeaf()) {
      const auto* object = static_cast<const fcl::CollisionObjectd*>(node->data);
      const auto& tag = *static_cast<const WorldShapeTag*>(object->getUserData());
      if (s_.robot_world_checked[r * s_.world.size() + tag.body]) worldPair(r, tag.clearance);
      return;
    }
    bodyVsWorld(r, center, radius, root_motion, node->children[0]);
    bodyVsWorld(r, center, radius, root_motion, node->children[1]);
  }

  // Nodes ia and ib (fraction f) of a self pair's trees, splitting the larger, nearer child first.
  void bodyVsBody(const Pair& p, int ia, int ib, double f) {
    if (!open(f)) return;
    const SphereNode& na = s_.sphere_trees[p.a][ia];
    const SphereNode& nb = s_.sphere_trees[p.b][ib];
    if (na.left < 0 && nb.left < 0) {
      leaf(f, (worldCenter(p.a, na) - worldCenter(p.b, nb)).norm() - na.radius - nb.radius,
           p.ma.at(na.reach) + p.mb.at(nb.reach));
      return;
    }
    const bool split_a = na.left >= 0 && (nb.left < 0 || na.radius >= nb.radius);
    const int a1 = split_a ? na.left : ia, a2 = split_a ? na.right : ia;
    const int b1 = split_a ? ib : nb.left, b2 = split_a ? ib : nb.right;
    const double f1 = pairFraction(p, a1, b1), f2 = pairFraction(p, a2, b2);
    if (f1 <= f2) {
      bodyVsBody(p, a1, b1, f1);
      if (pair_best_ > 0.0) bodyVsBody(p, a2, b2, f2);
    } else {
      bodyVsBody(p, a2, b2, f2);
      if (pair_best_ > 0.0) bodyVsBody(p, a1, b1, f1);
    }
  }

  // Per thread, so that a query allocates nothing once warm.
  struct Scratch {
    std::vector<Motion> link_motion;
    std::vector<Eigen::Vector3d> root_centers;
  };
  static Scratch& scratch() {
    thread_local Scratch s;
    return s;
  }

  const CollisionScene::Impl& s_;
  const std::vector<Eigen::Isometry3d>& poses_;
  const LinkMotionBound& bound_;
  const double tolerance_;
  double best_;               // what the query proves: the least over the pairs so far (or the cap)
  double unprovable_ = 0.0;   // once best_ is 0
  double pair_best_ = 0.0;    // the pair's lowest leaf fraction so far (or best_)
  double pair_pruned_ = 0.0;  // the pair's lowest fraction of a node left closed
  double pair_unprovable_ = 0.0;
  std::vector<Motion>& link_motion_;            // per link: all its terms
  std::vector<Eigen::Vector3d>& root_centers_;  // per robot body: its root sphere's centre in the world
};

SphereCertificate CollisionScene::Impl::certifyMotion(const std::vector<Eigen::Isometry3d>& poses,
                                                      const LinkMotionBound& bound, double cap,
                                                      double tolerance) const {
  if (!(cap > 0.0)) return SphereCertificate();
  return Certifier(*this, poses, bound, cap, tolerance).run();
}

SphereCertificate CollisionScene::precheckMotion(const std::vector<Eigen::Isometry3d>& link_poses,
                                                 const LinkMotionBound& bound, double cap, double tolerance) const {
  impl_->checkPoses(link_poses);
  const std::size_t n = impl_->links.size();
  if (bound.links.size() != n) {
    std::ostringstream msg;
    msg << "CollisionScene: got a motion bound for " << bound.links.size() << " links for " << n << " links";
    throw std::invalid_argument(msg.str());
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (const LinkMotionBound::Term& t : bound.links[i]) {
      if (!(t.linear >= 0.0) || !(t.angular >= 0.0) || !(t.growth >= 0.0)) {
        throw std::invalid_argument("CollisionScene: a motion bound term of link '" + impl_->link_names[i] +
                                    "' is negative or not a number");
      }
    }
  }
  if (!(tolerance >= 0.0)) throw std::invalid_argument("CollisionScene: the pre-check's tolerance must be >= 0");
  return impl_->certifyMotion(link_poses, bound, cap, tolerance);
}

}  // namespace sixdof_core
