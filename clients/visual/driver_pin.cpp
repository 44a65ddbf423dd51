#include "clients/visual/driver_pin.hpp"

#include <dlfcn.h>
#include <link.h>

#include <cstring>

namespace thx::visual {

void pinGlDriver() {
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void*) -> int {
        if (info->dlpi_name && std::strstr(info->dlpi_name, "_dri.so")) {
          // RTLD_NOLOAD: only the already loaded driver; RTLD_NODELETE: never unmapped. The
          // handle is deliberately kept.
          dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
        }
        return 0;
      },
      nullptr);
}

}  // namespace thx::visual
