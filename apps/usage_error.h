#pragma once
#include <stdexcept>
#include <string>

namespace viqu::app {

// A malformed command line: the program prints the message and the usage text, exit code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace viqu::app
