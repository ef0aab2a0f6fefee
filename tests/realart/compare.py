#!/usr/bin/env python3
"""Prints, for every tree of the real-art manifests, how far its obstacle's
centre lies from its base (expected_base) under the paper's footprint and
under auto; then, for every object that fills its tile or spans several
(expected_whole_base: its base's left, front and right corners), how far the
obstacle's centre lies from the base's centre and how much of the base's
width the obstacle spans: the evidence for the default in docs/beyond.md.
Usage: python3 tests/realart/compare.py PATH/TO/isolux-cli [CACHE]"""
import json, math, os, shutil, subprocess, sys

cli = sys.argv[1]
cache = sys.argv[2] if len(sys.argv) > 2 else os.environ.get(
    "ISOLUX_REALART_CACHE", os.path.expanduser("~/.cache/isolux-realart"))
here = os.path.dirname(os.path.abspath(__file__))
sets = {"freedroidrpg": "freedroidrpg-data", "lincity-ng": "lincity-ng-data", "widelands": "widelands-data",
        "freeciv": "freeciv-data", "flare": "flare-game"}
trees, bases = [], []
for name, package in sets.items():
    manifest = os.path.join(cache, package, f"isolux-{name}.json")
    shutil.copy(os.path.join(here, name + ".json"), manifest)
    sprites = json.load(open(manifest))["sprites"]
    runs = {}
    for mode in ("paper", "auto"):
        out = subprocess.run([cli, "check-tileset", manifest, "--json", "--footprint", mode],
                             capture_output=True, text=True, check=True).stdout
        runs[mode] = {s["name"]: s for s in json.loads(out)["sprites"]}
    for s in sprites:
        if s["name"] not in runs["auto"]:  # a floor
            continue
        detected = ", ".join(runs["auto"][s["name"]]["detected"]) or "-"
        if "expected_base" in s:
            ex, ey = s["expected_base"]
            def dist(mode):
                c = runs[mode][s["name"]]["obstacle_center"]
                return "none" if c is None else f"{math.hypot(c[0] - ex - 0.5, c[1] - ey - 0.5):.0f}"
            trees.append(f"| {name} | {s['name']} | {dist('paper')} | {dist('auto')} | {detected} |")
        if "expected_whole_base" in s:
            (lx, ly), _, (rx, ry) = s["expected_whole_base"]
            cx, cy = (lx + rx) / 2, (ly + ry) / 2
            def base(mode):
                r = runs[mode][s["name"]]
                c = r["obstacle_center"]
                if c is None:
                    return "none | 0 %"
                return f"{math.hypot(c[0] - cx, c[1] - cy):.0f} | {100 * r['obstacle_rect'][2] / (rx - lx):.0f} %"
            bases.append(f"| {name} | {s['name']} | {base('paper')} | {base('auto')} | {detected} |")
print("| tileset | sprite | paper: px from base | auto: px from base | auto detected |")
print("|---|---|---|---|---|")
print("\n".join(trees))
print()
print("| tileset | sprite | paper: px from the base's centre | paper: width of the base | auto: px from the base's centre | auto: width of the base | auto detected |")
print("|---|---|---|---|---|---|---|")
print("\n".join(bases))
