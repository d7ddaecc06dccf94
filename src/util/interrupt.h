#pragma once

#include <sys/types.h>

namespace colmap_gcn {

// SIGINT, SIGTERM and SIGHUP for commands that run COLMAP. Once installed, a
// signal that arrives while a child process runs is forwarded to the child
// (whose failure is then reported as an interruption, with the usual
// cleanup); one that arrives inside a CriticalSection is held until the
// section ends; one inside an InterruptCheckpoints scope is held until the
// next ThrowIfInterrupted(); otherwise it ends the process as it would by
// default.
void InstallInterruptHandlers();

// The signal that interrupted this run, 0 if none.
int PendingInterrupt();

// The child process a signal is forwarded to; 0 for none.
void SetInterruptibleChild(pid_t pid);

// Steps that must not stop half-way (publishing a file with fsync + rename):
// a signal arriving inside is acted on when the outermost section ends.
class CriticalSection {
 public:
  CriticalSection();
  ~CriticalSection();
  CriticalSection(const CriticalSection&) = delete;
  CriticalSection& operator=(const CriticalSection&) = delete;
};

// Loops of COLMAP runs (matching block by block): a signal between two runs
// is held and reported by the next ThrowIfInterrupted() like one that
// arrives while COLMAP runs, so an interrupted loop always ends the same way
// (its cleanup, one "ERROR: interrupted" line, exit 128 + signal) wherever
// the signal lands.
class InterruptCheckpoints {
 public:
  InterruptCheckpoints();
  ~InterruptCheckpoints();
  InterruptCheckpoints(const InterruptCheckpoints&) = delete;
  InterruptCheckpoints& operator=(const InterruptCheckpoints&) = delete;
};

// Throws Error "interrupted (signal N) <during>" when a signal is pending.
void ThrowIfInterrupted(const char* during);

// Test hook: when the environment variable COLMAP_GCN_STOP_AT equals name,
// the process stops itself (SIGSTOP) the first time it passes here, so
// that tests can interrupt a run at an exact step and resume or kill it.
void StopPointForTests(const char* name);

}  // namespace colmap_gcn
