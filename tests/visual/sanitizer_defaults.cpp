// Sanitizer defaults for the tests that render with Mesa in-process (sanitizer tree only; the
// function is unused elsewhere). With ASan's __tls_get_addr interception on, LeakSanitizer's
// exit-time check read a garbage dynamic-TLS range of the main thread ("DTLS 9 at
// 0x...0d1d-0x0018...1e1f", then "Tracer caught signal 11") after every test had passed, in
// VisualNormalReference.BricksSeenObliquely under ctest every time and elsewhere by chance: the
// GCC 12 runtime's DTLS bookkeeping and Mesa's dlopen'ed driver with its own TLS. Without the
// interception the dynamic TLS blocks are still ordinary heap blocks reachable through the
// thread's DTV, so leak checking keeps its roots. ASAN_OPTIONS from the environment still win.
extern "C" const char* __asan_default_options();
extern "C" const char* __asan_default_options() { return "intercept_tls_get_addr=0"; }
