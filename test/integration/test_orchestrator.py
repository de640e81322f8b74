# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""The orchestrator on small dummy processes: chaining, required, respawn, shutdown, orphans."""

import io
import os
import re
import signal
import sys
import textwrap
import time

from amr_description.launch.actions import OnProcessExit
from amr_description.launch.actions import Process
from amr_description.launch.orchestrator import Orchestrator

PY = sys.executable
STUBBORN = ('import signal, time; signal.signal(signal.SIGINT, signal.SIG_IGN); '
            'signal.signal(signal.SIGTERM, signal.SIG_IGN); print("ready", flush=True); '
            'time.sleep(60)')


def _py(code, name, **kwargs):
    return Process([PY, '-c', code], name=name, **kwargs)


def _pids(output):
    return {label: int(pid) for label, pid in
            re.findall(r'\[INFO\] \[(\S+)\]: process started with pid \[(\d+)\]', output)}


def _alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    try:  # a zombie still answers kill(0): look at its state
        with open(f'/proc/{pid}/stat') as f:
            return f.read().rsplit(')', 1)[1].split()[0] != 'Z'
    except OSError:
        return False


def _run(actions, timeout=60.0, **kwargs):
    out = io.StringIO()
    orch = Orchestrator(actions, stream=out, **kwargs).start()
    finished = orch.wait(timeout)
    if not finished:
        orch.shutdown()
        orch.wait(15)
    return orch, out.getvalue(), finished


def test_on_exit_chaining_and_log_lines():
    a = _py('import time; time.sleep(0.3); print("from a")', 'a')
    b = _py('print("from b"); raise SystemExit(3)', 'b')
    c = _py('print("from c")', 'c')
    skipped = _py('print("never")', 'skipped')
    orch, out, finished = _run([a, OnProcessExit(a, [b]), OnProcessExit(b, [c]),
                                OnProcessExit(b, [skipped], only_on_success=True)])
    assert finished and orch.exit_code == 0, out
    lines = out.splitlines()
    pids = _pids(out)
    assert sorted(pids) == ['a-1', 'b-2', 'c-3']
    order = [lines.index(x) for x in (
        '[a-1] from a', f'[INFO] [a-1]: process has finished cleanly [pid {pids["a-1"]}]',
        f'[INFO] [b-2]: process started with pid [{pids["b-2"]}]', '[b-2] from b',
        f'[ERROR] [b-2]: process has died [pid {pids["b-2"]}, exit code 3, '
        f"cmd '{PY} -c print(\"from b\"); raise SystemExit(3)'].",
        f'[INFO] [c-3]: process started with pid [{pids["c-3"]}]', '[c-3] from c')]
    assert order == sorted(order), out
    assert 'never' not in out


def test_required_exit_shuts_the_stack_down():
    sleeper = _py('import time; time.sleep(30)', 'sleeper')
    short = _py('import time; time.sleep(0.3)', 'short', required=True)
    start = time.monotonic()
    orch, out, finished = _run([sleeper, short])
    # well before the sleeper's own 30 s: the required process's exit stopped it
    assert finished and time.monotonic() - start < 20.0, out
    record = orch.find('sleeper')[0]
    assert record.returncode == -signal.SIGINT, out
    assert not _alive(record.pid)


def test_respawn_with_delay(tmp_path):
    stamps = tmp_path / 'stamps'
    code = f'import time; open({str(stamps)!r}, "a").write(f"{{time.monotonic()}}\\n")'
    orch = Orchestrator([_py(code, 'flaky', respawn=True, respawn_delay=0.5)],
                        stream=io.StringIO()).start()
    # wait for three starts (a loaded machine takes a while to start each interpreter)
    deadline = time.monotonic() + 60.0
    while time.monotonic() < deadline and (
            not stamps.exists() or len(stamps.read_text().split()) < 3):
        time.sleep(0.05)
    orch.shutdown()
    assert orch.wait(30)
    times = [float(t) for t in stamps.read_text().split()]
    assert len(times) >= 3, times
    gaps = [b - a for a, b in zip(times, times[1:])]
    assert all(g >= 0.5 for g in gaps), gaps
    record = orch.find('flaky')[0]
    # the last start may have been interrupted before it wrote its stamp
    assert record.label == 'flaky-1' and record.starts in (len(times), len(times) + 1)


def test_context_manager_stops_everything():
    ready = []
    code = 'import time; print("ready", flush=True); time.sleep(30)'
    with Orchestrator([_py(code, 'a'), _py(code, 'b')], stream=io.StringIO(),
                      line_callback=lambda label, line: ready.append(label)) as orch:
        deadline = time.monotonic() + 60
        while len(ready) < 2 and time.monotonic() < deadline:
            time.sleep(0.05)
        assert sorted(ready) == ['a-1', 'b-2']
    assert [r.returncode for r in orch.processes] == [-signal.SIGINT] * 2


DRIVER = textwrap.dedent("""
    import sys
    from amr_description.launch.actions import Process
    from amr_description.launch.orchestrator import Orchestrator
    actions = [Process([sys.executable, '-c', {stubborn!r}], name='stubborn'),
               Process([sys.executable, '-c', {sleeper!r}], name='sleeper')]
    sys.exit(Orchestrator(actions, sigterm_timeout=0.6, sigkill_timeout=0.6).run())
""")


def _start_driver(procs, ros_env, tmp_path):
    script = tmp_path / 'driver.py'
    sleeper = 'import time; print("ready", flush=True); time.sleep(60)'
    script.write_text(DRIVER.format(stubborn=STUBBORN, sleeper=sleeper))
    proc = procs.start([PY, str(script)], ros_env)
    assert proc.wait_for_output('[stubborn-1] ready', timeout=60), proc.output
    assert proc.wait_for_output('[sleeper-2] ready', timeout=60), proc.output
    deadline = time.monotonic() + 60
    while len(_pids(proc.output)) < 2 and time.monotonic() < deadline:
        time.sleep(0.05)
    pids = _pids(proc.output)
    assert sorted(pids) == ['sleeper-2', 'stubborn-1'], proc.output
    return proc, pids


def test_sigint_escalates_to_sigterm_then_sigkill(procs, ros_env, tmp_path):
    proc, pids = _start_driver(procs, ros_env, tmp_path)
    start = time.monotonic()
    os.kill(proc.popen.pid, signal.SIGINT)
    time.sleep(0.2)
    os.kill(proc.popen.pid, signal.SIGINT)  # a second Ctrl-C changes nothing
    assert proc.wait(60) == 0, proc.output
    elapsed = time.monotonic() - start
    # 0.6 s to SIGTERM plus 0.6 s to SIGKILL; the upper bound leaves room for a loaded
    # machine and still fails if the stubborn process were waited for (its own 60 s)
    assert 1.1 <= elapsed < 20.0, (elapsed, proc.output)
    out = proc.output
    assert '[WARNING] [launch]: user interrupted with ctrl-c (SIGINT)\n' in out
    assert 'user interrupted with ctrl-c (SIGINT) again, ignoring...' in out
    assert ("[ERROR] [stubborn-1]: process[stubborn-1] failed to terminate '0.6' seconds "
            "after receiving 'SIGINT', escalating to 'SIGTERM'") in out
    assert ("[ERROR] [stubborn-1]: process[stubborn-1] failed to terminate '1.2' seconds "
            "after receiving 'SIGTERM', escalating to 'SIGKILL'") in out
    assert f'process has died [pid {pids["stubborn-1"]}, exit code -9' in out
    assert f'process has died [pid {pids["sleeper-2"]}, exit code -2' in out
    assert 'escalating' not in ''.join(line for line in out.splitlines()
                                       if line.startswith('[ERROR] [sleeper-2]'))
    assert not any(_alive(pid) for pid in pids.values())


def test_no_orphans_when_orchestrator_is_sigkilled(procs, ros_env, tmp_path):
    proc, pids = _start_driver(procs, ros_env, tmp_path)
    os.kill(proc.popen.pid, signal.SIGKILL)  # only the orchestrator, not its group
    proc.wait(30)
    deadline = time.monotonic() + 30
    while any(_alive(pid) for pid in pids.values()) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not any(_alive(pid) for pid in pids.values())
