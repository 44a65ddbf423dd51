#pragma once
// A message's body bytes as its encoder writes them (no header, no padding): what the golden and
// layout tests compare with the captures of docs/vrpn.md §11.
#include <cstdint>
#include <vector>

#include "device/vrpn/byte_io.hpp"

namespace thx::vrpn::test {

template <class M>
std::vector<std::uint8_t> body(const M& m) {
  std::vector<std::uint8_t> out;
  ByteWriter w(out);
  m.encode(w);
  return out;
}

}  // namespace thx::vrpn::test
