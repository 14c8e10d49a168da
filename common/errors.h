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

// SIGINT or SIGTERM arrived while the program read its inputs (before a run began): the program
// exits with 128 + signal(), as a stopped run does.
class Stopped : public std::runtime_error {
 public:
  Stopped(int signal, const std::string& what) : std::runtime_error(what), signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

}  // namespace viqu
