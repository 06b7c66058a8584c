// Ending a tmclrun run from outside (docs/tmclrun.md, "Ending a run"): SIGINT and SIGTERM end it
// as a limit does, so the summary, --json, --csv, --plot and the EEPROM file are still written
// (halt "interrupted"); a trace whose output was closed ends it too (SIGPIPE is ignored, so the
// failed write is seen instead of killing the process); and a run that no limit bounds tells a
// terminal after 2 s of wall time how far simulated time got and how to bound it. The wall clock
// is only the note's timer (SIGALRM): simulated behaviour never depends on it. The VM sees one
// flag (Limits::stop) and stops between instructions; a note lets it go on where it was.
//
//   RunControl control(note);                 // handlers in place (one RunControl at a time)
//   trace.write_failed = [&] { control.output_closed(); };
//   RunResult r = control.run(vm, limits);    // halt Interrupted: r.message says by what
//   ... write the summary, JSON, CSV, plot, EEPROM ...
//   RunControl::end_by_signal();              // after the last write: die of the signal, if one ended it
#pragma once

#include <cstdio>

#include "tmcl/vm.hpp"

namespace tmcl {

class RunControl {
 public:
  // Catches SIGINT and SIGTERM and ignores SIGPIPE (for the rest of the process). With `note`,
  // arms the note to `note_to` after `note_after_ms` of wall time (tmclrun: no --max-time or
  // --max-steps, and standard error a terminal).
  explicit RunControl(bool note, std::FILE* note_to = stderr, int note_after_ms = 2000);
  ~RunControl();  // SIGINT, SIGTERM and SIGALRM as they were; the note disarmed
  RunControl(const RunControl&) = delete;
  RunControl& operator=(const RunControl&) = delete;

  // vm.run(limits) until the VM halts for a reason of its own or is ended from outside; the note
  // is printed on the way without changing the run. After a signal a second one acts at once.
  RunResult run(Vm& vm, Limits limits);
  // Called by a trace that can no longer write: the run ends (halt interrupted).
  void output_closed();
  bool output_was_closed() const;
  // The signal that ended the run (SIGINT, SIGTERM), or 0.
  static int ended_by();
  // When a signal ended the run, ends the process by that signal with its default action (the
  // shell then reports 128 + N, and a script stops as for any program killed so). Call it after
  // the last output is written; it returns when no signal ended the run.
  static void end_by_signal();
};

}  // namespace tmcl
