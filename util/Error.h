#pragma once
#include <stdexcept>
#include <string>

namespace candela {

/// Bad input from a file or a user value. The message names the file (and line or field where
/// known) and what was expected. Loaders throw it; the CLI and the editor catch it and report it.
class InputError : public std::runtime_error {
  public:
    explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

/// A command line that asks for something the command does not take (an unknown option, a
/// missing or extra argument): `candela` prints the command's usage and exits 2.
class UsageError : public InputError {
  public:
    explicit UsageError(const std::string& message) : InputError(message) {}
};

/// A GL or system failure that is not the user's input (context creation, shader compile).
class RuntimeError : public std::runtime_error {
  public:
    explicit RuntimeError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace candela
