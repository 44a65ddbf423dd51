#pragma once
// ModalError: a modal analysis the user can fix (a degenerate tet, an impossible material, a
// solve that does not converge). Every message names the object and the cause.
#include <string>

#include "base/error.hpp"

namespace thx::audio {

class ModalError : public Error {
 public:
  explicit ModalError(const std::string& what) : Error(Kind::Config, what) {}
};

}  // namespace thx::audio
