// A crash said in words. A fatal signal (SIGBUS, SIGSEGV, SIGABRT, SIGILL, SIGFPE) would end the
// process with nothing but the shell's "Bus error"; in depthprec the usual cause is the OpenCL
// driver executing a damaged file of its kernel cache (docs/caches.md), which the user can fix.
// The handler writes, async-signal-safely, which signal, the file mapped at the faulting address
// when there is one (a truncated kernel .so, say), and the advice set for the situation, then
// ends the process with an exit code instead of the signal: 4 (the OpenCL runtime) once the
// driver is in use, 1 (a bug) before. Under a debugger the signal stops the program first.
#pragma once

#include <string>

namespace depthprec {

// Installs the handler: in main, before anything else runs, and again once the OpenCL platform
// is up, since PoCL's LLVM installs handlers of its own for these signals then (they print a
// stack trace, then fall back to the previous handler for faults, but hand abort() back to
// glibc, which ends the process with SIGABRT before ours could run).
void install_fatal_signal_report();

// What to print after the signal and the file, and the exit code to end with, from now on
// (copied: the handler reads a fixed buffer). The driver cache sets it when PoCL is first used.
void set_fatal_signal_advice(const std::string& advice, int exit_code);

}  // namespace depthprec
