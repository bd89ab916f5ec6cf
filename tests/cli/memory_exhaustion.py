#!/usr/bin/env python3
"""Memory exhaustion (issue 24, defect 3): a run whose address space is limited (ulimit -v, set with
setrlimit(RLIMIT_AS) on the process that mpirun or alphaflex is) must end with exit 3 and one
message — what was being allocated, how much when known, and what to do (fewer unknowns per rank:
more ranks) — never a PETSc trace, an MPI_Abort, an internal error or a hang.

    memory_exhaustion.py --exe alphaflex --scene inputs/gridshell.yaml --out DIR --np N
                         [--mpirun mpiexec] --limits MB[,MB...] [--expect WHAT] [--set k=v ...]

Each limit (MB of address space per process) is one run. A run may still succeed (exit 0: the limit
was enough on this machine); every run that fails must fail as above, and at least one must fail
with the message matching --expect (a regex over the message: the phase that ran out). The runs
are killed after --timeout s (a hang: OpenBLAS waiting forever for its workspace, PETSc's hash
table growing forever), which fails the test.
"""
import argparse
import os
import re
import resource
import signal
import subprocess
import sys
import time

FORBID = re.compile(r"Segmentation fault|Caught signal|PETSC ERROR|MPI_ABORT|internal error|terminate called|"
                    r"Aborted|core dumped|Traceback|std::bad_alloc")
MESSAGE = re.compile(r"out of memory on rank \d+ while (.*?)(: [0-9.e+]+ MB could not be allocated)? \(this process: "
                     r".*What to do: fewer unknowns per rank — run on more ranks", re.DOTALL)


def run(cmd, limit_mb, timeout):
    def limit():
        b = int(limit_mb * 1048576)
        resource.setrlimit(resource.RLIMIT_AS, (b, b))
    t0 = time.monotonic()
    p = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         preexec_fn=limit, start_new_session=True)
    try:
        out, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, err = p.communicate()
        return None, out.decode(errors="replace"), err.decode(errors="replace"), time.monotonic() - t0
    return p.returncode, out.decode(errors="replace"), err.decode(errors="replace"), time.monotonic() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--mpirun", default="mpiexec")
    ap.add_argument("--limits", required=True, help="MB of address space per process, comma-separated")
    ap.add_argument("--expect", default=".", help="regex the phase of at least one failure must match")
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--timeout", type=float, default=40.0)
    a = ap.parse_args()
    base = [a.exe, "run", a.scene] + [x for s in a.set for x in ("--set", s)] + ["-af_exit_timeout", "3"]
    expect = re.compile(a.expect)
    seen = []
    for mb in [float(x) for x in a.limits.split(",")]:
        out_dir = os.path.join(a.out, f"limit_{int(mb)}")
        cmd = base + ["-o", out_dir]
        if a.np > 1:
            cmd = [a.mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(a.np)] + cmd
        code, out, err, wall = run(cmd, mb, a.timeout)
        print(f"limit {mb:.0f} MB, {a.np} rank(s): exit {code} after {wall:.1f} s")
        if code is None:
            print(f"FAIL: no end within {a.timeout} s (a hang)\n--- stderr:\n{err}")
            return 1
        if code == 0:
            continue
        m = MESSAGE.search(err)
        bad = FORBID.search(err)
        if code != 3 or not m or bad:
            print(f"FAIL: expected exit 3 and the out-of-memory message, without "
                  f"{bad.group(0) if bad else 'a trace'}\n--- stderr:\n{err}")
            return 1
        print(f"  while {m.group(1)[:200]}")
        seen.append(m.group(1))
    if not any(expect.search(s) for s in seen):
        print(f"FAIL: no run failed while {a.expect!r}; failures: {seen}")
        return 1
    print("OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
