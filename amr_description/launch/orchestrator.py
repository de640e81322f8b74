# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Run a stack of processes the way ``ros2 launch`` does: start, watch, chain, shut down.

Reproduces the observable behaviour of upstream ``launch`` (ROS 2 Jazzy, ``ExecuteLocal``):

* every process gets a label ``<name>-<N>`` (N counts started processes, from 1); its output
  is printed line by line as ``[label] line``;
* log lines ``[INFO] [label]: process started with pid [PID]``, ``[INFO] [label]: process has
  finished cleanly [pid PID]`` and ``[ERROR] [label]: process has died [pid PID, exit code C,
  cmd '...'].``;
* :class:`~amr_description.launch.actions.OnProcessExit` handlers start actions when their
  target exits; ``required`` processes shut the stack down when they exit; ``respawn``
  restarts a process after ``respawn_delay`` seconds unless the stack is shutting down;
* shutdown sends SIGINT to every running process, SIGTERM to those still running after
  ``sigterm_timeout`` seconds and SIGKILL ``sigkill_timeout`` seconds later, logging
  ``process[label] failed to terminate 'T' seconds after receiving 'SIGINT', escalating to
  'SIGTERM'`` as launch does.

Unlike launch, each child runs in its own process group (signals reach its children too, and
a terminal Ctrl-C reaches only the orchestrator, which forwards it) and is started with
``prctl(PR_SET_PDEATHSIG, SIGKILL)``, so children die with the orchestrator even when it is
SIGKILLed.

Python use (the orchestrator runs in a background thread)::

    with Orchestrator(stacks.sim({'rtf': '0'})) as stack:
        ...               # wait for a condition
    # leaving the block shuts the stack down and waits for every process
"""

import heapq
import itertools
import os
import queue
import signal
import subprocess
import sys
import threading
import time

from amr_description.launch.actions import LaunchError
from amr_description.launch.actions import OnProcessExit
from amr_description.launch.actions import Process
from amr_description.launch.child_process import tie_to_parent


class RunningProcess:
    """
    What the orchestrator knows about one started process action.

    :ivar action: the :class:`~amr_description.launch.actions.Process`.
    :ivar label: ``<name>-<N>``, kept across respawns.
    :ivar pid: pid of the current (or last) run, or None before the first start.
    :ivar returncode: exit code of the last run (negative: killed by that signal), or None
        while running / never started.
    :ivar starts: how many times it was started.
    :ivar cmd: the argv of the last start.
    :ivar last_line: the last non-blank line the process printed ('' before any).
    """

    def __init__(self, action, label):
        """Create the record; see the class docstring for the fields."""
        self.action = action
        self.label = label
        self.pid = None
        self.returncode = None
        self.starts = 0
        self.cmd = None
        self.popen = None
        self.last_line = ''

    @property
    def running(self):
        """Return True while the current run has not been reaped."""
        return self.popen is not None and self.returncode is None


class Orchestrator:
    """
    Start and supervise a list of actions (processes, nodes, exit handlers).

    :param actions: list of :class:`~amr_description.launch.actions.Process` (or
        :class:`~amr_description.launch.actions.Node`) and
        :class:`~amr_description.launch.actions.OnProcessExit`, started in order.
    :param sigterm_timeout: seconds between SIGINT and SIGTERM at shutdown (launch: 5).
    :param sigkill_timeout: seconds between SIGTERM and SIGKILL at shutdown (launch: 5).
    :param stream: where output and log lines go (default ``sys.stdout``).
    :param env: base environment of the children (default ``os.environ``); each action's
        ``env`` is merged over it; ``PYTHONUNBUFFERED=1`` is added so output is line-timely.
    :param line_callback: optional ``callable(label, line)`` called for every output line.
    """

    def __init__(self, actions, sigterm_timeout=5.0, sigkill_timeout=5.0, stream=None,
                 env=None, line_callback=None):
        """Prepare the orchestrator; nothing is started before :meth:`start`."""
        self.actions = list(actions)
        self.sigterm_timeout = float(sigterm_timeout)
        self.sigkill_timeout = float(sigkill_timeout)
        self.stream = stream if stream is not None else sys.stdout
        self.env = dict(os.environ if env is None else env)
        self.env.setdefault('PYTHONUNBUFFERED', '1')
        self.line_callback = line_callback
        self.processes = []
        self.exit_code = None
        self._records = {}
        self._handlers = []
        self._counter = itertools.count(1)
        self._events = queue.Queue()
        self._timers = []
        self._timer_seq = itertools.count()
        self._write_lock = threading.Lock()
        self._thread = None
        self._shutting_down = False
        self._shutdown_requested = 0
        self._error = False
        self._fatal = None
        self._temp_files = []
        self._pid = os.getpid()

    # ----------------------------------------------------------------- public API
    def start(self):
        """
        Start the actions in a background thread and return immediately.

        :returns: self.
        :raises RuntimeError: when already started.
        """
        if self._thread is not None:
            raise RuntimeError('orchestrator already started')
        self._thread = threading.Thread(target=self._loop, name='orchestrator', daemon=True)
        self._thread.start()
        return self

    def shutdown(self, reason='shutdown requested', due_to_sigint=False):
        """
        Request the stack shutdown: SIGINT, then SIGTERM, then SIGKILL to each process.

        Safe to call from any thread, and more than once (not from a signal handler: it takes
        the event queue's lock; :meth:`run` records signals and calls it from its loop).

        :param reason: text for the log.
        :param due_to_sigint: True when the user pressed Ctrl-C (logs as launch does).
        """
        self._events.put(('shutdown', reason, due_to_sigint))

    def wait(self, timeout=None):
        """
        Wait until every process has exited and nothing more can start.

        :param timeout: seconds, or None to wait forever.
        :returns: True when the stack is finished, False on timeout.
        """
        if self._thread is None:
            return True
        self._thread.join(timeout)
        return not self._thread.is_alive()

    def run(self):
        """
        Run in the foreground until done, handling Ctrl-C / SIGTERM like ``ros2 launch``.

        Must be called from the main thread.

        :returns: exit code: 0, or 1 when an action could not be started or a required
            process (``on_exit=Shutdown()``) died with a non-zero code; that process's last
            line is then printed again as the last line of the stack's output.
        """
        # the handler only records the signal: it runs in the main thread between any two
        # bytecodes, also while that thread holds the event queue's lock (Queue.put is not
        # reentrant: a shutdown() from the handler deadlocked a stack that then ignored every
        # further signal); the loop below turns each recorded signal into a shutdown()
        received = []

        def on_signal(signum, _frame):
            received.append(signum)

        old_int = signal.signal(signal.SIGINT, on_signal)
        old_term = signal.signal(signal.SIGTERM, on_signal)
        try:
            self.start()
            handled = 0
            while not self.wait(0.1):
                while handled < len(received):
                    signum = received[handled]
                    handled += 1
                    self.shutdown('signal', due_to_sigint=(signum == signal.SIGINT))
        finally:
            signal.signal(signal.SIGINT, old_int)
            signal.signal(signal.SIGTERM, old_term)
        return self.exit_code

    def __enter__(self):
        """Start the stack (context-manager use)."""
        return self.start()

    def __exit__(self, *exc):
        """Shut the stack down and wait for every process."""
        self.shutdown('leaving the context')
        self.wait()
        return False

    def find(self, name):
        """
        Return the :class:`RunningProcess` records whose action name or label is ``name``.

        :param name: e.g. ``'spawner'`` or ``'spawner-4'``.
        :returns: list of records, in start order.
        """
        return [r for r in list(self.processes) if name in (r.label, r.action.name)]

    # ----------------------------------------------------------------- output
    def _write(self, text):
        with self._write_lock:
            try:
                self.stream.write(text + '\n')
                self.stream.flush()
            except (OSError, ValueError):
                pass

    def _log(self, level, name, message):
        self._write(f'[{level}] [{name}]: {message}')

    def _reader(self, record, pipe, to_screen):
        for raw in iter(pipe.readline, b''):
            line = raw.decode(errors='replace').rstrip('\n')
            if line.strip():
                record.last_line = line
            if to_screen:
                self._write(f'[{record.label}] {line}')
            if self.line_callback is not None:
                try:
                    self.line_callback(record.label, line)
                except Exception as exc:  # noqa: B902 - a user callback must not stop us
                    self._log('ERROR', 'launch', f'line callback failed: {exc}')
        pipe.close()

    # ----------------------------------------------------------------- timers
    def _after(self, delay, callback):
        entry = [time.monotonic() + delay, next(self._timer_seq), callback, True]
        heapq.heappush(self._timers, entry)
        return entry

    def _cancel_timers(self, keep=None):
        for entry in self._timers:
            if keep is None or entry[2] not in keep:
                entry[3] = False

    # ----------------------------------------------------------------- main loop
    def _loop(self):
        self._log('INFO', 'launch', 'Default logging verbosity is set to INFO')
        try:
            for action in self.actions:
                if self._shutting_down:
                    break
                self._execute(action)
            while not self._idle():
                self._step()
        except Exception as exc:  # noqa: B902 - kill everything, never leave orphans
            self._error = True
            self._log('ERROR', 'launch', f'Caught exception in launch (see debug for '
                      f'traceback): {exc}')
            for record in self.processes:
                if record.running:
                    self._signal(record, signal.SIGKILL)
                    record.popen.wait()
        finally:
            for path in self._temp_files:
                try:
                    os.unlink(path)
                except OSError:
                    pass
            if self._fatal is not None and self._fatal.last_line:
                # the reason the stack stopped, last, after the other processes' goodbyes
                self._write(f'[{self._fatal.label}] {self._fatal.last_line}')
            self.exit_code = 1 if self._error or self._fatal is not None else 0

    def _idle(self):
        if any(r.running for r in self.processes):
            return False
        live = [t for t in self._timers if t[3]]
        return self._shutting_down or not live

    def _step(self):
        while self._timers and not self._timers[0][3]:
            heapq.heappop(self._timers)
        timeout = None
        if self._timers:
            timeout = max(0.0, self._timers[0][0] - time.monotonic())
        try:
            event = self._events.get(timeout=timeout)
        except queue.Empty:
            event = None
        if event is not None:
            self._handle(event)
        now = time.monotonic()
        while self._timers and self._timers[0][0] <= now:
            entry = heapq.heappop(self._timers)
            if entry[3]:
                entry[2]()

    def _handle(self, event):
        kind = event[0]
        if kind == 'exit':
            self._on_exit(event[1], event[2])
        elif kind == 'shutdown':
            self._on_shutdown(event[1], event[2])

    def _execute(self, action):
        if isinstance(action, OnProcessExit):
            self._handlers.append(action)
        elif isinstance(action, Process):
            self._spawn(action)
        else:
            raise LaunchError(f'cannot execute {type(action).__name__}')

    def _spawn(self, action):
        if self._shutting_down:
            return
        record = self._records.get(id(action))
        if record is None:
            record = RunningProcess(action, f'{action.name}-{next(self._counter)}')
            self._records[id(action)] = record
            self.processes.append(record)
        try:
            cmd = action.build_cmd()
        except LaunchError as exc:
            self._error = True
            self._log('ERROR', 'launch', str(exc))
            self._on_shutdown(f'{record.label} could not be started', False)
            return
        finally:
            self._temp_files.extend(p for p in action.temp_files() if p not in self._temp_files)
        env = dict(self.env)
        env.update(action.env)
        try:
            popen = subprocess.Popen(
                cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                env=env, cwd=action.cwd, process_group=0,
                preexec_fn=tie_to_parent(self._pid))
        except OSError as exc:
            self._error = True
            self._log('ERROR', record.label, f'exception occurred while executing process: '
                      f'{exc}')
            self._on_shutdown(f'{record.label} could not be started', False)
            return
        record.popen = popen
        record.pid = popen.pid
        record.returncode = None
        record.cmd = cmd
        record.starts += 1
        self._log('INFO', record.label, f'process started with pid [{popen.pid}]')
        screen = action.output in ('screen', 'both')
        readers = [
            threading.Thread(target=self._reader, args=(record, popen.stdout, screen),
                             daemon=True),
            threading.Thread(target=self._reader, args=(record, popen.stderr, True),
                             daemon=True),
        ]
        for reader in readers:
            reader.start()
        threading.Thread(target=self._waiter, args=(record, popen, readers),
                         daemon=True).start()

    def _waiter(self, record, popen, readers):
        returncode = popen.wait()
        for reader in readers:
            reader.join(1.0)  # a grandchild may keep the pipe open: do not wait for it
        self._events.put(('exit', (record, popen), returncode))

    def _on_exit(self, ref, returncode):
        record, popen = ref
        record.returncode = returncode
        cmd = ' '.join(part for part in record.cmd if part.strip())
        if returncode == 0:
            self._log('INFO', record.label, f'process has finished cleanly [pid {popen.pid}]')
        else:
            self._log('ERROR', record.label, f'process has died [pid {popen.pid}, exit code '
                      f"{returncode}, cmd '{cmd}'].")
        action = record.action
        if action.required and not self._shutting_down:
            if returncode != 0:
                self._fatal = record
            self._on_shutdown(f'required process {record.label} exited', False)
        for handler in list(self._handlers):
            if handler.target_action is not action or self._shutting_down:
                continue
            if handler.only_on_success and returncode != 0:
                self._log('WARNING', 'launch', f'{record.label} failed: not starting what '
                          'waits for its successful exit')
                continue
            for next_action in handler.on_exit:
                self._execute(next_action)
        if action.respawn and not self._shutting_down:
            self._after(action.respawn_delay, lambda: self._spawn(action))

    def _on_shutdown(self, reason, due_to_sigint):
        self._shutdown_requested += 1
        if due_to_sigint:
            if self._shutdown_requested == 1 or not self._shutting_down:
                self._log('WARNING', 'launch', 'user interrupted with ctrl-c (SIGINT)')
            else:
                self._log('WARNING', 'launch',
                          'user interrupted with ctrl-c (SIGINT) again, ignoring...')
        if self._shutting_down:
            return
        self._shutting_down = True
        self._cancel_timers()
        for record in self.processes:
            if record.running:
                self._shutdown_process(record)

    def _shutdown_process(self, record):
        popen = record.popen
        self._signal(record, signal.SIGINT)
        msg = "process[{}] failed to terminate '{}' seconds after receiving '{}', " \
              "escalating to '{}'"

        def escalate(sig, after, timeout, name):
            if record.popen is popen and record.running:
                self._log('ERROR', record.label,
                          msg.format(record.label, f'{timeout:g}', after, name))
                self._signal(record, sig)

        total = self.sigterm_timeout + self.sigkill_timeout
        self._after(self.sigterm_timeout, lambda: escalate(
            signal.SIGTERM, 'SIGINT', self.sigterm_timeout, 'SIGTERM'))
        self._after(total, lambda: escalate(signal.SIGKILL, 'SIGTERM', total, 'SIGKILL'))

    def _signal(self, record, sig):
        try:
            os.killpg(record.popen.pid, sig)
        except (ProcessLookupError, PermissionError):
            try:
                record.popen.send_signal(sig)
            except (ProcessLookupError, OSError):
                pass
