# SPDX-License-Identifier: GPL-3.0-or-later
"""Long jobs that do not block Blender: a job does its work in slices (``step``), so a modal
operator can run it from a timer with a progress bar and a status line and stop it on Esc,
while a script's ``bpy.ops`` call runs it to the end at once. Tests drive the slices directly
(a modal operator cannot run without a window).

A job changes the scene only in ``finish`` (or puts back what a slice showed in ``cancel``), so
a stopped job leaves the scene as it was."""

from __future__ import annotations

import math
import sys
import threading
import time

import bpy

from . import checks

SLICE_S = 0.08  # work a timer event may do on Blender's own thread
TIMER_S = 0.05
WORKER_SWITCH_S = 0.0005  # while a worker runs, Blender's drawing waits at most this for Python
CANCEL_WAIT_S = 1.0  # Esc waits at most this for a worker to reach its next progress call


class JobCancelled(Exception):
    """Raised inside a worker by its own progress callback once the job was cancelled."""


class Job:
    """Work in slices. ``fraction`` and ``status`` say how far it is."""

    title = "Working"
    fraction = 0.0
    status = ""

    def step(self, budget_s: float) -> bool:
        """Work for about ``budget_s`` seconds (math.inf: to the end); True when done."""
        raise NotImplementedError

    def cancel(self):
        """Stop and put back whatever a slice changed in the scene."""

    def finish(self, context) -> tuple[str, str]:
        """Apply the result to the scene; returns (report level, message)."""
        raise NotImplementedError

    def status_line(self) -> str:
        text = f"{self.title}: {100 * self.fraction:.0f}%"
        return f"{text} - {self.status} | Esc: stop" if self.status else f"{text} | Esc: stop"


class WorkerJob(Job):
    """Engine work that offers no slices of its own (writing a character, fitting) runs in a
    worker thread: plain Python and numpy, never bpy. Its ``progress`` callback reports how
    far it is and is where the worker stops: ``cancel`` sets a flag that the next call of
    ``progress`` (between the engine's steps) answers by ending the work; its result is
    discarded. Run to the end (a script), it runs on the caller's thread, as before."""

    def __init__(self, work):
        self._work = work  # work(progress) -> result; progress(fraction, *details)
        self._thread = None
        self._stop = threading.Event()
        self._switch = None
        self.result = None
        self.error = None
        self.finished = False

    def _progress(self, fraction, *details):
        self.fraction = float(fraction)
        self.status = self.describe(details)
        if self._stop.is_set():
            raise JobCancelled

    def describe(self, _details) -> str:
        return ""

    def _run(self):
        try:
            result = self._work(self._progress)
            if not self._stop.is_set():  # a result that came after Esc is not kept
                self.result = result
        except JobCancelled:
            pass
        except BaseException as exc:  # handed to Blender's thread by step()
            self.error = exc
        self.finished = True

    def step(self, budget_s: float) -> bool:
        if self._thread is None and math.isinf(budget_s):
            self._run()  # a script: on this thread, to the end
        elif self._thread is None:
            self._switch = sys.getswitchinterval()
            sys.setswitchinterval(WORKER_SWITCH_S)
            self._thread = threading.Thread(target=self._run, name=self.title, daemon=True)
            self._thread.start()
        else:
            self._thread.join(None if math.isinf(budget_s) else min(budget_s, 0.001))
        if not self.finished:
            return False
        self._restore_switch()
        if self.error is not None:
            raise self.error
        return True

    def cancel(self):
        """Stop cooperatively: the worker ends at its next progress call (waited for here at
        most CANCEL_WAIT_S; a worker still in a long step ends on its own, unseen)."""
        self._stop.set()
        t = self._thread
        if t is not None and t.is_alive():
            t.join(CANCEL_WAIT_S)
        self.result = None
        self._restore_switch()

    def _restore_switch(self):
        if self._switch is not None:
            sys.setswitchinterval(self._switch)
            self._switch = None


def deadline(budget_s: float):
    """A should_stop for the engine's seek: True once ``budget_s`` has passed."""
    if math.isinf(budget_s):
        return None
    end = time.perf_counter() + budget_s
    return lambda: time.perf_counter() > end


JOB_ERRORS = (*checks.USER_ERRORS, ValueError, OSError, MemoryError)


class JobOperator:
    """Mixin for an operator whose work is a Job: from the interface (``invoke`` sets
    ``in_background``) it runs modally, a slice a timer event, with a progress bar and a status
    line, Esc stopping it; from a script it runs to the end in ``execute``."""

    in_background: bpy.props.BoolProperty(default=False, options={"HIDDEN", "SKIP_SAVE"})

    def invoke(self, context, _event):
        """From the interface: run modally (an operator that asks first overrides this)."""
        self.in_background = True
        return self.execute(context)

    def run_job(self, context, job: Job) -> set:
        wm = context.window_manager
        if self.in_background and not bpy.app.background and context.window is not None:
            self.begin_job(context, job)
            wm.modal_handler_add(self)
            return {"RUNNING_MODAL"}
        wm.progress_begin(0, 100)
        try:
            while not job.step(math.inf):
                pass
        except JOB_ERRORS as exc:
            job.cancel()
            return self._failed(exc)
        finally:
            wm.progress_end()
        return self._finished(context, job)

    def begin_job(self, context, job: Job):
        """Progress bar, status line and the timer whose events run the slices."""
        self._job = job
        wm = context.window_manager
        wm.progress_begin(0, 100)
        self._timer = wm.event_timer_add(TIMER_S, window=context.window)
        context.workspace.status_text_set(job.status_line())

    def modal(self, context, event):
        job = self._job
        if event.type == "ESC":
            job.cancel()
            self._end(context)
            self.report({"WARNING"}, f"{job.title} stopped: the scene is as it was")
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        try:
            done = job.step(SLICE_S)
        except JOB_ERRORS as exc:
            job.cancel()
            self._end(context)
            return self._failed(exc)
        context.window_manager.progress_update(int(100 * job.fraction))
        context.workspace.status_text_set(job.status_line())
        if not done:
            return {"RUNNING_MODAL"}
        self._end(context)
        return self._finished(context, job)

    def cancel(self, context):
        self._job.cancel()
        self._end(context)

    def _end(self, context):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        context.workspace.status_text_set(None)

    def _failed(self, exc) -> set:
        if isinstance(exc, MemoryError):
            exc = "Not enough memory for this paper: lower its resolution"
        self.report({"ERROR"}, str(exc))
        return {"CANCELLED"}

    def _finished(self, context, job: Job) -> set:
        try:
            level, message = job.finish(context)
        except JOB_ERRORS as exc:
            return self._failed(exc)
        self.report({level}, message)
        return {"FINISHED"} if level != "ERROR" else {"CANCELLED"}
