// AddressSanitizer defaults compiled into every executable of the sanitizer tree (THX_SANITIZE;
// the top-level CMakeLists.txt adds this file to each one). Options from ASAN_OPTIONS still win.
//
// intercept_tls_get_addr=0: GCC 12's libasan (Debian 12) guesses where a dynamic TLS block
// starts with a heuristic written for glibc 2.19: a block whose address is 16 bytes into a page
// is taken to follow a glibc header {size, start}, and those 16 bytes are read as one. With
// ASan's allocator the 16 bytes before a heap block are ASan's own chunk header, so the block is
// recorded with a garbage range ("DTLS 9 at 0x...0d1d-0x0018...1e1f"), and LeakSanitizer's
// exit-time scan of that range crashes ("Tracer caught signal 11 ... LeakSanitizer has
// encountered a fatal error", exit 134) after the program itself has finished cleanly. In
// visual-client module 9 is libLLVM-15, which Mesa's llvmpipe loads with its driver; its block
// is malloc'ed per thread, so whether one lands 16 bytes into a page is chance (docs/visual.md,
// the sanitizer paragraph). Without the interception the dynamic TLS blocks are ordinary heap
// blocks reachable through each thread's DTV, so leak checking keeps its roots.
extern "C" const char* __asan_default_options();
extern "C" const char* __asan_default_options() { return "intercept_tls_get_addr=0"; }
