#pragma once
// Shared pieces of the Python bindings (module sixdof_core._sixdof_core): numpy <-> core conversions and the
// binding functions of each file. Poses are 4x4 homogeneous matrices, joint values 1-D arrays, paths 2-D
// arrays (one row per point).

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <Eigen/Geometry>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "sixdof_core/robot_model.h"

namespace pybind11::detail {

// Eigen::Isometry3d <-> a 4x4 float64 array (a homogeneous transform). A C-contiguous float64 array is read in
// place; anything else array-like is converted first. A 4x4 whose last row is not [0, 0, 0, 1] raises ValueError.
// The rotation block is taken as given: IK checks that it is a rotation (INVALID_INPUT).
template <>
struct type_caster<Eigen::Isometry3d> {
  PYBIND11_TYPE_CASTER(Eigen::Isometry3d, const_name("numpy.ndarray[numpy.float64[4, 4]]"));

  bool load(handle src, bool convert) {
    const bool in_place = isinstance<array_t<double, array::c_style>>(src);
    if (!in_place && !convert) return false;
    const array matrix =
        in_place ? reinterpret_borrow<array>(src) : array_t<double, array::c_style | array::forcecast>::ensure(src);
    if (!matrix || matrix.ndim() != 2 || matrix.shape(0) != 4 || matrix.shape(1) != 4) return false;
    const double* m = static_cast<const double*>(matrix.data());
    if (m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0) {
      throw std::invalid_argument("a pose must be a 4x4 homogeneous transform: its last row must be [0, 0, 0, 1]");
    }
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) value.matrix()(r, c) = m[4 * r + c];
    }
    return true;
  }

  static handle cast(const Eigen::Isometry3d& pose, return_value_policy, handle) {
    array_t<double> matrix({4, 4});
    double* m = matrix.mutable_data();
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) m[4 * r + c] = pose.matrix()(r, c);
    }
    return matrix.release();
  }
};

}  // namespace pybind11::detail

namespace sixdof_core::python {

namespace py = pybind11;

// A RobotModel as Python holds it: pybind11's holder needs a non-const pointee; every bound method is const.
using ModelPtr = std::shared_ptr<RobotModel>;

// A result class with the members of every result (the core's Result<Code>): status, message, ok and its truth, and
// its repr "<Name STATUS: message>".
template <class ResultType>
py::class_<ResultType> bindResult(py::module_& m, const char* name, const char* doc) {
  py::class_<ResultType> result(m, name, doc);
  result.def_readonly("status", &ResultType::status)
      .def_readonly("message", &ResultType::message)
      .def_property_readonly("ok", &ResultType::ok)
      .def("__bool__", &ResultType::ok)
      .def("__repr__", [type = std::string(name)](const ResultType& r) {
        const std::string status = py::str(py::cast(r.status).attr("name"));
        return "<" + type + " " + status + (r.message.empty() ? "" : ": " + r.message) + ">";
      });
  return result;
}

// A pose argument defaulting to the identity, shown as numpy.eye(4) in the signature.
inline py::arg_v identityPose(const char* name) {
  return py::arg_v(name, Eigen::Isometry3d::Identity(), "numpy.eye(4)");
}

// Rows of equal length as a (rows, cols) array; cols is used when there are no rows.
inline py::array_t<double> toArray(const std::vector<Eigen::VectorXd>& rows, Eigen::Index cols = 0) {
  if (!rows.empty()) cols = rows.front().size();
  py::array_t<double> out({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(cols)});
  auto view = out.mutable_unchecked<2>();
  for (size_t r = 0; r < rows.size(); ++r) {
    for (Eigen::Index c = 0; c < cols; ++c) view(r, c) = rows[r][c];
  }
  return out;
}

inline py::array_t<double> toArray(const std::vector<std::vector<double>>& rows, size_t cols) {
  py::array_t<double> out({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(cols)});
  auto view = out.mutable_unchecked<2>();
  for (size_t r = 0; r < rows.size(); ++r) {
    if (rows[r].size() != cols) throw std::invalid_argument("rows of different lengths");
    for (size_t c = 0; c < cols; ++c) view(r, c) = rows[r][c];
  }
  return out;
}

// The rows of a 2-D array as vectors.
inline std::vector<Eigen::VectorXd> toRows(const Eigen::MatrixXd& matrix) {
  std::vector<Eigen::VectorXd> rows;
  rows.reserve(matrix.rows());
  for (Eigen::Index r = 0; r < matrix.rows(); ++r) rows.emplace_back(matrix.row(r).transpose());
  return rows;
}

void bindExceptions(py::module_& m);
void bindModel(py::module_& m);
void bindState(py::module_& m);
void bindKinematics(py::module_& m);
void bindCollision(py::module_& m);
void bindPlanning(py::module_& m);
void bindTrajectory(py::module_& m);
void bindSetupAssistant(py::module_& m);
void bindWireFormat(py::module_& m);

}  // namespace sixdof_core::python
