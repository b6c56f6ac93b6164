// A private wire-format helper for sixdof_commander (sixdof_scripts): ROS 1 messages to and from their serialized
// bytes, as genpy's generated (de)serializers make and read them, for the message classes described by a layout
// that sixdof_commander builds from genpy's slots. Not part of the core's API (its name starts with an underscore;
// it is not in __init__.pyi).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "common.h"

// After Python.h (common.h): PyMemberDef, the slots of genpy's message classes.
#include <structmember.h>

namespace sixdof_core::python {

namespace {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "ROS serializes little-endian; this codec copies as is");

enum class Kind : uint8_t {
  kBool,
  kInt8,
  kUInt8,
  kInt16,
  kUInt16,
  kInt32,
  kUInt32,
  kInt64,
  kUInt64,
  kFloat32,
  kFloat64,
  kString,
  kTime,
  kDuration,
  kMessage,
};

constexpr int64_t kScalar = -2;    // a field that is one value
constexpr int64_t kVariable = -1;  // T[]: a uint32 count on the wire, then the values

// How a primitive value is read: the Python object of the bytes at `data` (as many as the kind's size).
using ReadValue = PyObject* (*)(const char* data);

PyObject* readBool(const char* data) { return PyBool_FromLong(*data != 0); }

template <class T>
PyObject* readInteger(const char* data) {
  T value;
  std::memcpy(&value, data, sizeof(T));
  if constexpr (std::is_signed_v<T>) {
    return PyLong_FromLongLong(value);
  } else {
    return PyLong_FromUnsignedLongLong(value);
  }
}

template <class T>
PyObject* readReal(const char* data) {
  T value;
  std::memcpy(&value, data, sizeof(T));
  return PyFloat_FromDouble(value);
}

struct KindInfo {
  const char* name;  // the layout's name of the kind: ROS's primitive types (char and byte given as uint8, int8)
  Kind kind;
  size_t size;                // bytes on the wire (the smallest a string or message takes)
  ReadValue read = nullptr;   // numbers and bools
  int64_t low = 0, high = 0;  // the range of an integer written (struct.pack's; uint64 is checked apart)
};

// Indexed by Kind.
constexpr KindInfo kKinds[] = {
    {"bool", Kind::kBool, 1, readBool, 0, UINT8_MAX},
    {"int8", Kind::kInt8, 1, readInteger<int8_t>, INT8_MIN, INT8_MAX},
    {"uint8", Kind::kUInt8, 1, readInteger<uint8_t>, 0, UINT8_MAX},
    {"int16", Kind::kInt16, 2, readInteger<int16_t>, INT16_MIN, INT16_MAX},
    {"uint16", Kind::kUInt16, 2, readInteger<uint16_t>, 0, UINT16_MAX},
    {"int32", Kind::kInt32, 4, readInteger<int32_t>, INT32_MIN, INT32_MAX},
    {"uint32", Kind::kUInt32, 4, readInteger<uint32_t>, 0, UINT32_MAX},
    {"int64", Kind::kInt64, 8, readInteger<int64_t>, INT64_MIN, INT64_MAX},
    {"uint64", Kind::kUInt64, 8, readInteger<uint64_t>},
    {"float32", Kind::kFloat32, 4, readReal<float>},
    {"float64", Kind::kFloat64, 8, readReal<double>},
    {"string", Kind::kString, 4},
    {"time", Kind::kTime, 8},
    {"duration", Kind::kDuration, 8},
    {"message", Kind::kMessage, 0},
};

constexpr bool kindsInOrder() {
  for (size_t i = 0; i < std::size(kKinds); ++i) {
    if (static_cast<size_t>(kKinds[i].kind) != i) return false;
  }
  return true;
}
static_assert(kindsInOrder(), "kKinds is indexed by Kind");

const KindInfo& info(Kind kind) { return kKinds[static_cast<size_t>(kind)]; }

bool isNumber(Kind kind) { return kind <= Kind::kFloat64 && kind != Kind::kBool; }

// Where a decoded value is stored in its object: the offset of the instance's slot for it (see slotOffset), or -1:
// through setattr.
using SlotOffset = Py_ssize_t;

struct Field {
  py::str name;
  Kind kind = Kind::kFloat64;
  int64_t count = kScalar;
  size_t node = 0;        // kMessage: the nested message's node
  py::object type;        // kTime, kDuration: the class of the values (genpy.Time, genpy.Duration)
  size_t element_size = 0;  // bytes one value takes at least on the wire
  SlotOffset offset = -1;   // the field's slot in the message's instances
  SlotOffset secs_offset = -1, nsecs_offset = -1;  // kTime, kDuration: the value's slots
};

struct Node {
  py::object type;
  std::string type_name;
  std::vector<Field> fields;
  size_t min_size = 0;  // bytes the message takes at least on the wire
};

// The exception raised for a value encode() does not write (the caller serializes with genpy instead).
struct Unwritten {
  std::string what;
};

// An instance of `type` made as `type.__new__(type)` does: no __init__ (genpy's constructors check every keyword
// and make default values only to have them replaced).
py::object bare(PyObject* type) {
  auto* kind = reinterpret_cast<PyTypeObject*>(type);
  static PyObject* const no_arguments = PyTuple_New(0);  // kept for the process's life, as the names below
  py::object made = py::reinterpret_steal<py::object>(kind->tp_new(kind, no_arguments, nullptr));
  if (!made) throw py::error_already_set();
  return made;
}

void setField(const py::object& object, PyObject* name, const py::object& value) {
  if (PyObject_SetAttr(object.ptr(), name, value.ptr()) != 0) throw py::error_already_set();
}

// The offset of the slot in which setattr(instance, name, value) stores value for instances of `type`: found when
// setattr is the generic one and the attribute a writable object slot (a __slots__ entry, as every field of genpy's
// message classes and genpy.Time's secs and nsecs), -1 otherwise. Storing there is what setattr does then, without
// the attribute's lookup on every call.
SlotOffset slotOffset(PyObject* type, PyObject* name) {
  auto* kind = reinterpret_cast<PyTypeObject*>(type);
  if (kind->tp_setattro != PyObject_GenericSetAttr) return -1;
  PyObject* descriptor = _PyType_Lookup(kind, name);  // borrowed; the attribute setattr finds through the MRO
  if (descriptor == nullptr || Py_TYPE(descriptor) != &PyMemberDescr_Type) return -1;
  const PyMemberDef* member = reinterpret_cast<PyMemberDescrObject*>(descriptor)->d_member;
  if (member->type != T_OBJECT_EX || (member->flags & READONLY) != 0) return -1;
  return member->offset;
}

// setattr(object, name, value) through the slot at `offset` when there is one (object is an instance of the type
// the offset was found for).
void store(const py::object& object, SlotOffset offset, PyObject* name, py::object value) {
  if (offset < 0) {
    setField(object, name, value);
    return;
  }
  PyObject** slot = reinterpret_cast<PyObject**>(reinterpret_cast<char*>(object.ptr()) + offset);
  PyObject* old = *slot;
  *slot = value.release().ptr();
  Py_XDECREF(old);
}

// The names of a time's fields (interned, kept for the process's life).
PyObject* secsName() {
  static PyObject* const name = PyUnicode_InternFromString("secs");
  return name;
}
PyObject* nsecsName() {
  static PyObject* const name = PyUnicode_InternFromString("nsecs");
  return name;
}

py::object steal(PyObject* made) {
  if (made == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::object>(made);
}

// Reads values in order; ValueError naming the field for bytes that end before it does.
class Reader {
 public:
  Reader(const char* data, size_t size) : data_(data), size_(size) {}

  void need(size_t bytes, const Node& node, const Field& field) const {
    if (bytes > size_ - at_) {
      throw py::value_error(node.type_name + "." + std::string(field.name) + " needs " + std::to_string(bytes) +
                            " bytes at offset " + std::to_string(at_) + ", " + std::to_string(size_ - at_) +
                            " left");
    }
  }

  template <class T>
  T raw() {  // after need()
    T value;
    std::memcpy(&value, data_ + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }

  const char* take(size_t bytes) {  // after need()
    const char* start = data_ + at_;
    at_ += bytes;
    return start;
  }

 private:
  const char* data_;
  size_t size_;
  size_t at_ = 0;
};

class Writer {
 public:
  template <class T>
  void raw(T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out_.append(bytes, sizeof(T));
  }
  void append(const char* data, size_t size) { out_.append(data, size); }
  const std::string& bytes() const { return out_; }
  void reserve(size_t size) { out_.reserve(size); }

 private:
  std::string out_;
};

class MessageCodec {
 public:
  explicit MessageCodec(const py::handle& layout) { root_ = compile(layout); }

  py::object decode(const py::handle& data) const {
    Py_buffer view;
    if (PyObject_GetBuffer(data.ptr(), &view, PyBUF_SIMPLE) != 0) throw py::error_already_set();
    struct Release {
      Py_buffer* view;
      ~Release() { PyBuffer_Release(view); }
    } release{&view};
    Reader reader(static_cast<const char*>(view.buf), static_cast<size_t>(view.len));
    return decodeMessage(nodes_[root_], reader);
  }

  py::bytes encode(const py::handle& message) const {
    Writer writer;
    writer.reserve(1024);
    try {
      encodeMessage(nodes_[root_], message, writer);
    } catch (const Unwritten& unwritten) {
      throw py::type_error(unwritten.what);
    }
    return py::bytes(writer.bytes().data(), writer.bytes().size());
  }

  py::object type() const { return nodes_[root_].type; }

 private:
  size_t compile(const py::handle& layout) {
    const auto entry = layout.cast<py::tuple>();
    if (entry.size() != 2) throw py::value_error("a message's layout is (class, fields)");
    const py::object type = entry[0];
    if (!PyType_Check(type.ptr())) throw py::type_error("a message's layout starts with its class");
    if (const auto known = index_.find(type.ptr()); known != index_.end()) return known->second;
    Node node;
    node.type = type;
    node.type_name = py::str(type.attr("__name__"));
    for (const py::handle& spec : entry[1].cast<py::tuple>()) {
      const auto parts = spec.cast<py::tuple>();
      if (parts.size() != 4) throw py::value_error(node.type_name + ": a field's layout is (name, kind, count, sub)");
      Field field;
      field.name = parts[0].cast<py::str>();
      field.offset = slotOffset(type.ptr(), field.name.ptr());
      const auto kind_name = parts[1].cast<std::string>();
      const KindInfo* kind = nullptr;
      for (const KindInfo& known : kKinds) {
        if (kind_name == known.name) kind = &known;
      }
      if (kind == nullptr) {
        throw py::value_error(node.type_name + "." + std::string(field.name) + ": unknown kind '" + kind_name + "'");
      }
      field.kind = kind->kind;
      field.element_size = kind->size;
      field.count = parts[2].cast<int64_t>();
      if (field.count < kScalar) throw py::value_error(node.type_name + "." + std::string(field.name) + ": count");
      if (field.kind == Kind::kMessage) {
        field.node = compile(parts[3]);
        field.element_size = nodes_[field.node].min_size;
      } else if (field.kind == Kind::kTime || field.kind == Kind::kDuration) {
        field.type = py::reinterpret_borrow<py::object>(parts[3]);
        if (!PyType_Check(field.type.ptr())) {
          throw py::type_error(node.type_name + "." + std::string(field.name) + ": a time's layout names its class");
        }
        field.secs_offset = slotOffset(field.type.ptr(), secsName());
        field.nsecs_offset = slotOffset(field.type.ptr(), nsecsName());
      }
      node.min_size += field.count == kScalar     ? field.element_size
                       : field.count == kVariable ? 4
                                                  : field.element_size * static_cast<size_t>(field.count);
      node.fields.push_back(std::move(field));
    }
    nodes_.push_back(std::move(node));
    index_.emplace(type.ptr(), nodes_.size() - 1);
    return nodes_.size() - 1;
  }

  // ---- decoding: the objects genpy's deserializer gives ----

  py::object decodeMessage(const Node& node, Reader& reader) const {
    py::object message = bare(node.type.ptr());
    for (const Field& field : node.fields) {
      store(message, field.offset, field.name.ptr(), decodeField(node, field, reader));
    }
    return message;
  }

  py::object decodeField(const Node& node, const Field& field, Reader& reader) const {
    if (field.count == kScalar) return decodeValue(node, field, reader);
    size_t count = static_cast<size_t>(field.count);
    if (field.count == kVariable) {
      reader.need(4, node, field);
      count = reader.raw<uint32_t>();
    }
    // Before anything is sized by a count from the wire (a message without fields counted as a byte: genpy reads
    // any count of those, this codec no more than the bytes left).
    reader.need(count * std::max<size_t>(field.element_size, 1), node, field);
    if (field.kind == Kind::kUInt8) {  // uint8[] and char[]: bytes
      return steal(PyBytes_FromStringAndSize(reader.take(count), static_cast<Py_ssize_t>(count)));
    }
    if (isNumber(field.kind)) {  // struct.unpack's tuple, from the bytes checked above
      const ReadValue read = info(field.kind).read;
      py::object values = steal(PyTuple_New(static_cast<Py_ssize_t>(count)));
      for (size_t i = 0; i < count; ++i) {
        PyTuple_SET_ITEM(values.ptr(), i, steal(read(reader.take(field.element_size))).release().ptr());
      }
      return values;
    }
    py::object values = steal(PyList_New(static_cast<Py_ssize_t>(count)));  // bool[] (as bools), strings, messages
    for (size_t i = 0; i < count; ++i) {
      PyList_SET_ITEM(values.ptr(), i, decodeValue(node, field, reader).release().ptr());
    }
    return values;
  }

  py::object decodeValue(const Node& node, const Field& field, Reader& reader) const {
    if (field.kind == Kind::kMessage) return decodeMessage(nodes_[field.node], reader);
    reader.need(field.element_size, node, field);
    if (field.kind <= Kind::kFloat64) return steal(info(field.kind).read(reader.take(field.element_size)));
    switch (field.kind) {
      case Kind::kString: {
        const uint32_t size = reader.raw<uint32_t>();
        reader.need(size, node, field);
        // Strict: bytes that are not UTF-8 raise UnicodeDecodeError (genpy replaces them and logs once).
        return steal(PyUnicode_DecodeUTF8(reader.take(size), size, "strict"));
      }
      case Kind::kTime:
      case Kind::kDuration: {  // the values as read: genpy normalizes only a message's own time fields
        py::object stamp = bare(field.type.ptr());
        if (field.kind == Kind::kTime) {
          store(stamp, field.secs_offset, secsName(), steal(PyLong_FromUnsignedLong(reader.raw<uint32_t>())));
          store(stamp, field.nsecs_offset, nsecsName(), steal(PyLong_FromUnsignedLong(reader.raw<uint32_t>())));
        } else {
          store(stamp, field.secs_offset, secsName(), steal(PyLong_FromLong(reader.raw<int32_t>())));
          store(stamp, field.nsecs_offset, nsecsName(), steal(PyLong_FromLong(reader.raw<int32_t>())));
        }
        return stamp;
      }
      default:
        break;
    }
    throw py::value_error("unreachable field kind");
  }

  // ---- encoding: the bytes genpy's serializer writes, for the values it writes them from ----

  void encodeMessage(const Node& node, const py::handle& message, Writer& writer) const {
    for (const Field& field : node.fields) {
      PyObject* value = PyObject_GetAttr(message.ptr(), field.name.ptr());
      if (value == nullptr) {
        PyErr_Clear();
        throw Unwritten{node.type_name + "." + std::string(field.name) + ": no such attribute"};
      }
      const py::object held = py::reinterpret_steal<py::object>(value);
      try {
        encodeField(field, held, writer);
      } catch (Unwritten& unwritten) {
        unwritten.what = node.type_name + "." + std::string(field.name) + " " + unwritten.what;
        throw;
      }
    }
  }

  void encodeField(const Field& field, const py::handle& value, Writer& writer) const {
    if (field.count == kScalar) {
      encodeValue(field, value, writer);
      return;
    }
    if (field.kind == Kind::kUInt8) {  // genpy: a list or tuple of ints, or else bytes
      if (PyBytes_CheckExact(value.ptr())) {
        const auto size = static_cast<size_t>(PyBytes_GET_SIZE(value.ptr()));
        if (field.count == kVariable) {
          if (size > std::numeric_limits<uint32_t>::max()) throw Unwritten{"holds over 4 GB"};
          writer.raw(static_cast<uint32_t>(size));
        } else if (size != static_cast<size_t>(field.count)) {
          throw Unwritten{"holds bytes of another length than the field's"};  // genpy pads or cuts them
        }
        writer.append(PyBytes_AS_STRING(value.ptr()), size);
        return;
      }
      if (!PyList_CheckExact(value.ptr()) && !PyTuple_CheckExact(value.ptr())) {
        throw Unwritten{"is neither bytes nor a list or tuple"};
      }
    }
    const Py_ssize_t size = PyObject_Length(value.ptr());
    if (size < 0) {
      PyErr_Clear();
      throw Unwritten{"has no length"};
    }
    if (field.count == kVariable) {
      if (static_cast<uint64_t>(size) > std::numeric_limits<uint32_t>::max()) throw Unwritten{"holds over 2^32 values"};
      writer.raw(static_cast<uint32_t>(size));
    } else if (size != field.count) {
      throw Unwritten{"holds " + std::to_string(size) + " values, not " + std::to_string(field.count)};
    }
    PyObject* sequence = PySequence_Fast(value.ptr(), "an array field");
    if (sequence == nullptr) {
      PyErr_Clear();
      throw Unwritten{"is not iterable"};
    }
    const py::object values = py::reinterpret_steal<py::object>(sequence);
    if (PySequence_Fast_GET_SIZE(values.ptr()) != size) throw Unwritten{"iterates over another count than its length"};
    PyObject** items = PySequence_Fast_ITEMS(values.ptr());
    for (Py_ssize_t i = 0; i < size; ++i) encodeValue(field, items[i], writer);
  }

  static py::object asInt(const py::handle& value) {
    // struct.pack's integer formats take an int or an object with __index__.
    PyObject* made = PyLong_Check(value.ptr()) || PyIndex_Check(value.ptr()) ? PyNumber_Index(value.ptr()) : nullptr;
    if (made == nullptr) {
      PyErr_Clear();
      throw Unwritten{"is not an integer"};
    }
    return py::reinterpret_steal<py::object>(made);
  }

  static int64_t integer(const py::handle& value, int64_t low, int64_t high) {
    // In the format's range.
    const py::object index = asInt(value);
    int overflow = 0;
    const long long number = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
    if (number == -1 && PyErr_Occurred()) {
      PyErr_Clear();
      throw Unwritten{"is not an integer"};
    }
    if (overflow != 0 || number < low || number > high) throw Unwritten{"is out of the type's range"};
    return number;
  }

  static double real(const py::handle& value) {
    // struct.pack's float formats: PyFloat_AsDouble (a float, or an object with __float__ or __index__).
    const double number = PyFloat_AsDouble(value.ptr());
    if (number == -1.0 && PyErr_Occurred()) {
      PyErr_Clear();
      throw Unwritten{"is not a float"};
    }
    return number;
  }

  void encodeValue(const Field& field, const py::handle& value, Writer& writer) const {
    if (field.kind <= Kind::kInt64) {
      const KindInfo& kind = info(field.kind);
      const int64_t number = integer(value, kind.low, kind.high);
      writer.append(reinterpret_cast<const char*>(&number), kind.size);  // little-endian: the narrower type's bytes
      return;
    }
    switch (field.kind) {
      case Kind::kUInt64: {
        const py::object index = asInt(value);
        const unsigned long long number = PyLong_AsUnsignedLongLong(index.ptr());
        if (number == static_cast<unsigned long long>(-1) && PyErr_Occurred()) {
          PyErr_Clear();
          throw Unwritten{"is out of the type's range"};
        }
        writer.raw(static_cast<uint64_t>(number));
        return;
      }
      case Kind::kFloat32: {
        const double number = real(value);
        const auto narrow = static_cast<float>(number);
        if (std::isinf(narrow) && !std::isinf(number)) throw Unwritten{"is too large for a float32"};
        writer.raw(narrow);
        return;
      }
      case Kind::kFloat64:
        writer.raw(real(value));
        return;
      case Kind::kString: {
        if (!PyUnicode_Check(value.ptr())) throw Unwritten{"is not a str"};
        Py_ssize_t size = 0;
        const char* text = PyUnicode_AsUTF8AndSize(value.ptr(), &size);
        if (text == nullptr) {
          PyErr_Clear();
          throw Unwritten{"is not encodable as UTF-8"};
        }
        if (static_cast<uint64_t>(size) > std::numeric_limits<uint32_t>::max()) throw Unwritten{"is over 4 GB"};
        writer.raw(static_cast<uint32_t>(size));
        writer.append(text, static_cast<size_t>(size));
        return;
      }
      case Kind::kTime:
      case Kind::kDuration: {
        PyObject* parts[2] = {PyObject_GetAttr(value.ptr(), secsName()),
                              PyObject_GetAttr(value.ptr(), nsecsName())};
        const py::object held[2] = {py::reinterpret_steal<py::object>(parts[0]),
                                    py::reinterpret_steal<py::object>(parts[1])};
        if (parts[0] == nullptr || parts[1] == nullptr) {
          PyErr_Clear();
          throw Unwritten{"has no secs and nsecs"};
        }
        for (const py::object& part : held) {
          if (field.kind == Kind::kTime) {
            writer.raw(static_cast<uint32_t>(integer(part, 0, UINT32_MAX)));
          } else {
            writer.raw(static_cast<int32_t>(integer(part, INT32_MIN, INT32_MAX)));
          }
        }
        return;
      }
      case Kind::kMessage:
        encodeMessage(nodes_[field.node], value, writer);
        return;
      default:  // the integers above
        return;
    }
  }

  std::vector<Node> nodes_;
  std::unordered_map<PyObject*, size_t> index_;  // a class's node (each class once, however often it is nested)
  size_t root_ = 0;
};

}  // namespace

void bindWireFormat(py::module_& m) {
  py::class_<MessageCodec>(
      m, "_MessageCodec",
      "A private wire-format helper of sixdof_commander (not the core's API): a ROS 1 message class's objects to and "
      "from their serialized bytes, as genpy's generated serializer writes them and its deserializer reads them.\n\n"
      "layout: (class, fields), each field (name, kind, count, sub): kind one of bool, int8, uint8, int16, uint16, "
      "int32, uint32, int64, uint64, float32, float64, string, time, duration, message (char as uint8, byte as "
      "int8); count -2 for one value, -1 for T[], N for T[N]; sub the nested message's layout (message), the class "
      "of the values (time, duration: genpy.Time, genpy.Duration), else None.")
      .def(py::init<py::handle>(), py::arg("layout"))
      .def_property_readonly("type", &MessageCodec::type, "The message class of the layout's root.")
      .def("decode", &MessageCodec::decode, py::arg("data"),
           "The message serialized in data (bytes or any buffer), made as genpy's deserializer makes it: every "
           "message made without __init__ and every field set; float and integer arrays as tuples, uint8[] and "
           "char[] as bytes, bool[], string[] and message arrays as lists, times as read (no normalizing); bytes "
           "beyond the message are not read. ValueError naming the field for bytes that end before it does, "
           "UnicodeDecodeError for a string that is not UTF-8 (genpy replaces its bytes).")
      .def("encode", &MessageCodec::encode, py::arg("message"),
           "message's serialized bytes, as genpy's serialize writes them (without the length TCPROS puts before "
           "them). TypeError naming the field for a value this codec does not write as genpy would: a value of "
           "another type, a number out of its type's range, a fixed-length array of another length, uint8[] that "
           "are neither bytes nor a list or tuple (genpy raises for some of these, and pads or cuts fixed-length "
           "bytes): the caller serializes such messages with genpy.");
}

}  // namespace sixdof_core::python
