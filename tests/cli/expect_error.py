#!/usr/bin/env python3
"""Run a command and check that it fails the way it should.

    expect_error.py --exit CODE --stderr REGEX [--timeout S] [--forbid REGEX] -- COMMAND [ARG ...]

Passes (exit 0) when COMMAND ends within the timeout, with exit code CODE, and its stderr matches
REGEX (Python re.search, so the match may be anywhere; the message may span lines) and does not
match the forbidden pattern (by default: signs of a crash, an abort or a PETSc stack trace, which a
bad input must never produce). Otherwise prints what was expected, what happened, and the full
stderr, and exits 1.

The command runs in its own process group; on timeout the group gets SIGTERM (mpiexec passes it on
to its ranks), then SIGKILL, so a hang is reported as a failure instead of blocking the test run.
"""
import argparse
import os
import re
import signal
import subprocess
import sys

# A bad input gets a one-line error and a non-zero exit: never a crash, an MPI_Abort or a PETSc trace.
DEFAULT_FORBID = (r"Segmentation fault|Caught signal|PETSC ERROR|MPI_ABORT|internal error|"
                  r"terminate called|Aborted|core dumped|Traceback")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exit", type=int, required=True, dest="code", help="expected exit code")
    ap.add_argument("--stderr", required=True, help="regex that stderr must match (re.search)")
    ap.add_argument("--timeout", type=float, default=30.0, help="seconds (default 30)")
    ap.add_argument("--forbid", default=DEFAULT_FORBID,
                    help="regex that stderr must not match ('' to allow anything)")
    ap.add_argument("command", nargs=argparse.REMAINDER, help="-- COMMAND [ARG ...]")
    a = ap.parse_args()
    cmd = a.command[1:] if a.command[:1] == ["--"] else a.command
    if not cmd:
        ap.error("no command given (put it after --)")
    try:
        pattern = re.compile(a.stderr, re.MULTILINE | re.DOTALL)
        forbid = re.compile(a.forbid) if a.forbid else None
    except re.error as e:
        ap.error(f"bad regex: {e}")

    shown = " ".join(cmd)
    try:
        p = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             start_new_session=True)
    except OSError as e:
        print(f"FAIL: cannot start {shown}: {e}")
        return 1
    try:
        out, err = p.communicate(timeout=a.timeout)
    except subprocess.TimeoutExpired:
        # SIGTERM first: mpiexec forwards it to its ranks (which run in process groups of their
        # own) and cleans up; SIGKILL the group if that does not end it.
        os.killpg(p.pid, signal.SIGTERM)
        try:
            out, err = p.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            out, err = p.communicate()
        print(f"FAIL: {shown}\n  did not finish within {a.timeout:g} s (hang?); killed.")
        print("--- stderr ---\n" + err.decode(errors="replace") + "--- stdout ---\n" + out.decode(errors="replace"))
        return 1
    err_text = err.decode(errors="replace")
    out_text = out.decode(errors="replace")

    problems = []
    if p.returncode != a.code:
        got = f"killed by signal {-p.returncode}" if p.returncode < 0 else str(p.returncode)
        problems.append(f"exit code {got}, expected {a.code}")
    if not pattern.search(err_text):
        problems.append(f"stderr does not match /{a.stderr}/")
    if forbid:
        m = forbid.search(err_text)
        if m:
            problems.append(f"stderr contains '{m.group(0)}' (a crash or abort, not an input error)")
    if problems:
        print(f"FAIL: {shown}")
        for pr in problems:
            print("  " + pr)
        print("--- stderr ---\n" + err_text + "--- stdout ---\n" + out_text, end="")
        return 1
    first = err_text.strip().splitlines()[0] if err_text.strip() else "(empty stderr)"
    print(f"ok: exit {p.returncode}: {first}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
