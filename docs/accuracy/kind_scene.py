#!/usr/bin/env python3
"""Writes the town scene (assets/scenes/town.json) with one object kind alone:
every tile's overlays cleared, then KIND on every tile whose column plus row
is a multiple of 3, but for the tiles the town scene keeps clear under its
lights (a lamp inside a hut lights nothing); the seed's floors, the scene's
settings, lights and camera kept. Usage: kind_scene.py KIND OUT.json"""
import json, os, sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
kind, out = sys.argv[1], sys.argv[2]
scene = json.load(open(os.path.join(ROOT, "assets", "scenes", "town.json")))
scene["tileset"] = os.path.relpath(os.path.join(ROOT, "assets", "town", "tileset.json"), os.path.dirname(os.path.abspath(out)))
clear = {tuple(e["tile"]) for e in scene["edits"] if not e["overlays"]}
scene["edits"] = [{"tile": [c, r], "overlays": [kind] if (c + r) % 3 == 0 and (c, r) not in clear else []}
                  for r in range(scene["height"]) for c in range(scene["width"])]
with open(out, "w") as f:
    json.dump(scene, f, indent=2)
    f.write("\n")
