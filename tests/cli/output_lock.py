#!/usr/bin/env python3
"""Two runs sharing an output directory (issue 24, defect 2; io/output_lock.hpp).

    output_lock.py --exe ALPHAFLEX --scene SCENE --out DIR [--np N --mpirun MPIRUN]

A long run A starts; once its lock file OUTDIR/NAME.lock names it, a second run B of the same
scene into the same directory must be refused at start (exit 6) with a message naming A (its PID
and host) and must leave A's files alone. A is then killed with SIGKILL (its lock file stays,
naming a process that no longer holds it): a run C must take the stale lock over (a warning saying
so), finish with exit 0 and the results of C alone (the CSV's t increasing from 0 to t_end), and
remove the lock file at its end.
"""
import os
import re
import signal
import subprocess
import sys
import time

import run_options


def fail(msg, err=""):
    print("FAIL: " + msg + ("\n--- output ---\n" + err if err else ""))
    sys.exit(1)


def main():
    ap = run_options.parser(__doc__)
    a = ap.parse_args()
    name = run_options.prepare(a)
    lock = os.path.join(a.out, name + ".lock")

    def command(t_end):
        pre = [a.mpirun, "--oversubscribe", "-np", str(a.np)] if a.np > 1 else []
        return pre + [a.exe, "run", a.scene, "-o", a.out, "--set", f"solver.t_end={t_end}"]

    first = subprocess.Popen(command(1000), stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        deadline = time.time() + 60
        text = ""
        while time.time() < deadline and "pid " not in text:
            time.sleep(0.2)
            if first.poll() is not None:
                fail(f"run A ended (exit {first.returncode}) before it held the lock", first.stderr.read())
            text = open(lock).read() if os.path.exists(lock) else ""
        pid = re.search(r"^pid (\d+)$", text, re.M)
        host = re.search(r"^host (\S+)$", text, re.M)
        if not pid or not host:
            fail(f"{lock} does not name run A: {text!r}")
        csv = os.path.join(a.out, name + ".csv")
        # Run A takes the lock before it creates its files: under load its CSV can lag the lock.
        header = ""
        while time.time() < deadline and not header.endswith("\n"):
            header = open(csv).readline() if os.path.exists(csv) else ""
            if not header.endswith("\n"):
                time.sleep(0.1)
        if not header:
            fail(f"run A holds the lock but wrote no {csv} within 60 s")
        second = subprocess.run(command(0.05), stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=60)
        want = (re.escape(lock) + r": another run writes the results of '" + re.escape(name) +
                r"' in this directory \(PID " + pid.group(1) + " on host " + re.escape(host.group(1)))
        if second.returncode != 6 or not re.search(want, second.stderr):
            fail(f"run B: exit {second.returncode}, expected 6 and /{want}/", second.stderr)
        if first.poll() is not None:
            fail("run A ended while B was refused", first.stderr.read())
        if open(csv).readline() != header:
            fail("run B touched run A's CSV")
    finally:
        if first.poll() is None:
            os.killpg(first.pid, signal.SIGKILL)  # the whole job: mpirun and its ranks
        first.wait()
    # The ranks of a killed mpirun job end a moment after mpirun (Open MPI's launcher kills them
    # when it loses mpirun): wait until the process the lock names is gone, then C runs.
    deadline = time.time() + 60
    while time.time() < deadline:
        try:
            os.kill(int(pid.group(1)), 0)
        except ProcessLookupError:
            break
        except PermissionError:
            pass
        time.sleep(0.1)
    else:
        fail(f"run A's process {pid.group(1)} still exists 60 s after SIGKILL to its job")
    time.sleep(0.2)
    if not os.path.exists(lock):
        fail("run A's lock file is gone after SIGKILL: the stale case is not tested")
    third = subprocess.run(command(0.05), stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=120)
    if third.returncode != 0 or not re.search(r"\.lock: the lock of a run that did not end cleanly \(PID " + pid.group(1) +
                                              r" .*\) was taken over: no process holds it any more", third.stdout):
        fail(f"run C: exit {third.returncode}, expected 0 and a warning that the stale lock was taken over",
             third.stdout + third.stderr)
    times = [float(line.split(",")[0]) for line in open(csv).read().splitlines()[1:]]
    if times[0] != 0.0 or abs(times[-1] - 0.05) > 1e-12 or any(b <= c for c, b in zip(times, times[1:])):
        fail(f"the CSV is not run C's alone: t from {times[0]} to {times[-1]}, {len(times)} rows")
    if os.path.exists(lock):
        fail(f"{lock} is left after run C ended")
    print(f"OK: run B refused naming PID {pid.group(1)} on {host.group(1)}; the stale lock taken over by run C")
    return 0


if __name__ == "__main__":
    sys.exit(main())
