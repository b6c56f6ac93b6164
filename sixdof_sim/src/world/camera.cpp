#include "sixdof_sim/camera.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "camera_meshes.h"
#include "sixdof_core/robot_model.h"

namespace sixdof_sim {
namespace {

// Share of a surface's colour lit regardless of its angle to the light: surfaces seen edge-on stay
// recognisably coloured instead of going black.
constexpr float kAmbient = 0.3f;
// The infinite ground plane as a square of this half size (m): beyond any sensible far clip.
constexpr double kGroundHalfSize = 500.0;
const Color kGroundColor{0.45, 0.45, 0.45, 1.0};
const Color kDefaultLinkColor{0.7, 0.7, 0.7, 1.0};
// Rays are cast in 4 x 4 pixel packets (Embree's 16-wide packets: native with AVX-512, two 8-wide halves
// otherwise); threads take 4-row strips of the image in turn.
constexpr int kPacketSide = 4;

bool validName(const std::string& name) {
  if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0]))) return false;
  return std::all_of(name.begin(), name.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

bool sameLook(const ObjectSpec& a, const ObjectSpec& b) {
  const Shape& s = a.shape;
  const Shape& t = b.shape;
  return s.type == t.type && s.box_size == t.box_size && s.radius == t.radius && s.length == t.length &&
         s.mesh_resource == t.mesh_resource && s.mesh_scale == t.mesh_scale && a.color.r == b.color.r &&
         a.color.g == b.color.g && a.color.b == b.color.b;
}

Eigen::Affine3d scaling(const Eigen::Vector3d& s) { return Eigen::Affine3d(Eigen::Scaling(s)); }

}  // namespace

CameraIntrinsics cameraIntrinsics(const CameraSpec& camera) {
  CameraIntrinsics k;
  k.fx = camera.width / (2.0 * std::tan(camera.horizontal_fov / 2.0));
  k.fy = k.fx;
  k.cx = (camera.width - 1) / 2.0;
  k.cy = (camera.height - 1) / 2.0;
  return k;
}

Eigen::Isometry3d opticalInLink() {
  // rpy(-pi/2, 0, -pi/2): optical z = link x (forward), optical x = -link y (right), optical y = -link z (down).
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return t;
}

Result validateCameraSpec(const CameraSpec& c) {
  auto bad = [](const std::string& what) { return Result{Status::kInvalidArgument, what}; };
  auto text = [](double v) {
    std::ostringstream out;
    out << v;
    return out.str();
  };
  if (!validName(c.name)) {
    return bad("'name' must start with a letter and hold only letters, digits and '_' (it names topics and "
               "frames), got '" +
               c.name + "'");
  }
  if (!c.pose.matrix().allFinite()) return bad("'position' and 'rpy' must be finite");
  constexpr int kMaxSide = 8192;
  if (c.width <= 0 || c.width > kMaxSide) {
    return bad("'width' must be in [1, " + std::to_string(kMaxSide) + "] pixels, got " + std::to_string(c.width));
  }
  if (c.height <= 0 || c.height > kMaxSide) {
    return bad("'height' must be in [1, " + std::to_string(kMaxSide) + "] pixels, got " + std::to_string(c.height));
  }
  if (!(c.horizontal_fov > 0.0 && c.horizontal_fov < M_PI)) {
    return bad("'horizontal_fov_deg' must be in (0, 180) degrees, got " + text(c.horizontal_fov * 180.0 / M_PI));
  }
  if (!(c.rate > 0.0) || !std::isfinite(c.rate)) return bad("'rate' must be > 0 (Hz), got " + text(c.rate));
  if (!(c.near_clip > 0.0) || !std::isfinite(c.near_clip)) {
    return bad("'near' must be > 0 (m), got " + text(c.near_clip));
  }
  if (!(c.far_clip > c.near_clip) || !std::isfinite(c.far_clip)) {
    return bad("'near' must be < 'far', got near " + text(c.near_clip) + " and far " + text(c.far_clip));
  }
  if (!(c.depth_noise_stddev >= 0.0) || !std::isfinite(c.depth_noise_stddev)) {
    return bad("'depth_noise_stddev' must be >= 0 (m), got " + text(c.depth_noise_stddev));
  }
  if (!(c.depth_noise_quadratic >= 0.0) || !std::isfinite(c.depth_noise_quadratic)) {
    return bad("'depth_noise_quadratic' must be >= 0 (1/m), got " + text(c.depth_noise_quadratic));
  }
  return Result::success();
}

struct CameraRenderer::Impl {
  // One placed copy of a shape's hierarchy in the top-level scene.
  struct Instance {
    RTCGeometry geometry = nullptr;
    unsigned id = RTC_INVALID_GEOMETRY_ID;
  };
  struct LinkVisual {
    std::string link;
    Eigen::Affine3d in_link;  // the unit shape (scaled) in the link frame
    Color color;
    Instance instance;
  };
  struct ObjectVisual {
    ObjectSpec spec;
    Eigen::Affine3d in_object;  // the unit shape (scaled) in the object frame
    Instance instance;
  };
  // What shading needs of the instance a ray hit, by instance id.
  struct Shading {
    Eigen::Matrix3f normal_to_world = Eigen::Matrix3f::Identity();  // inverse transpose of the linear part
    float rgb[3] = {0.0f, 0.0f, 0.0f};
  };

  const World& world;
  std::vector<CameraSpec> cameras;
  std::vector<std::uint64_t> frames;  // frames rendered per camera (noise seeds)
  int threads = 1;
  RTCDevice device = nullptr;
  RTCScene top = nullptr;
  std::map<std::string, RTCScene> shapes;  // one hierarchy per unit primitive and per mesh file
  std::vector<LinkVisual> links;
  std::map<std::string, ObjectVisual> objects;
  Instance ground;  // geometry null without a ground plane
  std::vector<Shading> shading;
  std::string error;  // the device's last error

  explicit Impl(const World& w) : world(w) {}

  ~Impl() {
    for (LinkVisual& l : links) rtcReleaseGeometry(l.instance.geometry);
    for (auto& entry : objects) rtcReleaseGeometry(entry.second.instance.geometry);
    if (ground.geometry != nullptr) rtcReleaseGeometry(ground.geometry);
    for (auto& entry : shapes) rtcReleaseScene(entry.second);
    if (top != nullptr) rtcReleaseScene(top);
    if (device != nullptr) rtcReleaseDevice(device);
  }

  void check(const std::string& what) const {
    if (!error.empty()) throw WorldError("camera renderer: " + what + ": " + error);
  }

  RTCScene triangleScene(const TriangleMesh& mesh) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), mesh.vertices.size() / 3));
    auto* i = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), mesh.indices.size() / 3));
    std::copy(mesh.vertices.begin(), mesh.vertices.end(), v);
    std::copy(mesh.indices.begin(), mesh.indices.end(), i);
    return commitShape(g);
  }

  RTCScene commitShape(RTCGeometry g) {
    rtcCommitGeometry(g);
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
    return scene;
  }

  RTCScene unitShape(const std::string& key) {
    auto it = shapes.find(key);
    if (it != shapes.end()) return it->second;
    RTCScene scene = nullptr;
    if (key == "box") {
      scene = triangleScene(unitBox());
    } else if (key == "cylinder") {
      scene = triangleScene(unitCylinder());
    } else if (key == "square") {
      scene = triangleScene(unitSquare());
    } else if (key == "sphere") {
      // A true sphere (ray-sphere intersection), not a tessellation.
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
      auto* p = static_cast<float*>(
          rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
      p[0] = p[1] = p[2] = 0.0f;
      p[3] = 1.0f;
      scene = commitShape(g);
    } else {
      scene = triangleScene(meshFileTriangles(key));
    }
    check("building shape '" + key + "'");
    return shapes.emplace(key, scene).first->second;
  }

  // The hierarchy of a shape and the transform from its unit shape to the shape in its own frame.
  RTCScene shapeScene(const Shape& shape, Eigen::Affine3d* unit_to_shape) {
    switch (shape.type) {
      case ShapeType::kBox:
        *unit_to_shape = scaling(shape.box_size);
        return unitShape("box");
      case ShapeType::kCylinder:
        *unit_to_shape = scaling(Eigen::Vector3d(shape.radius, shape.radius, shape.length));
        return unitShape("cylinder");
      case ShapeType::kSphere:
        *unit_to_shape = scaling(Eigen::Vector3d::Constant(shape.radius));
        return unitShape("sphere");
      case ShapeType::kMesh: {
        std::string path = shape.mesh_path;  // robot link meshes come resolved by the model
        if (path.empty()) {
          try {
            path = world.packageResolver().resolve(shape.mesh_resource);
          } catch (const sixdof_core::RobotModelError& e) {
            throw WorldError(e.what());
          }
        }
        *unit_to_shape = scaling(shape.mesh_scale);
        return unitShape(path);
      }
    }
    throw WorldError("unknown shape type");
  }

  Instance addInstance(RTCScene scene) {
    Instance instance;
    instance.geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(instance.geometry, scene);
    rtcSetGeometryTimeStepCount(instance.geometry, 1);
    instance.id = rtcAttachGeometry(top, instance.geometry);
    if (shading.size() <= instance.id) shading.resize(instance.id + 1);
    return instance;
  }

  void removeInstance(const Instance& instance) {
    rtcDetachGeometry(top, instance.id);
    rtcReleaseGeometry(instance.geometry);
  }

  void place(const Instance& instance, const Eigen::Affine3d& transform, const Color& color) {
    const Eigen::Matrix<float, 3, 4> m = transform.matrix().topRows<3>().cast<float>();
    rtcSetGeometryTransform(instance.geometry, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, m.data());
    rtcCommitGeometry(instance.geometry);
    Shading& s = shading[instance.id];
    s.normal_to_world = transform.linear().inverse().transpose().cast<float>();
    s.rgb[0] = static_cast<float>(color.r);
    s.rgb[1] = static_cast<float>(color.g);
    s.rgb[2] = static_cast<float>(color.b);
  }

  // The robot's visuals (their collision shapes for links without any) from the world's core robot model.
  void addRobot() {
    for (const sixdof_core::LinkModel& link : world.robotModel().links()) {
      auto add = [&](const sixdof_core::PlacedShape& placed, const Color& color) {
        Eigen::Affine3d unit_to_shape;
        LinkVisual visual;
        try {
          visual.instance = addInstance(shapeScene(placed.shape, &unit_to_shape));
        } catch (const WorldError& e) {
          throw WorldError("camera renderer: URDF link '" + link.name + "': " + e.what());
        }
        visual.link = link.name;
        visual.in_link = Eigen::Affine3d(placed.origin.matrix()) * unit_to_shape;
        visual.color = color;
        links.push_back(visual);
      };
      if (!link.visuals.empty()) {
        for (const sixdof_core::LinkVisual& v : link.visuals) {
          add(v.placed, v.rgba ? Color{(*v.rgba)[0], (*v.rgba)[1], (*v.rgba)[2], 1.0} : kDefaultLinkColor);
        }
      } else {
        for (const sixdof_core::PlacedShape& c : link.collision.shapes) add(c, kDefaultLinkColor);
      }
    }
  }

  // Moves every instance to the world's current poses; adds and removes objects.
  void sync() {
    Eigen::Isometry3d pose;
    for (const LinkVisual& l : links) {
      if (world.linkPose(l.link, &pose).ok()) place(l.instance, pose * l.in_link, l.color);
    }
    std::set<std::string> present;
    ObjectState state;
    for (const std::string& name : world.objectNames()) {
      if (!world.objectState(name, &state).ok()) continue;
      present.insert(name);
      auto it = objects.find(name);
      if (it != objects.end() && !sameLook(it->second.spec, state.spec)) {
        removeInstance(it->second.instance);
        objects.erase(it);
        it = objects.end();
      }
      if (it == objects.end()) {
        ObjectVisual visual;
        Eigen::Affine3d unit_to_shape;
        try {
          visual.instance = addInstance(shapeScene(state.spec.shape, &unit_to_shape));
        } catch (const WorldError& e) {
          throw WorldError("camera renderer: object '" + name + "': " + e.what());
        }
        visual.in_object = unit_to_shape;
        it = objects.emplace(name, visual).first;
      }
      it->second.spec = state.spec;
      place(it->second.instance, state.spec.pose * it->second.in_object, state.spec.color);
    }
    for (auto it = objects.begin(); it != objects.end();) {
      if (present.count(it->first)) {
        ++it;
      } else {
        removeInstance(it->second.instance);
        it = objects.erase(it);
      }
    }
    rtcCommitScene(top);
    check("updating the scene");
  }

  Eigen::Isometry3d linkPose(const CameraSpec& camera) const {
    if (camera.parent_link.empty()) return camera.pose;
    Eigen::Isometry3d parent = Eigen::Isometry3d::Identity();
    world.linkPose(camera.parent_link, &parent);  // checked at construction
    return parent * camera.pose;
  }

  void render(size_t index, CameraFrame* frame) {
    sync();
    const CameraSpec& camera = cameras.at(index);
    const std::uint64_t frame_index = frames[index]++;
    const CameraIntrinsics k = cameraIntrinsics(camera);
    const int width = camera.width, height = camera.height;
    frame->width = width;
    frame->height = height;
    frame->rgb.assign(static_cast<size_t>(width) * height * 3, 0);
    frame->depth.assign(static_cast<size_t>(width) * height, std::numeric_limits<float>::quiet_NaN());
    frame->link_pose = linkPose(camera);
    frame->sim_time = world.simTime();

    // Ray of pixel (u, v): origin o, direction d0 + u du + v dv, whose optical z component is 1, so the
    // hit distance in units of the direction is the depth along the optical axis.
    const Eigen::Isometry3d optical = frame->link_pose * opticalInLink();
    const Eigen::Matrix3d r = optical.linear();
    const Eigen::Vector3f o = optical.translation().cast<float>();
    const Eigen::Vector3f d0 = (r * Eigen::Vector3d(-k.cx / k.fx, -k.cy / k.fy, 1.0)).cast<float>();
    const Eigen::Vector3f du = (r.col(0) / k.fx).cast<float>();
    const Eigen::Vector3f dv = (r.col(1) / k.fy).cast<float>();
    const float near_clip = static_cast<float>(camera.near_clip);
    const float far_clip = static_cast<float>(camera.far_clip);
    const float noise = static_cast<float>(camera.depth_noise_stddev);
    const float noise_quadratic = static_cast<float>(camera.depth_noise_quadratic);

    // Raw pointers: stores through the vectors' data would make the compiler reload them for every pixel.
    std::uint8_t* const rgb_out = frame->rgb.data();
    float* const depth_out = frame->depth.data();
    const Shading* const shade = shading.data();
    const int strips = (height + kPacketSide - 1) / kPacketSide;
    std::atomic<int> next_strip{0};
    RTCScene scene = top;
    const std::uint64_t seed = camera.seed;
    // The lambda copies what the pixel loop reads: captures by reference would be reloaded after every byte
    // stored (a uint8_t store may alias anything).
    auto work = [=, &next_strip] {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      for (int strip = next_strip++; strip < strips; strip = next_strip++) {
        const int v0 = strip * kPacketSide;
        for (int u0 = 0; u0 < width; u0 += kPacketSide) {
          alignas(64) int valid[16];
          alignas(64) RTCRayHit16 packet;
          for (int i = 0; i < 16; ++i) {
            const int u = u0 + i % kPacketSide, v = v0 + i / kPacketSide;
            valid[i] = (u < width && v < height) ? -1 : 0;
            const Eigen::Vector3f d = d0 + static_cast<float>(u) * du + static_cast<float>(v) * dv;
            packet.ray.org_x[i] = o.x();
            packet.ray.org_y[i] = o.y();
            packet.ray.org_z[i] = o.z();
            packet.ray.dir_x[i] = d.x();
            packet.ray.dir_y[i] = d.y();
            packet.ray.dir_z[i] = d.z();
            packet.ray.tnear[i] = 0.0f;
            packet.ray.tfar[i] = std::numeric_limits<float>::infinity();
            packet.ray.time[i] = 0.0f;
            packet.ray.mask[i] = 0xFFFFFFFFu;
            packet.ray.id[i] = static_cast<unsigned>(i);
            packet.ray.flags[i] = 0;
            packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
            packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
          }
          rtcIntersect16(valid, scene, &context, &packet);
          for (int i = 0; i < 16; ++i) {
            const unsigned instance = packet.hit.instID[0][i];
            if (!valid[i] || instance == RTC_INVALID_GEOMETRY_ID) continue;
            const size_t pixel = static_cast<size_t>(v0 + i / kPacketSide) * width + u0 + i % kPacketSide;
            const Shading& s = shade[instance];
            const Eigen::Vector3f n =
                s.normal_to_world * Eigen::Vector3f(packet.hit.Ng_x[i], packet.hit.Ng_y[i], packet.hit.Ng_z[i]);
            const Eigen::Vector3f d(packet.ray.dir_x[i], packet.ray.dir_y[i], packet.ray.dir_z[i]);
            const float cosine = std::abs(n.dot(d)) / std::sqrt(std::max(n.squaredNorm() * d.squaredNorm(), 1e-30f));
            const float light = 255.0f * (kAmbient + (1.0f - kAmbient) * cosine);
            std::uint8_t* rgb = rgb_out + 3 * pixel;
            for (int c = 0; c < 3; ++c) rgb[c] = static_cast<std::uint8_t>(std::min(255.0f, s.rgb[c] * light) + 0.5f);
            const float depth = packet.ray.tfar[i];
            if (depth >= near_clip && depth <= far_clip) depth_out[pixel] = depth;
          }
        }
        if (noise > 0.0f || noise_quadratic > 0.0f) {
          // Per strip and frame: the same noise whichever thread renders the strip.
          std::seed_seq strip_seed{seed, frame_index, static_cast<std::uint64_t>(strip)};
          std::mt19937 rng(strip_seed);
          std::normal_distribution<float> gauss(0.0f, 1.0f);
          const size_t end = std::min<size_t>(static_cast<size_t>(v0 + kPacketSide), height) * width;
          for (size_t p = static_cast<size_t>(v0) * width; p < end; ++p) {
            const float depth = depth_out[p];
            if (!std::isnan(depth)) depth_out[p] += gauss(rng) * (noise + noise_quadratic * depth * depth);
          }
        }
      }
    };
    std::vector<std::thread> helpers;
    for (int t = 1; t < threads; ++t) helpers.emplace_back(work);
    work();
    for (std::thread& t : helpers) t.join();
  }
};

CameraRenderer::CameraRenderer(const World& world, const WorldSpec& spec, const CameraRendererOptions& options)
    : impl_(std::make_unique<Impl>(world)) {
  Impl& d = *impl_;
  const std::vector<std::string> link_names = world.linkNames();
  const std::set<std::string> robot_links(link_names.begin(), link_names.end());
  std::set<std::string> names;
  for (const CameraSpec& camera : spec.cameras) {
    const std::string context = "camera '" + camera.name + "': ";
    const Result valid = validateCameraSpec(camera);
    if (!valid.ok()) throw WorldError(context + valid.message);
    if (!names.insert(camera.name).second) throw WorldError(context + "duplicate camera 'name'");
    if (!camera.parent_link.empty() && !robot_links.count(camera.parent_link)) {
      throw WorldError(context + "'parent' '" + camera.parent_link + "' is not a link of the robot");
    }
    for (const std::string& frame : {camera.name + "_link", camera.name + "_optical_frame"}) {
      if (robot_links.count(frame)) throw WorldError(context + "its frame '" + frame + "' is a robot link");
    }
  }
  d.cameras = spec.cameras;
  d.frames.assign(spec.cameras.size(), 0);
  d.threads =
      options.threads > 0 ? options.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  // BVH builds stay on the calling thread: shapes are built once and the per-frame top-level build of a few
  // dozen instances is too small to spread.
  d.device = rtcNewDevice("threads=1");
  if (d.device == nullptr) throw WorldError("camera renderer: Embree device creation failed");
  rtcSetDeviceErrorFunction(
      d.device, [](void* user, RTCError, const char* text) { static_cast<Impl*>(user)->error = text; }, &d);
  d.top = rtcNewScene(d.device);
  rtcSetSceneFlags(d.top, RTC_SCENE_FLAG_DYNAMIC);
  rtcSetSceneBuildQuality(d.top, RTC_BUILD_QUALITY_LOW);
  d.addRobot();
  if (spec.ground.enabled) {
    d.ground = d.addInstance(d.unitShape("square"));
    Eigen::Affine3d t = Eigen::Affine3d::Identity();
    t.translation().z() = spec.ground.z;
    d.place(d.ground, t * scaling(Eigen::Vector3d(kGroundHalfSize, kGroundHalfSize, 1.0)), kGroundColor);
  }
  d.sync();
}

CameraRenderer::~CameraRenderer() = default;

const std::vector<CameraSpec>& CameraRenderer::cameras() const { return impl_->cameras; }

Eigen::Isometry3d CameraRenderer::linkPose(size_t camera) const { return impl_->linkPose(impl_->cameras.at(camera)); }

void CameraRenderer::render(size_t camera, CameraFrame* frame) { impl_->render(camera, frame); }

}  // namespace sixdof_sim
