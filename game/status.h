// How loaders and commands report failure: a message and the exit code the contract assigns.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace game {

/// Exit codes from the contract: 2 for bad usage or input, 1 for any other failure.
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitFailure = 1;

/// A failure to report. `message` is what follows "error: ", e.g.
/// `scene.json: bodies[2].radius: must be > 0`.
struct Failure {
  int exit_code = kExitBadInput;
  std::string message;
};

inline Failure BadInput(std::string message) { return {kExitBadInput, std::move(message)}; }
inline Failure RuntimeFailure(std::string message) { return {kExitFailure, std::move(message)}; }

/// A value or the failure that prevented it.
template <class T>
class Expected {
 public:
  Expected(T value) : v_(std::move(value)) {}  // NOLINT: implicit by design, like std::expected
  Expected(Failure failure) : v_(std::move(failure)) {}  // NOLINT
  bool HasValue() const { return v_.index() == 0; }
  T& Value() { return std::get<0>(v_); }
  const T& Value() const { return std::get<0>(v_); }
  const Failure& Error() const { return std::get<1>(v_); }

 private:
  std::variant<T, Failure> v_;
};

/// The result of a command: nothing, or the failure to report.
using Status = std::optional<Failure>;

}  // namespace game
