#pragma once
// SIGINT and SIGTERM set one process-wide stop flag that every loop of a client checks; a second
// signal is not needed and nothing else happens in the handler (async-signal-safe).
namespace thx::client {

// Installs the handlers (idempotent). Blocking calls are interrupted (no SA_RESTART) so a loop
// waiting in LCM notices the flag at once.
void installStopSignals();
bool stopRequested();
// Sets the flag as a signal would (tests, or a program that decides to stop).
void requestStop();
// Clears the flag (tests that run several client loops in one process).
void clearStopRequest();

}  // namespace thx::client
