// Conveyor belts (a surface velocity on their contacts), object sources and sinks.
#include <set>

#include "sixdof_sim/conveyor.h"
#include "world_impl.h"

namespace sixdof_sim {
namespace {

// A contact on the belt's top face: its normal within ~25 deg of the belt's up axis. Contacts on the box's sides
// and ends do not move.
constexpr double kTopFaceCosine = 0.9;
// A source waits while an object's origin is closer to its spot than this times max_size (plus the jitter).
constexpr double kSpawnClearance = 1.5;
// Spawned objects start this far above the belt (m).
constexpr double kSpawnGap = 0.001;

bool finiteAndPositive(double v) { return std::isfinite(v) && v > 0.0; }

Result bad(const std::string& what, const std::string& name, const std::string& problem) {
  return {Status::kInvalidArgument, what + " '" + name + "': " + problem};
}

Eigen::Vector3d direction(const ConveyorSpec& conveyor) {
  return conveyor.pose.linear() * Eigen::Vector3d(conveyor.direction.x(), conveyor.direction.y(), 0.0).normalized();
}

}  // namespace

Result validateConveyorSpec(const ConveyorSpec& spec) {
  const std::string& n = spec.name;
  if (n.empty()) return {Status::kInvalidArgument, "conveyor name must not be empty"};
  if (!finite(spec.pose)) return bad("conveyor", n, "pose is not finite");
  if (!(spec.size.minCoeff() > 0.0) || !spec.size.allFinite())
    return bad("conveyor", n, "'size' must be > 0 in x, y and z");
  if (!std::isfinite(spec.speed)) return bad("conveyor", n, "'speed' must be finite");
  if (!spec.direction.allFinite() || !(spec.direction.norm() > 1e-9)) {
    return bad("conveyor", n, "'direction' must be a non-zero vector [x, y] in the belt plane");
  }
  if (!(spec.friction >= 0.0) || !std::isfinite(spec.friction)) return bad("conveyor", n, "'friction' must be >= 0");
  for (double c : {spec.color.r, spec.color.g, spec.color.b, spec.color.a}) {
    if (!(c >= 0.0 && c <= 1.0)) return bad("conveyor", n, "colour components must be in [0, 1]");
  }
  return Result::success();
}

Result validateSourceSpec(const SourceSpec& spec) {
  const std::string& n = spec.name;
  if (n.empty()) return {Status::kInvalidArgument, "source name must not be empty"};
  if (spec.conveyor.empty()) return bad("source", n, "'conveyor' must name a conveyor");
  if (!spec.position.allFinite()) return bad("source", n, "'position' must be finite");
  if (!(spec.lateral_jitter >= 0.0) || !std::isfinite(spec.lateral_jitter)) {
    return bad("source", n, "'lateral_jitter' must be >= 0");
  }
  if (spec.shapes.empty()) return bad("source", n, "'shapes' must not be empty");
  for (ShapeType shape : spec.shapes) {
    if (shape == ShapeType::kMesh) return bad("source", n, "'shapes' may be box, cylinder or sphere");
  }
  if (!finiteAndPositive(spec.min_size) || !(spec.max_size >= spec.min_size) || !std::isfinite(spec.max_size)) {
    return bad("source", n, "'size' [min, max] must have 0 < min <= max");
  }
  for (const Color& c : spec.colors) {
    for (double v : {c.r, c.g, c.b, c.a}) {
      if (!(v >= 0.0 && v <= 1.0)) return bad("source", n, "colour components must be in [0, 1]");
    }
  }
  if (!finiteAndPositive(spec.mass)) return bad("source", n, "'mass' must be > 0");
  if (!(spec.friction >= 0.0) || !std::isfinite(spec.friction)) return bad("source", n, "'friction' must be >= 0");
  if (!(spec.start >= 0.0) || !std::isfinite(spec.start)) return bad("source", n, "'start' must be >= 0");
  if (spec.period != 0.0) {
    if (!finiteAndPositive(spec.period)) return bad("source", n, "'period' must be > 0 (s)");
  } else if (!finiteAndPositive(spec.min_interval) || !(spec.max_interval >= spec.min_interval) ||
             !std::isfinite(spec.max_interval)) {
    return bad("source", n, "'interval' [min, max] must have 0 < min <= max (s), or give a 'period'");
  }
  if (spec.max_count < 0) return bad("source", n, "'max_count' must be >= 0 (0: no limit)");
  return Result::success();
}

Result validateSinkSpec(const SinkSpec& spec) {
  const std::string& n = spec.name;
  if (n.empty()) return {Status::kInvalidArgument, "sink name must not be empty"};
  if (spec.below_only) {
    if (!std::isfinite(spec.below)) return bad("sink", n, "'below' must be finite");
    return Result::success();
  }
  if (!finite(spec.pose)) return bad("sink", n, "pose is not finite");
  if (!(spec.size.minCoeff() > 0.0) || !spec.size.allFinite())
    return bad("sink", n, "'size' must be > 0 in x, y and z");
  return Result::success();
}

Result validateConveyors(const WorldSpec& world) {
  std::set<std::string> names;
  for (const ObjectSpec& object : world.objects) names.insert(object.name);
  for (const ConveyorSpec& conveyor : world.conveyors) {
    const Result r = validateConveyorSpec(conveyor);
    if (!r.ok()) return r;
    if (!names.insert(conveyor.name).second) {
      return bad("conveyor", conveyor.name, "its name is taken by another object or conveyor");
    }
  }
  std::set<std::string> sources;
  for (const SourceSpec& source : world.sources) {
    const Result r = validateSourceSpec(source);
    if (!r.ok()) return r;
    if (!sources.insert(source.name).second) return bad("source", source.name, "duplicate name");
    bool known = false;
    for (const ConveyorSpec& conveyor : world.conveyors) known = known || conveyor.name == source.conveyor;
    if (!known) return bad("source", source.name, "no conveyor '" + source.conveyor + "'");
  }
  std::set<std::string> sinks;
  for (const SinkSpec& sink : world.sinks) {
    const Result r = validateSinkSpec(sink);
    if (!r.ok()) return r;
    if (!sinks.insert(sink.name).second) return bad("sink", sink.name, "duplicate name");
  }
  return Result::success();
}

ObjectSpec beltObject(const ConveyorSpec& conveyor) {
  ObjectSpec belt;
  belt.name = conveyor.name;
  belt.shape.type = ShapeType::kBox;
  belt.shape.box_size = conveyor.size;
  belt.pose = conveyor.pose;
  belt.is_static = true;
  belt.friction = conveyor.friction;
  belt.color = conveyor.color;
  return belt;
}

Eigen::Vector3d beltVelocity(const ConveyorSpec& conveyor, double speed) { return speed * direction(conveyor); }

void DynamicsWorld::solveConstraints(btContactSolverInfo& solver_info) {
  if (before_solve) before_solve();
  btMultiBodyDynamicsWorld::solveConstraints(solver_info);
  if (after_solve) after_solve();
}

// Belts are static objects like tables; the solver's friction directions of their top-face contacts are set here
// (Bullet uses the given directions and target slips when SOLVER_ENABLE_FRICTION_DIRECTION_CACHING is on and a
// contact is flagged; others keep Bullet's own directions).
void World::Impl::addConveyors() {
  conveyor_speeds.clear();
  for (size_t i = 0; i < spec.conveyors.size(); ++i) {
    const Result r = addObject(beltObject(spec.conveyors[i]));
    if (!r.ok()) throw WorldError("world '" + spec.name + "': conveyor " + r.message);
    findObject(spec.conveyors[i].name)->conveyor = static_cast<int>(i);
    conveyor_speeds.push_back(spec.conveyors[i].speed);
  }
  sources.assign(spec.sources.size(), SourceRuntime());
  for (size_t i = 0; i < spec.sources.size(); ++i) {
    sources[i].rng.seed(spec.sources[i].seed);
    sources[i].next_spawn = spec.sources[i].start;
  }
  sink_counts.assign(spec.sinks.size(), 0);
  sunk.clear();
  if (!spec.conveyors.empty()) {
    world->getSolverInfo().m_solverMode |= SOLVER_ENABLE_FRICTION_DIRECTION_CACHING;
    static_cast<DynamicsWorld*>(world.get())->before_solve = [this] { applyBeltMotion(); };
  }
}

Eigen::Vector3d World::Impl::beltVelocity(size_t conveyor) const {
  return sixdof_sim::beltVelocity(spec.conveyors[conveyor], conveyor_speeds[conveyor]);
}

// Each top-face contact of a belt with a dynamic object: friction direction 1 along the belt (in the contact plane),
// 2 across it, and target slips equal to the belt's velocity along each: friction drives the object's contact point
// to the belt's velocity, bounded by the Coulomb cone like any contact. The solver's constraint row asks
// (v_body0 - v_body1) . dir = motion, the belt being either body.
void World::Impl::applyBeltMotion() {
  const int manifolds = dispatcher->getNumManifolds();
  for (int m = 0; m < manifolds; ++m) {
    btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
    const btCollisionObject* a = manifold->getBody0();
    const btCollisionObject* b = manifold->getBody1();
    auto beltOf = [](const btCollisionObject* o) -> const ObjectRuntime* {
      if (o->getUserIndex() != kObjectBody) return nullptr;
      const auto* object = static_cast<const ObjectRuntime*>(o->getUserPointer());
      return object->conveyor >= 0 ? object : nullptr;
    };
    const ObjectRuntime* belt = beltOf(a);
    const bool belt_is_a = belt != nullptr;
    if (!belt_is_a) belt = beltOf(b);
    const btCollisionObject* other = belt_is_a ? b : a;
    if (belt == nullptr || other->getUserIndex() != kObjectBody || other->isStaticObject()) continue;
    const ConveyorSpec& conveyor = spec.conveyors[belt->conveyor];
    const Eigen::Vector3d up = conveyor.pose.linear().col(2);
    const Eigen::Vector3d along = direction(conveyor);
    const Eigen::Vector3d velocity = beltVelocity(belt->conveyor);
    const double sign = belt_is_a ? -1.0 : 1.0;
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      btManifoldPoint& point = manifold->getContactPoint(p);
      const Eigen::Vector3d normal = toEigen(point.m_normalWorldOnB);  // from body1 towards body0
      if ((belt_is_a ? -normal : normal).dot(up) < kTopFaceCosine) continue;
      const Eigen::Vector3d dir1 = (along - normal * normal.dot(along)).normalized();
      const Eigen::Vector3d dir2 = dir1.cross(normal).normalized();
      point.m_lateralFrictionDir1 = toBt(dir1);
      point.m_lateralFrictionDir2 = toBt(dir2);
      point.m_contactMotion1 = sign * velocity.dot(dir1);
      point.m_contactMotion2 = sign * velocity.dot(dir2);
      point.m_contactPointFlags |= BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED;
    }
  }
}

void World::Impl::stepSources() {
  const double now = static_cast<double>(steps) * dt();
  for (size_t i = 0; i < spec.sources.size(); ++i) {
    const SourceSpec& source = spec.sources[i];
    SourceRuntime& runtime = sources[i];
    if ((source.max_count > 0 && runtime.spawned >= source.max_count) || now + 1e-9 < runtime.next_spawn) continue;
    size_t c = 0;
    while (spec.conveyors[c].name != source.conveyor) ++c;
    const ConveyorSpec& conveyor = spec.conveyors[c];
    const Eigen::Vector3d spot =
        conveyor.pose * Eigen::Vector3d(source.position.x(), source.position.y(), conveyor.size.z() / 2.0);
    const double clearance = kSpawnClearance * source.max_size + source.lateral_jitter;
    bool blocked = false;
    for (const auto& o : objects) {
      if (!o->spec.is_static && (objectPose(*o).translation() - spot).norm() < clearance) blocked = true;
    }
    if (blocked) continue;
    // The draws, always in this order: shape, size, colour, jitter, interval.
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto pick = [&](size_t count) { return std::min(count - 1, static_cast<size_t>(unit(runtime.rng) * count)); };
    ObjectSpec object;
    object.shape.type = source.shapes[pick(source.shapes.size())];
    const double size = source.min_size + (source.max_size - source.min_size) * unit(runtime.rng);
    object.shape.box_size = Eigen::Vector3d::Constant(size);
    object.shape.radius = size / 2.0;
    object.shape.length = size;
    if (!source.colors.empty()) object.color = source.colors[pick(source.colors.size())];
    const double jitter = source.lateral_jitter * (2.0 * unit(runtime.rng) - 1.0);
    object.pose = conveyor.pose * Eigen::Translation3d(source.position.x(), source.position.y() + jitter,
                                                       conveyor.size.z() / 2.0 + size / 2.0 + kSpawnGap);
    object.mass = source.mass;
    object.friction = source.friction;
    long long serial = runtime.spawned + 1;
    do {
      object.name = source.name + "_" + std::to_string(serial++);
    } while (findObject(object.name) != nullptr);
    const Result r = addObject(object);
    if (!r.ok()) throw WorldError("source '" + source.name + "': " + r.message);
    // Objects arrive moving with the belt, as from a belt upstream.
    findObject(object.name)->body->setLinearVelocity(toBt(beltVelocity(c)));
    ++runtime.spawned;
    const double interval = source.period > 0.0
                                ? source.period
                                : source.min_interval + (source.max_interval - source.min_interval) * unit(runtime.rng);
    // A spawn delayed by a blocked spot restarts the schedule from its own time.
    runtime.next_spawn = (now - runtime.next_spawn > dt() ? now : runtime.next_spawn) + interval;
  }
}

void World::Impl::stepSinks() {
  for (size_t i = 0; i < objects.size();) {
    ObjectRuntime* object = objects[i].get();
    const std::string& name = object->spec.name;
    const bool held = (grasp_fix && grasp_fix->attached() == name) || suction.held == name;
    int into = -1;
    if (!object->spec.is_static && !held) {
      const Eigen::Vector3d position = objectPose(*object).translation();
      for (size_t k = 0; k < spec.sinks.size() && into < 0; ++k) {
        const SinkSpec& sink = spec.sinks[k];
        const bool inside =
            sink.below_only ? position.z() < sink.below
                            : ((sink.pose.inverse() * position).cwiseAbs().array() <= (sink.size / 2.0).array()).all();
        if (inside) into = static_cast<int>(k);
      }
    }
    if (into < 0) {
      ++i;
      continue;
    }
    ++sink_counts[into];
    sunk.push_back(spec.sinks[into].name + ":" + name);
    removeObject(object);
  }
}

Result World::setConveyorSpeed(const std::string& conveyor, double speed) {
  Impl& d = *impl_;
  for (size_t i = 0; i < d.spec.conveyors.size(); ++i) {
    if (d.spec.conveyors[i].name != conveyor) continue;
    if (!std::isfinite(speed)) {
      return {Status::kInvalidArgument,
              "conveyor '" + conveyor + "': speed must be finite (m/s), got " + std::to_string(speed)};
    }
    d.conveyor_speeds[i] = speed;
    d.wakeObjects();  // objects asleep on a stopped belt ride again
    return Result::success();
  }
  return {Status::kUnknownObject, "unknown conveyor '" + conveyor + "'"};
}

std::vector<ConveyorState> World::conveyorStates() const {
  std::vector<ConveyorState> states;
  for (size_t i = 0; i < impl_->spec.conveyors.size(); ++i) {
    states.push_back({impl_->spec.conveyors[i].name, impl_->conveyor_speeds[i], impl_->beltVelocity(i)});
  }
  return states;
}

std::vector<SourceState> World::sourceStates() const {
  std::vector<SourceState> states;
  for (size_t i = 0; i < impl_->spec.sources.size(); ++i) {
    states.push_back({impl_->spec.sources[i].name, impl_->sources[i].spawned});
  }
  return states;
}

std::vector<SinkState> World::sinkStates() const {
  std::vector<SinkState> states;
  for (size_t i = 0; i < impl_->spec.sinks.size(); ++i) {
    states.push_back({impl_->spec.sinks[i].name, impl_->sink_counts[i]});
  }
  return states;
}

std::vector<std::string> World::takeSunkObjects() {
  std::vector<std::string> out;
  out.swap(impl_->sunk);
  return out;
}

}  // namespace sixdof_sim
