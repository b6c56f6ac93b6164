#pragma once
// The one outcome type of every call that can fail without throwing (docs/design.md "Results and enums").
// Header only; part of the model layer, so the simulator and the rviz plugins use it too.

#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>

namespace sixdof_core {

// A code from `Code` plus a message naming the problem. The code's value 0 (its first enumerator, kSuccess or
// kOk) is success and is the default, so `Result<Code>()` and `Result<Code>::success()` are successes (a
// success's message is empty unless its result documents a note). A function that returns a result sets the
// failure code explicitly on every failure path (`fail()`): no result relies on its default to fail. A result with a payload derives from it (`struct IkResult : Result<IkStatus> {...}`), so
// every result reads the same way: `if (result)`, `result.ok()`, `result.status`, `result.message`.
template <class Code>
struct Result {
  static_assert(std::is_enum_v<Code>, "Result<Code>: Code must be an enum whose value 0 means success");

  Code status{};
  std::string message;

  bool ok() const { return status == Code{}; }
  // Explicit, so a result does not turn into an int or compare with one by accident.
  explicit operator bool() const { return ok(); }

  static Result success() { return Result(); }
  static Result failure(Code code, std::string why) { return Result{code, std::move(why)}; }

  // Sets the code and message of a result with a payload (whose other fields keep their values).
  void fail(Code code, std::string why) {
    status = code;
    message = std::move(why);
  }
};

// The name of an enumerator, from a table of every enumerator's name in declaration order (values 0, 1, ...).
// kLast, the enum's last enumerator, makes a table that misses one fail to compile:
//   return enumName<IkStatus::kInvalidInput>(status, {"success", ...});  (as a static table, see ik_solver.cpp)
template <auto kLast, std::size_t N>
const char* enumName(decltype(kLast) value, const char* const (&names)[N], const char* unknown = "UNKNOWN") {
  static_assert(std::is_enum_v<decltype(kLast)>, "enumName: kLast must be an enumerator");
  static_assert(N == static_cast<std::size_t>(kLast) + 1, "enumName: the table must name every enumerator");
  const auto index = static_cast<std::size_t>(value);
  return index < N ? names[index] : unknown;
}

}  // namespace sixdof_core
