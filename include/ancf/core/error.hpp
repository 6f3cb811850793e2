// Exception types. Every error ancf raises says what was being done and what was expected.
#pragma once

#include <stdexcept>
#include <string>

namespace ancf {

/// A model or scene that cannot be built as given (bad parameter, undefined reference ...).
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A solver that could not make progress (Newton divergence, singular matrix, step too small).
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ancf
