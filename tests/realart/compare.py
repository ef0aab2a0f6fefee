#!/usr/bin/env python3
"""Prints, for every tree of the real-art manifests, how far its obstacle's
centre lies from its base (expected_base) under the paper's footprint and
under auto: the evidence for the default in docs/method.md.
Usage: python3 tests/realart/compare.py PATH/TO/isolux-cli [CACHE]"""
import json, math, os, shutil, subprocess, sys

cli = sys.argv[1]
cache = sys.argv[2] if len(sys.argv) > 2 else os.environ.get(
    "ISOLUX_REALART_CACHE", os.path.expanduser("~/.cache/isolux-realart"))
here = os.path.dirname(os.path.abspath(__file__))
sets = {"freedroidrpg": "freedroidrpg-data", "lincity-ng": "lincity-ng-data", "widelands": "widelands-data"}
print("| tileset | sprite | paper: px from base | auto: px from base | auto detected |")
print("|---|---|---|---|---|")
for name, package in sets.items():
    manifest = os.path.join(cache, package, f"isolux-{name}.json")
    shutil.copy(os.path.join(here, name + ".json"), manifest)
    expected = {s["name"]: s["expected_base"] for s in json.load(open(manifest))["sprites"] if "expected_base" in s}
    runs = {}
    for mode in ("paper", "auto"):
        out = subprocess.run([cli, "check-tileset", manifest, "--json", "--footprint", mode],
                             capture_output=True, text=True, check=True).stdout
        runs[mode] = {s["name"]: s for s in json.loads(out)["sprites"]}
    for sprite, (ex, ey) in expected.items():
        def dist(mode):
            c = runs[mode][sprite]["obstacle_center"]
            return "none" if c is None else f"{math.hypot(c[0] - ex - 0.5, c[1] - ey - 0.5):.0f}"
        detected = ", ".join(runs["auto"][sprite]["detected"]) or "-"
        print(f"| {name} | {sprite} | {dist('paper')} | {dist('auto')} | {detected} |")
