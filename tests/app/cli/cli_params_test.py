#!/usr/bin/env python3
"""Every row of the parameter table through the command line, generated from
`isolux-cli params`: both ends of its range are accepted and written to the
preset, one step beyond is refused with a one-line error naming the field, and
the old flag names still work. Usage: cli_params_test.py PATH/TO/isolux-cli"""
import json, math, os, subprocess, sys, tempfile

cli = sys.argv[1]
failures, passes = [], 0


def run(*args):
    return subprocess.run([cli, *args], capture_output=True, text=True)


def expect_written(row, flag_args, want):
    global passes
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "p.json")
        r = run("preset", *flag_args, "--out", out)
        if r.returncode != 0:
            failures.append(f"{row['name']} {flag_args}: exit {r.returncode}: {r.stderr.strip()}")
            return
        got = json.load(open(out))[row["name"]]
        if got != want:
            failures.append(f"{row['name']} {flag_args}: wrote {got!r}, want {want!r}")
            return
    passes += 1


def expect_refused(row, flag_args):
    global passes
    r = run("preset", *flag_args, "--out", os.devnull + ".never")
    lines = r.stderr.strip().splitlines()
    if r.returncode != 2 or len(lines) != 1 or row["name"] not in lines[0]:
        failures.append(f"{row['name']} {flag_args}: exit {r.returncode}, stderr {r.stderr.strip()!r}")
        return
    passes += 1


listing = run("params")
assert listing.returncode == 0, listing.stderr
header, *lines = listing.stdout.strip().splitlines()
keys = header.split("\t")
rows = [dict(zip(keys, line.split("\t"))) for line in lines]
assert len(rows) >= 13, f"only {len(rows)} parameters listed"

for row in rows:
    flag, kind = row["flag"], row["type"]
    flags = [flag] + ([row["old_flag"]] if row["old_flag"] != "-" else [])
    if kind in ("integer", "real"):
        excluded = row["min"].endswith("(excluded)")
        lo = float(row["min"].split()[0])
        hi = float(row["max"])
        num = int if kind == "integer" else float
        if not excluded:
            for f in flags:
                expect_written(row, [f, row["min"]], num(lo))
        expect_written(row, [flag, row["max"]], num(hi))
        if kind == "integer":
            below, above = str(int(lo) - 1), str(int(hi) + 1)
        else:
            below = repr(lo) if excluded else repr(math.nextafter(lo, -math.inf))
            above = repr(math.nextafter(hi, math.inf))
        expect_refused(row, [flag, below])
        expect_refused(row, [flag, above])
    elif kind == "choice":
        for name in (row["min"], row["max"]):
            expect_written(row, [flag, name], name)
        expect_refused(row, [flag, "no_such_choice"])
    elif kind == "boolean":
        expect_written(row, [flag], True)
    else:
        failures.append(f"{row['name']}: unknown type {kind}")

for f in failures:
    print("FAIL", f)
print(f"cli params: {passes} passed, {len(failures)} failed")
sys.exit(1 if failures else 0)
