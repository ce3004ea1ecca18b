#pragma once
/// \file errors.h
/// The project's exception family. Library code throws; programs map the type to an exit code
/// in one place (see cli_main.h): InvalidInput -> 2, IoError -> 3, anything else -> 1.
/// Messages are one line naming the file, line, atom or option and the problem.

#include <stdexcept>
#include <string>

namespace mg {

/// Base of every error the project throws on purpose.
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The caller's data or options break a documented precondition (bad radius, malformed file).
struct InvalidInput : Error {
  using Error::Error;
};

/// A file cannot be opened, read, written or renamed.
struct IoError : Error {
  using Error::Error;
};

/// A topological invariant the algorithm guarantees failed (an internal defect, not bad input).
struct TopologyError : Error {
  using Error::Error;
};

/// A numerical computation could not reach the required accuracy.
struct NumericalError : Error {
  using Error::Error;
};

}  // namespace mg
