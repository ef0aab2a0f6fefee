"""The tally the Python end-to-end tests keep (tests/capi, tests/godot,
tests/tiled): each check passes or prints what failed, and finish() prints
the count and exits non-zero on any failure."""
import sys

failures = []  # what failed, in order
_passes = 0


def check(ok, what):
    global _passes
    if ok:
        _passes += 1
    else:
        failures.append(what)
        print("FAIL", what)


def finish(name):
    print(f"{name}: {_passes} passed, {len(failures)} failed")
    sys.exit(1 if failures else 0)
