#include "util/interrupt.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>

#include <gtest/gtest.h>

#include "util/error.h"

namespace colmap_gcn {
namespace {

// Runs body in a forked child with the interrupt handlers installed and
// returns its wait status; the child exits 0 when body returns.
int StatusOfChild(const std::function<void()>& body) {
  const pid_t pid = fork();
  if (pid == 0) {
    InstallInterruptHandlers();
    body();
    _exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

TEST(Interrupt, SignalWithNoChildEndsTheProcessByTheSignal) {
  // Raised inside the handler the signal is blocked: unless unblocked, the
  // process would _exit(130) silently instead of ending by the signal.
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    const int status = StatusOfChild([&] {
      raise(signal_number);
      _exit(3);  // not reached
    });
    EXPECT_TRUE(WIFSIGNALED(status)) << signal_number;
    if (WIFSIGNALED(status)) {
      EXPECT_EQ(WTERMSIG(status), signal_number);
    }
  }
}

TEST(Interrupt, CheckpointsHoldTheSignalUntilTheNextCheck) {
  const int status = StatusOfChild([] {
    const InterruptCheckpoints checkpoints;
    raise(SIGINT);
    // Still running: the signal waits for the check.
    if (PendingInterrupt() != SIGINT) _exit(4);
    try {
      ThrowIfInterrupted("between two blocks");
    } catch (const Error& error) {
      const std::string message = error.what();
      _exit(message == "interrupted (signal 2) between two blocks" ? 42 : 5);
    }
    _exit(6);
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 42);
}

TEST(Interrupt, CriticalSectionActsOnTheSignalWhenItEnds) {
  const int status = StatusOfChild([] {
    {
      const CriticalSection critical;
      raise(SIGTERM);
      if (PendingInterrupt() != SIGTERM) _exit(4);
    }
    _exit(7);  // not reached: the section's end acts on the signal
  });
  EXPECT_TRUE(WIFSIGNALED(status));
  if (WIFSIGNALED(status)) {
    EXPECT_EQ(WTERMSIG(status), SIGTERM);
  }
}

TEST(Interrupt, NoSignalNoThrow) {
  const int status = StatusOfChild([] {
    const InterruptCheckpoints checkpoints;
    ThrowIfInterrupted("never");
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

}  // namespace
}  // namespace colmap_gcn
