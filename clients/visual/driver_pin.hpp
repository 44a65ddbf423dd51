#pragma once
// Keeps Mesa's DRI driver (swrast_dri.so: llvmpipe) mapped until the process ends. Mesa unloads
// it on eglTerminate and at exit; the blocks it still references from its own globals then look
// like leaks of an unmapped module (LeakSanitizer, ASan tree: "indirect leak" from an address it
// cannot name, so no suppression could single them out). Mapped, the driver's globals stay
// roots of the leak scan and those blocks are reachable: leak checks stay fully on, with no
// suppressions. Call after a context exists; a no-op when no DRI driver is loaded.
namespace thx::visual {

void pinGlDriver();

}  // namespace thx::visual
