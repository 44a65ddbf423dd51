#pragma once
// thx::Error: the one base of every error a user can fix (a bad scene, texture, hand script or
// device address, a file that cannot be read, a command line, a server that does not answer),
// so a program's main catches it once and prints what() as it is. Every message names its
// source (file:line, option, URL...), the problem and what was expected. Untrusted bytes from the
// network are not errors of this kind: they are refused where they arrive (VRPN's Result<T>,
// hapticd's untrusted_input), and the server keeps running.
#include <stdexcept>
#include <string>

namespace thx {

class Error : public std::runtime_error {
 public:
  enum class Kind {
    Config,  // a scene, texture, script or setting the user wrote
    Io,      // a file, device or transport that cannot be used
    Usage,   // a command line (programs exit 2 on these, 1 on the others)
  };
  Error(Kind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

// A command-line mistake; `main` prints it with a pointer to --help and exits 2.
class UsageError : public Error {
 public:
  explicit UsageError(const std::string& what) : Error(Kind::Usage, what) {}
};

// The exit status for an error: 2 for usage, 1 otherwise.
inline int exitStatus(const Error& e) { return e.kind() == Error::Kind::Usage ? 2 : 1; }

}  // namespace thx
