#include "util/interrupt.h"

#include <signal.h>

#include <atomic>
#include <cstdlib>
#include <cstring>

#include "util/error.h"

namespace colmap_gcn {
namespace {

std::atomic<pid_t> g_child{0};
std::atomic<int> g_pending{0};
std::atomic<int> g_critical_depth{0};
std::atomic<int> g_checkpoint_depth{0};

const int kInterruptSignals[] = {SIGINT, SIGTERM, SIGHUP};

[[noreturn]] void DieBySignal(const int signal_number) {
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = SIG_DFL;
  sigaction(signal_number, &action, nullptr);
  // Called from the handler, the signal is blocked until it returns; raised
  // while blocked it would stay pending and the process would _exit
  // silently instead of ending by the signal.
  sigset_t unblock;
  sigemptyset(&unblock);
  sigaddset(&unblock, signal_number);
  sigprocmask(SIG_UNBLOCK, &unblock, nullptr);
  raise(signal_number);
  _exit(128 + signal_number);
}

void HandleInterrupt(const int signal_number) {
  int expected = 0;
  g_pending.compare_exchange_strong(expected, signal_number);
  const pid_t child = g_child.load();
  if (child > 0) {
    kill(child, signal_number);
    return;
  }
  if (g_critical_depth.load() > 0 || g_checkpoint_depth.load() > 0) return;
  DieBySignal(signal_number);
}

}  // namespace

void InstallInterruptHandlers() {
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = &HandleInterrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (const int signal_number : kInterruptSignals) {
    sigaction(signal_number, &action, nullptr);
  }
}

int PendingInterrupt() { return g_pending.load(); }

void SetInterruptibleChild(const pid_t pid) { g_child.store(pid); }

CriticalSection::CriticalSection() { ++g_critical_depth; }

CriticalSection::~CriticalSection() {
  if (--g_critical_depth == 0 && g_pending.load() != 0 && g_child.load() == 0 &&
      g_checkpoint_depth.load() == 0) {
    DieBySignal(g_pending.load());
  }
}

InterruptCheckpoints::InterruptCheckpoints() { ++g_checkpoint_depth; }

InterruptCheckpoints::~InterruptCheckpoints() { --g_checkpoint_depth; }

void ThrowIfInterrupted(const char* during) {
  const int signal_number = g_pending.load();
  if (signal_number != 0) {
    ThrowError("interrupted (signal ", signal_number, ") ", during);
  }
}

void StopPointForTests(const char* name) {
  static std::atomic<bool> stopped{false};
  const char* stop_at = std::getenv("COLMAP_GCN_STOP_AT");
  if (stop_at != nullptr && std::strcmp(stop_at, name) == 0 &&
      !stopped.exchange(true)) {
    raise(SIGSTOP);
  }
}

}  // namespace colmap_gcn
