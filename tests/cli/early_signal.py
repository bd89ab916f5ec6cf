#!/usr/bin/env python3
"""A stop signal while the run starts (issue 24, defect 6): exit 5 with a checkpoint, not 143.

    early_signal.py --exe ALPHAFLEX --scene SCENE --out DIR [--set key=value ...]

SIGTERM is sent as soon as the process catches it (its /proc/PID/status SigCgt), which must be
while it has one thread, i.e. before MPI_Init starts its threads (MPI and PETSc take ~0.7 s): the handler was installed only
after PetscInitialize, and an early signal killed the run with exit 143 and no message. The run
must go on to its first step, write a checkpoint and exit 5 with the stop message.
"""
import argparse
import os
import signal
import subprocess
import sys
import time


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--set", action="append", default=[])
    a = ap.parse_args()
    cmd = [a.exe, "run", a.scene, "-o", a.out] + [w for s in a.set for w in ("--set", s)]
    p = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    sigterm = 1 << (signal.SIGTERM - 1)
    deadline = time.time() + 30
    while time.time() < deadline and p.poll() is None:
        try:
            status = open(f"/proc/{p.pid}/status").read()
        except OSError:
            break
        caught = int(next(l.split()[1] for l in status.splitlines() if l.startswith("SigCgt:")), 16)
        threads = int(next(l.split()[1] for l in status.splitlines() if l.startswith("Threads:")))
        if caught & sigterm:
            if threads > 1:  # MPI_Init starts threads: the handler came after it
                p.kill()
                p.communicate()
                print(f"FAIL: SIGTERM is caught only once MPI has started ({threads} threads): a signal before kills the run")
                return 1
            break
        time.sleep(0.0005)
    p.send_signal(signal.SIGTERM)
    out, err = p.communicate(timeout=120)
    if p.returncode != 5 or "stopped by SIGTERM" not in err:
        print(f"FAIL: {' '.join(cmd)}: exit {p.returncode}, expected 5 and 'stopped by SIGTERM'\n{err}")
        return 1
    if not os.path.exists(os.path.join(a.out, os.path.basename(err.split("checkpoint ")[1].split(",")[0]))):
        print(f"FAIL: no checkpoint\n{err}")
        return 1
    print("OK: " + err.strip().splitlines()[0])
    return 0


if __name__ == "__main__":
    sys.exit(main())
