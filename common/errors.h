#pragma once
#include <stdexcept>
#include <string>

namespace viqu {

// Bad input from the user (malformed or invalid file, unknown key, missing file, corrupt data).
// The command-line program reports what() and exits with code 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run that started but failed (robot fell when not allowed, renderer lost...). Exit code 1.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace viqu
