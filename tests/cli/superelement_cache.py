#!/usr/bin/env python3
"""The superelement cache (issue 19, `output.superelement_cache`, io/superelement_cache.hpp): a
reduced block is computed once and kept in OUTDIR/NAME.superelements.h5; a later run with the
same key reads it. The pendulum of tests/cli/reduced_pendulum.yaml, its strip reduced to 4
Craig-Bampton modes with geometric stiffness (so that the cubic and quartic tensors are stored too).

Checks:
- the first run computes and writes the file; the second reads it (the summary says which) and
  its sensor CSV is the first's to the last byte;
- a cut-off file and a file that is not HDF5 are named in a warning, the block is computed again
  (the same CSV), the file rewritten, and the next run reads it;
- another key (6 modes; another Young's modulus; the modes given by a parameter whose value --set
  changes) is computed and kept beside the first: the 4-mode key is still read afterwards;
- `output.superelement_cache: off` writes no file and reads none;
- 2 ranks: rank 0 reads and sends; the CSV equals the 2-rank run that computed, and 1 rank reading
  the file 2 ranks wrote gives the 1-rank CSV;
- a cache path that cannot be read or written (a directory of that name) is a warning, never a
  failed run: the results are all there."""
import os
import shutil
import subprocess
import sys

import reduced_pendulum

NAME = "reduced_pendulum"
RED = "beams.0.reduction={method: craig_bampton, modes: %d, interface: [root], geometric_stiffness: on}"


def main():
    p = reduced_pendulum.cli_parser()
    a = p.parse_args()
    shutil.rmtree(a.out, ignore_errors=True)
    ok = True

    def check(cond, what):
        nonlocal ok
        print(("ok   " if cond else "FAIL ") + what)
        ok = ok and cond

    def run(d, modes=4, extra=(), np=1):
        launcher = [a.mpirun, "--oversubscribe", "-np", str(np)] if np > 1 else []
        out = os.path.join(a.out, d)
        r = subprocess.run(launcher + [a.exe, "run", a.scene, "-o", out, "--set", "solver.t_end=0.05", "--set", RED % modes] + list(extra),
                           capture_output=True, text=True, timeout=120)
        if r.returncode != 0:
            sys.exit(f"{d}: exit {r.returncode}\n{r.stdout}\n{r.stderr}")
        with open(os.path.join(out, NAME + ".csv"), "rb") as f:
            return r.stdout, f.read()

    cache = lambda d: os.path.join(a.out, d, NAME + ".superelements.h5")
    s1, csv1 = run("one")
    check("strip: computed in" in s1 and "written to " + cache("one") in s1 and os.path.isfile(cache("one")),
          "the first run computes the block and writes the cache")
    s2, csv2 = run("one")
    check("strip: read from " + cache("one") in s2, "the second run reads it")
    check(csv2 == csv1, "and its CSV is the first's to the last byte")

    size = os.path.getsize(cache("one"))
    with open(cache("one"), "r+b") as f:
        f.truncate(size // 2)
    s3, csv3 = run("one")
    check("warning: " + cache("one") in s3 and "computed again" in s3 and "strip: computed in" in s3,
          "a cut-off file: a warning naming it, the block computed again")
    check(csv3 == csv1, "the same CSV")
    s4, _ = run("one")
    check("strip: read from" in s4 and "warning" not in s4, "the rewritten file is read by the next run")
    with open(cache("one"), "w") as f:
        f.write("not an HDF5 file\n")
    s5, csv5 = run("one")
    check("warning: " + cache("one") in s5 and "cannot be read as an HDF5 file" in s5 and csv5 == csv1,
          "a file that is not HDF5: a warning, computed again, the same CSV")

    s6, csv6 = run("one", modes=6)
    check("strip: computed in" in s6 and csv6 != csv1, "6 modes: another key, computed")
    s7, _ = run("one", extra=["--set", "beams.0.section.E=2.0e11"])
    check("strip: computed in" in s7, "another Young's modulus: another key, computed")
    s8, csv8 = run("one")
    check("strip: read from" in s8 and csv8 == csv1, "the 4-mode key is still kept beside them and read")

    # The modes given by a parameter: the key holds the evaluated count, not the text `nm`.
    par = lambda nm: ["--set", f"parameters.nm={nm}", "--set",
                      "beams.0.reduction={method: craig_bampton, modes: nm, interface: [root], geometric_stiffness: on}"]
    p4, pcsv4 = run("param", extra=par(4))
    p6, pcsv6 = run("param", extra=par(6))
    check("strip: computed in" in p6 and pcsv4 == csv1 and pcsv6 == csv6,
          "modes: nm with --set parameters.nm=6 after nm=4: another key (the evaluated count), computed")

    s9, csv9 = run("off", extra=["--set", "output.superelement_cache=off"])
    check("no superelement cache" in s9 and not os.path.exists(cache("off")) and csv9 == csv1,
          "superelement_cache: off writes no file (the same CSV)")

    t1, c1 = run("two", np=2)
    t2, c2 = run("two", np=2)
    check("strip: computed in" in t1 and "strip: read from" in t2 and c2 == c1, "2 ranks: read and sent by rank 0, the same CSV")
    t3, c3 = run("two")
    check("strip: read from" in t3 and c3 == csv1, "1 rank reading the file of 2 ranks: the 1-rank CSV")

    os.makedirs(cache("blocked"))
    u, cu = run("blocked")
    check(u.count("warning: ") >= 2 and "not kept: see the warning" in u and "written to" not in u and cu == csv1 and os.path.isfile(os.path.join(a.out, "blocked", NAME + ".h5")),
          "a cache path that is a directory: warnings, the run and its results complete")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
