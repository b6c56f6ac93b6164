// A private wire-format helper for sixdof_commander (sixdof_scripts): the points of a trajectory_msgs/JointTrajectory
// read from a ROS message's serialized bytes into the Python message objects genpy's deserializer would give.
// Not part of the core's API (its name starts with an underscore; it is not in __init__.pyi).
#include <cstdint>
#include <cstring>
#include <string>

#include "common.h"

namespace sixdof_core::python {

namespace {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "ROS serializes little-endian; this reader copies as is");

// The smallest serialized point: four empty float64[] (a uint32 length each) and a duration (2 x int32).
constexpr size_t kMinPointSize = 4 * 4 + 8;

// A buffer's bytes, held for the call.
class Bytes {
 public:
  explicit Bytes(py::handle object) {
    if (PyObject_GetBuffer(object.ptr(), &view_, PyBUF_SIMPLE) != 0) throw py::error_already_set();
  }
  ~Bytes() { PyBuffer_Release(&view_); }
  Bytes(const Bytes&) = delete;
  Bytes& operator=(const Bytes&) = delete;
  const char* data() const { return static_cast<const char*>(view_.buf); }
  size_t size() const { return static_cast<size_t>(view_.len); }

 private:
  Py_buffer view_{};
};

// Reads fields in order from `at`; ValueError for a field that would end beyond the buffer.
class Reader {
 public:
  Reader(const Bytes& bytes, size_t at) : data_(bytes.data()), size_(bytes.size()), at_(at) {
    if (at > size_) throw py::value_error("offset " + std::to_string(at) + " beyond the " + std::to_string(size_) +
                                          " bytes");
  }
  size_t at() const { return at_; }
  size_t remaining() const { return size_ - at_; }

  void need(size_t bytes, const char* what) const {
    if (bytes > remaining()) {
      throw py::value_error(std::string(what) + " needs " + std::to_string(bytes) + " bytes at offset " +
                            std::to_string(at_) + ", " + std::to_string(remaining()) + " left");
    }
  }

  template <class T>
  T read(const char* what) {
    need(sizeof(T), what);
    T value;
    std::memcpy(&value, data_ + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }

  // A float64[]: its uint32 length, then the values; a tuple of floats as genpy's struct.unpack gives.
  py::object float64s() {
    const uint32_t count = read<uint32_t>("a float64[] length");
    need(size_t{8} * count, "a float64[]");
    py::object values = py::reinterpret_steal<py::object>(PyTuple_New(count));
    if (!values) throw py::error_already_set();
    for (uint32_t i = 0; i < count; ++i) {
      PyObject* value = PyFloat_FromDouble(read<double>("a float64"));
      if (!value) throw py::error_already_set();
      PyTuple_SET_ITEM(values.ptr(), i, value);  // steals the reference
    }
    return values;
  }

 private:
  const char* data_;
  size_t size_;
  size_t at_;
};

// An instance of `type` made as `type.__new__(type)` does: no __init__ (genpy's constructors check every keyword).
py::object bare(const py::type& type) {
  auto* kind = reinterpret_cast<PyTypeObject*>(type.ptr());
  py::object made = py::reinterpret_steal<py::object>(kind->tp_new(kind, py::tuple().ptr(), nullptr));
  if (!made) throw py::error_already_set();
  return made;
}

void set(const py::object& object, const py::str& name, const py::object& value) {
  if (PyObject_SetAttr(object.ptr(), name.ptr(), value.ptr()) != 0) throw py::error_already_set();
}

py::tuple decodeTrajectoryPoints(py::handle data, size_t offset, const py::type& point_type,
                                 const py::type& duration_type) {
  static const py::str positions("positions"), velocities("velocities"), accelerations("accelerations"),
      effort("effort"), time_from_start("time_from_start"), secs("secs"), nsecs("nsecs");
  const Bytes bytes(data);
  Reader reader(bytes, offset);
  const uint32_t count = reader.read<uint32_t>("the point count");
  reader.need(kMinPointSize * count, "the points");  // before the list is sized by a count from the wire
  py::list points(count);
  for (uint32_t i = 0; i < count; ++i) {
    py::object point = bare(point_type);
    set(point, positions, reader.float64s());
    set(point, velocities, reader.float64s());
    set(point, accelerations, reader.float64s());
    set(point, effort, reader.float64s());
    py::object duration = bare(duration_type);
    set(duration, secs, py::int_(reader.read<int32_t>("time_from_start.secs")));
    set(duration, nsecs, py::int_(reader.read<int32_t>("time_from_start.nsecs")));
    set(point, time_from_start, duration);
    PyList_SET_ITEM(points.ptr(), i, point.release().ptr());  // steals the reference
  }
  return py::make_tuple(std::move(points), reader.at());
}

}  // namespace

void bindWireFormat(py::module_& m) {
  m.def("_decode_trajectory_points", &decodeTrajectoryPoints, py::arg("data"), py::arg("offset"),
        py::arg("point_type"), py::arg("duration_type"),
        "A private wire-format helper of sixdof_commander (not the core's API): the points of a serialized "
        "trajectory_msgs/JointTrajectory, read from data (bytes or any buffer) at offset, as (points, the offset "
        "after them).\n\n"
        "The layout read, little-endian as ROS serializes: a uint32 count, then per point its positions, "
        "velocities, accelerations and effort (each float64[]: a uint32 length, then that many float64) and its "
        "time_from_start (int32 secs, int32 nsecs). Each point is point_type.__new__(point_type) with those five "
        "attributes set (no __init__): tuples of floats for the float64[] and duration_type.__new__(duration_type) "
        "with secs and nsecs as read, the objects genpy's deserializer gives. Bytes that end before the points do "
        "raise ValueError; nothing is read beyond the buffer.");
}

}  // namespace sixdof_core::python
