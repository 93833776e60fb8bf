#pragma once
/// Typed errors of the Fissure core. Every message names its culprit (file, parameter, tet, …);
/// the CLI maps each class to its own exit code and the studio to a dialog.

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fissure {

/// Base of every error the core throws on purpose.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// User data is wrong: an out-of-range parameter, a degenerate mesh, a selection that selects
/// nothing. Fixing the input fixes the problem.
class InvalidInput : public Error {
public:
  using Error::Error;
};

/// A file could not be found, read or written, or its content is not in the expected format.
class IoError : public Error {
public:
  using Error::Error;
};

/// A request whose estimated memory exceeds the allowed limit (base/memory.hpp): bad input of
/// its own kind so a front end can say how to allow it anyway.
class MemoryLimitExceeded : public InvalidInput {
public:
  using InvalidInput::InvalidInput;
};

/// A computation failed numerically: a factorisation lost positive definiteness, an eigensolver
/// did not converge, a residual is too large, a result is not finite.
class NumericalFailure : public Error {
public:
  using Error::Error;
};

/// The operation was cancelled through its CancelToken.
class Cancelled : public Error {
public:
  Cancelled() : Error("cancelled") {}
  using Error::Error;
};

/// The validate() of an options struct: throws InvalidInput "<context>: p1; p2; …" when
/// `problems` is not empty.
void throw_if_problems(std::string_view context, const std::vector<std::string>& problems);

}  // namespace fissure
