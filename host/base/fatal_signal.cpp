#include "host/base/fatal_signal.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>

namespace depthprec {

namespace {

// Everything the handler reads is set before a crash can happen and never freed: fixed buffers,
// no allocation, no stdio, only write(), open(), read(), close() and _exit().
char g_advice[4096] = "";
std::atomic<int> g_exit_code{1};
std::atomic<bool> g_reporting{false};
alignas(16) char g_alt_stack[64 * 1024];

constexpr const char* kBug =
    "depthprec: this is a bug in depthprec: please report it, with the command line\n";

void say(const char* s) {
  size_t n = std::strlen(s);
  while (n > 0) {
    const ssize_t w = ::write(2, s, n);
    if (w <= 0) return;
    s += w;
    n -= static_cast<size_t>(w);
  }
}

const char* signal_text(int sig) {
  switch (sig) {
    case SIGBUS:
      return "SIGBUS (bus error: memory mapped from a file that is shorter than it claims)";
    case SIGSEGV:
      return "SIGSEGV (invalid memory access)";
    case SIGABRT:
      return "SIGABRT (aborted, after a failed assertion or an error the library could not "
             "return)";
    case SIGILL:
      return "SIGILL (illegal instruction)";
    case SIGFPE:
      return "SIGFPE (arithmetic exception)";
  }
  return "a fatal signal";
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

// One line of /proc/self/maps: "start-end perms offset dev inode   path". True, with the path
// (empty for anonymous memory), when addr lies in [start, end).
bool line_maps(const char* line, size_t len, uintptr_t addr, const char** path, size_t* path_len) {
  size_t i = 0;
  uintptr_t start = 0, end = 0;
  for (int d; i < len && (d = hex_digit(line[i])) >= 0; ++i) start = start * 16 + d;
  if (i >= len || line[i] != '-') return false;
  for (int d; ++i < len && (d = hex_digit(line[i])) >= 0;) end = end * 16 + d;
  if (addr < start || addr >= end) return false;
  for (int field = 0; field < 4 && i < len; ++field) {  // perms, offset, dev, inode
    while (i < len && line[i] == ' ') ++i;
    while (i < len && line[i] != ' ') ++i;
  }
  while (i < len && line[i] == ' ') ++i;
  *path = line + i;
  *path_len = len - i;
  return true;
}

// Writes the file mapped at addr, if any, as " in FILE".
void say_mapping(uintptr_t addr) {
  const int fd = ::open("/proc/self/maps", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  static char buf[8192];
  size_t have = 0;
  bool done = false;
  while (!done) {
    const ssize_t r = ::read(fd, buf + have, sizeof(buf) - have);
    if (r <= 0) break;
    have += static_cast<size_t>(r);
    size_t start = 0;
    for (size_t k = 0; k < have; ++k) {
      if (buf[k] != '\n') continue;
      const char* path = nullptr;
      size_t path_len = 0;
      if (line_maps(buf + start, k - start, addr, &path, &path_len)) {
        if (path_len > 0 && path[0] == '/') {
          say(" in ");
          (void)!::write(2, path, path_len);
        }
        done = true;
        break;
      }
      start = k + 1;
    }
    if (done) break;
    if (start == 0 && have == sizeof(buf)) break;  // a line longer than the buffer: give up
    std::memmove(buf, buf + start, have - start);
    have -= start;
  }
  ::close(fd);
}

void on_fatal_signal(int sig, siginfo_t* info, void*) {
  if (g_reporting.exchange(true)) {  // another thread is reporting: let it finish
    for (;;) ::pause();
  }
  say("\ndepthprec: crashed with ");
  say(signal_text(sig));
  if ((sig == SIGBUS || sig == SIGSEGV) && info)
    say_mapping(reinterpret_cast<uintptr_t>(info->si_addr));
  say("\n");
  say(g_advice[0] ? g_advice : kBug);
  ::_exit(g_exit_code.load());
}

}  // namespace

void install_fatal_signal_report() {
  stack_t alt{};
  alt.ss_sp = g_alt_stack;
  alt.ss_size = sizeof(g_alt_stack);
  sigaltstack(&alt, nullptr);  // a stack overflow's SIGSEGV still gets its report (main thread)
  struct sigaction sa {};
  sa.sa_sigaction = on_fatal_signal;
  sa.sa_flags = SA_SIGINFO | SA_ONSTACK;
  sigemptyset(&sa.sa_mask);
  for (const int sig : {SIGBUS, SIGSEGV, SIGABRT, SIGILL, SIGFPE}) sigaction(sig, &sa, nullptr);
}

void set_fatal_signal_advice(const std::string& advice, int exit_code) {
  const size_t n = std::min(advice.size(), sizeof(g_advice) - 1);
  std::memcpy(g_advice, advice.data(), n);
  g_advice[n] = '\0';
  g_exit_code.store(exit_code);
}

}  // namespace depthprec
