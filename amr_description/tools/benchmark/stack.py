# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""The stack under test: the ``sim`` or ``fleet`` stack under the orchestrator."""

import os
import tempfile
import time

from amr_description.tools.benchmark.common import BenchmarkError
from amr_description.tools.benchmark.common import SPACING


class Stack:
    """The ``sim`` (one robot) or ``fleet`` stack under the orchestrator, output captured."""

    def __init__(self, count, rtf, domain_id, extra=()):
        """
        Start the stack.

        :param count: number of robots.
        :param rtf: real-time factor (0 = as fast as possible).
        :param domain_id: ROS domain.
        :param extra: more launch arguments (``name:=value``).
        """
        from amr_description.launch import registry
        from amr_description.launch.orchestrator import Orchestrator

        self.count = count
        self.stage = f'{count} robot{"s" if count > 1 else ""}, rtf {rtf:g}'
        name = 'sim' if count == 1 else 'fleet'
        argv = [f'rtf:={rtf:g}', 'headless:=true']
        if count > 1:
            argv += [f'robots:={count}', f'spacing:={SPACING:g}']
        if 'viewer' in {d.name for d in registry.STACKS[name][1]}:
            argv.append('viewer:=false')
        argv += list(extra)
        self.lines = {}
        env = dict(os.environ, ROS_DOMAIN_ID=str(domain_id),
                   ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
        self._log = tempfile.TemporaryFile(mode='w+')
        self.orchestrator = Orchestrator(registry.describe(name, argv), stream=self._log,
                                         env=env, line_callback=self._line)
        self.started = time.monotonic()
        self.orchestrator.start()
        self.spawners = count  # one spawner per robot, for both controllers

    def _line(self, label, line):
        self.lines.setdefault(label, []).append(line)

    def output(self, label, tail=40):
        """Return the last ``tail`` output lines of process ``label``."""
        return '\n'.join(f'[{label}] {line}' for line in self.lines.get(label, [])[-tail:])

    def _failed(self):
        """Return the record of a process that exited with an error (or the sim), or None."""
        for record in list(self.orchestrator.processes):
            code = record.returncode
            if code is None:
                continue
            if code != 0 or record.action.name == 'mujoco_sim':
                return record
        return None

    def check(self, what):
        """
        Raise :class:`BenchmarkError` when a process of the stack failed.

        :param what: the stage, e.g. ``'start-up'``.
        """
        record = self._failed()
        if record is not None:
            raise BenchmarkError(f'{what}, {self.stage}',
                                 f'{record.label} exited with code {record.returncode}',
                                 self.output(record.label))

    def wait_active(self, timeout):
        """
        Wait until every spawner exited 0; return the wall seconds since the stack started.

        :raises BenchmarkError: a process failed, or not every controller was active in time.
        """
        deadline = self.started + timeout
        while time.monotonic() < deadline:
            self.check('start-up')
            done = [r for r in self.orchestrator.find('spawner') if r.returncode == 0]
            if len(done) >= self.spawners:
                return time.monotonic() - self.started
            time.sleep(0.02)
        records = list(self.orchestrator.processes)
        states = ', '.join(
            f'{r.label} ' + ('running' if r.returncode is None else f'exit {r.returncode}')
            for r in records)
        raise BenchmarkError(
            f'start-up, {self.stage}',
            f'controllers not active after {timeout:g} s ({self.spawners} spawner(s) '
            f'expected to exit 0; processes: {states})',
            '\n'.join(self.output(r.label, 8) for r in records if r.returncode is None))

    def pids(self, name=None):
        """Return the pids of the running processes (of action ``name`` only, if given)."""
        return [r.pid for r in list(self.orchestrator.processes)
                if r.returncode is None and r.pid and (name is None or r.action.name == name)]

    def close(self):
        """Stop every process of the stack and wait for them."""
        self.orchestrator.shutdown()
        self.orchestrator.wait(timeout=30.0)
        self._log.close()
