#!/usr/bin/python3
"""Output that costs nothing when it is not wanted (issue 22): output.sensors, output.sensors_dt and
output.checkpoint_at_end, through the real executable, on --np ranks.

  1. default: NAME.csv has a row per step (and t = 0), NAME.checkpoint.h5 exists;
  2. output.sensors=off, output.checkpoint_at_end=off: no NAME.csv, no checkpoint, and the
     summary's final sensor values equal the default run's (bit for bit: the same steps);
  3. output.sensors_dt = 5 h: the rows are those of run 1 at t = 0, 5h, 10h, ... and t_end, value
     for value;
  4. the same with a checkpoint after step 7 and a restart from it: the CSV equals run 3's.
"""
import json
import os
import subprocess
import sys

from run_options import parser, prepare


def main():
    ap = parser(__doc__)
    a = ap.parse_args()
    name = prepare(a)
    launcher = [a.mpirun, "--oversubscribe", "-np", str(a.np)] if a.np > 1 else []

    def run(tag, *sets, restart=None):
        out = os.path.join(a.out, tag)
        cmd = launcher + [a.exe, "run", a.scene, "-o", out, "--set", "output.hdf5=off"]
        for s in list(a.set) + list(sets):
            cmd += ["--set", s]
        if restart:
            cmd += ["--restart", restart]
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=60)
        if p.returncode != 0:
            sys.exit(f"{tag}: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
        with open(os.path.join(out, name + ".summary.json")) as fh:
            return out, json.load(fh)

    def rows(out):
        with open(os.path.join(out, name + ".csv")) as fh:
            lines = fh.read().splitlines()
        return lines[0], [line.split(",") for line in lines[1:]]

    failures = []
    out1, s1 = run("default")
    head1, r1 = rows(out1)
    if len(r1) != s1["steps"] + 1:
        failures.append(f"default: {len(r1)} rows for {s1['steps']} steps (expected steps + 1)")
    if not os.path.exists(os.path.join(out1, name + ".checkpoint.h5")):
        failures.append("default: no checkpoint at the end")

    out2, s2 = run("off", "output.sensors=off", "output.checkpoint_at_end=off")
    for f in (name + ".csv", name + ".checkpoint.h5"):
        if os.path.exists(os.path.join(out2, f)):
            failures.append(f"sensors and checkpoint off: {f} was written")
    if s2["final_sensors"] != s1["final_sensors"]:
        failures.append(f"sensors off: final sensors {s2['final_sensors']} != {s1['final_sensors']}")
    if s2["checkpoints"]["written"] != 0:
        failures.append(f"checkpoint_at_end off: {s2['checkpoints']['written']} checkpoints written")

    h, t_end = s1["h"], s1["t_end"]
    every = 5
    _, s3 = run("dt", f"output.sensors_dt={every * h!r}")
    out3 = os.path.join(a.out, "dt")
    head3, r3 = rows(out3)
    expected = [r for k, r in enumerate(r1) if k % every == 0 or k == len(r1) - 1]
    if head3 != head1 or r3 != expected:
        failures.append(f"sensors_dt = {every} h: {len(r3)} rows {[r[0] for r in r3]}, expected {[r[0] for r in expected]}")

    # A checkpoint after step 7 only (none at the end), then a restart from it into the same
    # directory: the CSV is cut to the checkpoint's rows and goes on.
    ck_out, _ = run("dt_restart", f"output.sensors_dt={every * h!r}", "output.checkpoint_every=7",
                    "output.checkpoint_at_end=off")
    run("dt_restart", f"output.sensors_dt={every * h!r}", restart=os.path.join(ck_out, name + ".checkpoint.h5"))
    _, r4 = rows(ck_out)
    if r4 != r3:
        failures.append(f"restart with sensors_dt: rows {[r[0] for r in r4]}, expected {[r[0] for r in r3]}")

    if failures:
        print("\n".join(failures))
        sys.exit(1)
    print(f"ok: {len(r1)} rows by default, {len(r3)} with sensors_dt = {every} h, none with sensors off; "
          f"final sensors equal; restart rows equal (t_end = {t_end} s)")


if __name__ == "__main__":
    main()
