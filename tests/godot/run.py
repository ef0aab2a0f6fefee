#!/usr/bin/env python3
"""isolux inside Godot 3.2 (Debian's godot3-server, headless, and godot3 under
the test suite's Xvfb), with the add-on in engines/godot/addons/isolux:

1. The importer (tmx_importer.gd) turns isolux's TMX exports of the default
   and showcase scenes and examples/walk's level into Godot scenes, saved as .scn. Node by node, in
   Godot's pixels: each Light2D stands at its scene light's world pixel with
   its colour, energy and a x b area; each LightOccluder2D covers only
   obstacle pixels of `isolux-cli render --layer obstacles`, and all of them
   together cover every obstacle pixel; every overlay is a Sprite; every floor
   cell is in the TileMap; the CanvasModulate is the ambient clarity.
2. The imported level drawn by godot3 with its lights and CanvasModulate off
   matches `isolux-cli render --layer map` over the same world rectangle:
   at most 0.5 % of pixels differ by more than 2/255 (idiff, RGB).
3. IsoluxLighting (the GDNative library) renders the default and showcase
   scenes and an exported TMX inside godot3-server: its light texture and its
   final picture have isolux-cli's bytes.

4. The demo (demo/main.tscn, the installed project's main scene) walks a
   light for a few frames in godot3-server; its last frame has the bytes of
   `isolux-cli render` with that light.

6. Normal maps (export-tiled --normal-maps): every overlay Sprite gets its
   normal map, and godot3 draws a Light2D over them; the share of sprite
   pixels where Godot and isolux's own `solids` shading agree on whether the
   surface faces the light is at least 90 % with the importer's maps (its
   normal_frame "ground") and below 90 % without normal maps; the maps as a
   light over the screen reads them ("screen", green flipped) are measured
   beside them (normal_light.gd).

5. The importer against hostile maps (a sheet declaring two million
   columns, too many, too few and non-numeric CSV values, truncated files,
   data outside a layer, a layer of width 0, oversized maps, gids beyond 32
   bits, lights of area 0 and of areas that are not numbers, height maps
   that are missing, 8-bit, of another size than their sprite, cut short,
   short of rows or with an unknown row filter; one that uses all five of
   PNG's row filters imports): each is
   refused with isolux's reader's message, or imported, and Godot neither
   crashes nor prints a script error (import_refusals.gd).

Everything runs from an install (`cmake --install BUILD_DIR`), as a game
gets it.

Usage: run.py ISOLUX_CLI BUILD_DIR SOURCE_DIR
"""
import json, os, shutil, subprocess, sys, tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "capi"))
from png_rgba import png_rgba  # noqa: E402 (tests/capi/png_rgba.py)

cli, build, src = (os.path.abspath(a) for a in sys.argv[1:4])
tmp = tempfile.mkdtemp(prefix="isolux_godot_")
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from checks import check, failures, finish  # noqa: E402 (tests/checks.py)


def run(args, env=None, timeout=120):
    try:
        p = subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=timeout,
                           env=dict(os.environ, **(env or {})), stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        # A GDScript error leaves Godot waiting: the timeout is the failure.
        print("timed out:", " ".join(map(str, args)))
        return None
    if p.returncode != 0:
        print("command:", " ".join(map(str, args)), "exit", p.returncode, "\n", p.stdout[-3000:], p.stderr[-3000:])
    return p


# The installed Godot project (<prefix>/share/isolux/godot: the add-on with
# its library and default tileset, and the demo), plus the test scripts.
prefix = os.path.join(tmp, "prefix")
p = run(["cmake", "--install", build, "--prefix", prefix])
if not p or p.returncode:
    sys.exit("godot: cmake --install failed")
project = os.path.join(prefix, "share/isolux/godot")
for script in ("import_level.gd", "lighting_bytes.gd", "import_refusals.gd", "normal_light.gd", "view.gd"):
    shutil.copy(os.path.join(src, "tests/godot", script), project)
# No ISOLUX_ASSETS: the library finds the default tileset beside itself.
godot_env = {"HOME": tmp, "ISOLUX_ASSETS": ""}


def godot(binary, script, env):
    return run([binary, "--path", project, "-s", script], dict(godot_env, **env))


def cli_png(args, name):
    out = os.path.join(tmp, name + ".png")
    p = run([cli, "render", *args, "--out", out])
    return png_rgba(out) if p and p.returncode == 0 else None


# ------------------------------------------------------------ 1, 2: import
VIEW = (256, 70, 1024, 768)  # fits the suite's 1280x1024 Xvfb screen
# The default scene with its round lights measured on the ground (a = b):
# each Light2D an ellipse twice as wide as tall on the 128 x 64 tiles.
ground = json.load(open(os.path.join(src, "assets/scenes/default.json")))
ground.setdefault("preset", {}).update({"falloff_space": "ground", "falloff_shape": "euclidean", "edge_fade": True})
ground_path = os.path.join(tmp, "ground.json")
json.dump(ground, open(ground_path, "w"))
for name, scene_path in (("default", os.path.join(src, "assets/scenes/default.json")),
                         ("showcase", os.path.join(src, "assets/scenes/showcase.json")),
                         ("walk", os.path.join(src, "examples/walk/level.json")),
                         ("ground", ground_path)):
    scene = json.load(open(scene_path))
    tmx = os.path.join(tmp, name, "level.tmx")
    os.makedirs(os.path.dirname(tmx))
    p = run([cli, "export-tiled", "--scene", scene_path, "--out", tmx])
    if not p or p.returncode:
        check(False, f"{name}: export-tiled failed")
        continue
    text = open(tmx).read()
    check(text.count('type="occluder"') > 10, f"{name}: obstacles are written as type=\"occluder\"")
    nodes_path = os.path.join(tmp, name + ".nodes.json")
    p = godot("godot3-server", "import_level.gd", {"ISOLUX_TMX": tmx, "ISOLUX_NODES_OUT": nodes_path,
                                                    "ISOLUX_SCENE_OUT": os.path.join(tmp, name + ".scn")})
    if not p or p.returncode or not os.path.exists(nodes_path):
        check(False, f"{name}: the importer failed in godot3-server")
        continue
    print(p.stdout.strip().splitlines()[-1])
    nodes = json.load(open(nodes_path))
    check(os.path.getsize(os.path.join(tmp, name + ".scn")) > 1000, f"{name}: the scene is saved")

    # Lights: at the scene's world pixels, with its colours and areas.
    preset = scene.get("preset", {})
    lights = nodes["lights"]
    check(len(lights) == len(scene["lights"]), f"{name}: {len(lights)} Light2D for {len(scene['lights'])} lights")
    for got, want in zip(lights, scene["lights"]):
        area = [want.get("a", preset.get("area_a", 128)), want.get("b", preset.get("area_b", 128))]
        ok = (abs(got["x"] - want["x"]) < 0.01 and abs(got["y"] - want["y"]) < 0.01 and
              got["color"] == want["color"] and abs(got["energy"] - want["intensity"]) < 1e-6 and got["area"] == area)
        check(ok, f"{name}: Light2D {got} for the scene's {want}")
        # Its drawn half-extents: the a x b box, or on the ground (r = 2) the
        # ellipse of ground distance inside it.
        r = 2.0 if preset.get("falloff_space") == "ground" else 1.0
        drawn = [min(area[0], r * area[1]), min(area[1], area[0] / r)]
        if min(area) > 0:
            check(all(abs(g - w) < 0.01 for g, w in zip(got["drawn"], drawn)),
                  f"{name}: Light2D drawn {got['drawn']} for half-extents {drawn}")
    check(abs(nodes["ambient"] - preset.get("ambient_clarity", 1)) < 1e-3, f"{name}: CanvasModulate {nodes['ambient']}")
    check(len(nodes["sprites"]) == text.count(" gid="), f"{name}: {len(nodes['sprites'])} sprites")
    check(nodes["floors"]["cells"] == scene["width"] * scene["height"], f"{name}: {nodes['floors']['cells']} floor cells")

    # Occluders: exactly the obstacle map's pixels (isolux-cli paints them
    # white over the map; a pixel the map already has white proves nothing).
    span = scene["width"] + scene["height"]
    frame = (-256, -256, span * 64 + 512, span * 32 + 768)  # world pixels around the whole map (128x64 tiles)
    at = ["--view", ",".join(map(str, frame))]
    obstacles = cli_png(["--scene", scene_path, "--layer", "obstacles", *at], name + ".obstacles")
    plain = cli_png(["--scene", scene_path, "--layer", "map", *at], name + ".map")
    if obstacles and plain:
        w, h, px = obstacles
        covered = set()
        for poly in nodes["occluders"]:
            xs, ys = [q[0] for q in poly], [q[1] for q in poly]
            for y in range(int(round(min(ys))), int(round(max(ys)))):
                for x in range(int(round(min(xs))), int(round(max(xs)))):
                    covered.add((x - frame[0], y - frame[1]))
        white = {(i // 4 % w, i // 4 // w) for i in range(0, len(px), 4) if px[i:i + 3] == b"\xff\xff\xff"}
        outside = len(covered - white)
        missed = sum(1 for x, y in white - covered if plain[2][(y * w + x) * 4:(y * w + x) * 4 + 3] != b"\xff\xff\xff")
        print(f"{name}: occluders cover {len(covered)} pixels, the obstacle map {len(white)}: "
              f"{outside} outside it, {missed} missed")
        check(len(white) > 100 and outside == 0 and missed == 0,
              f"{name}: occluders and the obstacle map differ ({outside} outside, {missed} missed)")

    # The level drawn by Godot against isolux's map layer.
    drawn = os.path.join(tmp, name + ".godot.png")
    p = godot("godot3", "import_level.gd", {"ISOLUX_TMX": tmx, "ISOLUX_NODES_OUT": nodes_path,
                                            "ISOLUX_SCENE_OUT": os.path.join(tmp, name + ".scn"),
                                            "ISOLUX_DRAW_OUT": drawn, "ISOLUX_VIEW": ",".join(map(str, VIEW))})
    ours = os.path.join(tmp, name + ".isolux.png")
    q = run([cli, "render", "--scene", scene_path, "--layer", "map", "--view", ",".join(map(str, VIEW)), "--out", ours])
    if not p or p.returncode or not os.path.exists(drawn) or not q or q.returncode:
        check(False, f"{name}: godot3 did not draw the level (needs a display: the suite runs under Xvfb)")
        continue
    for f in (drawn, ours):
        run(["oiiotool", f, "--ch", "R,G,B", "-o", f + ".rgb.png"])
    d = subprocess.run(["idiff", "-v", "-fail", "0.0079", "-warn", "0.0079", "-failpercent", "0.5", drawn + ".rgb.png",
                        ours + ".rgb.png"], capture_output=True, text=True)
    over = [l.strip() for l in d.stdout.splitlines() if "over 0.0079" in l]
    print(f"{name}: Godot's drawing against isolux's map layer: {over[0] if over else d.stdout[-300:]}")
    check(d.returncode in (0, 1), f"{name}: Godot draws the imported level unlike isolux\n{d.stdout[-600:]}")

# ------------------------------------------------------------ 3: GDNative
levels = [("default", os.path.join(src, "assets/scenes/default.json"), "--scene"),
          ("showcase", os.path.join(src, "assets/scenes/showcase.json"), "--scene"),
          ("default TMX", os.path.join(tmp, "default", "level.tmx"), "--map")]
for name, path, flag in levels:
    for layer in ("light", "final"):
        raw = os.path.join(tmp, f"{name}.{layer}.raw".replace(" ", "_"))
        p = godot("godot3-server", "lighting_bytes.gd", {"ISOLUX_LEVEL": path, "ISOLUX_LAYER": layer,
                                                         "ISOLUX_BYTES_OUT": raw})
        want = cli_png([flag, path, "--layer", layer], f"{name}.{layer}.cli".replace(" ", "_"))
        if not p or p.returncode or not os.path.exists(raw) or not want:
            check(False, f"{name}: IsoluxLighting did not render its {layer} layer in godot3-server")
            continue
        got = open(raw, "rb").read()
        same = got == want[2]
        lit = sum(1 for i in range(0, len(got), 4) if any(got[i:i + 3]))
        print(f"{name}: IsoluxLighting's {layer} layer in Godot, {want[0]}x{want[1]}: "
              f"{'the same bytes as' if same else 'NOT the bytes of'} isolux-cli ({lit} lit pixels)")
        check(same and lit > 1000, f"{name}: IsoluxLighting's {layer} layer differs from isolux-cli's")

# ------------------------------------------------------------ 4: the demo
out = os.path.join(tmp, "demo.raw")
p = run(["godot3-server", "--path", project], dict(godot_env, ISOLUX_DEMO_FRAMES="3", ISOLUX_DEMO_OUT=out))
if not p or p.returncode or not os.path.exists(out + ".txt"):
    check(False, "the demo did not run in godot3-server")
else:
    f, lx, ly, vx, vy, vw, vh = map(int, open(out + ".txt").read().split())
    level = os.path.join(project, "demo/level.json")
    area = json.load(open(level))["preset"]["area_a"]
    want = cli_png(["--scene", level, "--view", f"{vx},{vy},{vw},{vh}",
                    "--light", f"{lx},{ly},{area},{area},ffe0b0,h=30"], "demo.cli")
    same = want is not None and open(out, "rb").read() == want[2]
    print(f"demo: frame {f}, the walking light at ({lx}, {ly}): "
          f"{'the same bytes as' if same else 'NOT the bytes of'} isolux-cli")
    check(same, "the demo's frame differs from isolux-cli's")

# ------------------------------------------------------------ 6: normal maps
# One white light 40 px up over the default map, flat mode (no shadows on
# either side, so only the shading differs), no blur.
lit_scene = {"schema_version": 1, "seed": "isolux", "width": 12, "height": 12, "layout": "diamond",
             "preset": {"mode": "flat", "blur_radius": 0, "area_a": 300, "area_b": 300, "falloff_scale": 60,
                        "ambient_clarity": 0.3, "light_height": 40},
             "lights": [{"x": 700, "y": 420, "color": "ffffff", "intensity": 0.5}],
             "camera": {"x": 0, "y": 0, "width": 0, "height": 0}}
normal_dir = os.path.join(tmp, "normals")
os.makedirs(normal_dir)
lit_path = os.path.join(normal_dir, "scene.json")
json.dump(lit_scene, open(lit_path, "w"))
NVIEW = "450,270,500,300"
p = run([cli, "export-tiled", "--scene", lit_path, "--out", os.path.join(normal_dir, "level.tmx"), "--normal-maps"])
shaded = cli_png(["--scene", lit_path, "--layer", "light", "--view", NVIEW, "--sprite-shading", "solids"], "normals.shaded")
flat_light = cli_png(["--scene", lit_path, "--layer", "light", "--view", NVIEW], "normals.flat")
agreement = {}
FRAMES = {"ground": "re-expressed for a light over the ground", "screen": "green flipped"}
for frame in FRAMES:
    prefix = os.path.join(normal_dir, f"{frame}_")
    q = godot("godot3", "normal_light.gd", {"ISOLUX_TMX": os.path.join(normal_dir, "level.tmx"), "ISOLUX_VIEW": NVIEW,
                                            "ISOLUX_OUT_PREFIX": prefix, "ISOLUX_NORMALS": frame})
    if not p or p.returncode or not q or q.returncode or not shaded or not flat_light:
        check(False, "normal maps: the export or godot3's drawing failed (needs a display: the suite runs under Xvfb)")
        break
    said = [l for l in q.stdout.splitlines() if l.startswith("overlays with a normal map")]
    counts = said[0].split(":")[1].split(" of ") if said else ["0", "1"]
    check(int(counts[0]) == int(counts[1]) > 100, f"normal maps: {said}")
    pics = {k: png_rgba(prefix + k + ".png")[2] for k in ("mask", "dark", "normals", "flat")}
    w, h = 500, 300
    agree = {"normals": 0, "flat": 0}
    total = 0
    for i in range(0, w * h * 4, 4):
        if not any(pics["mask"][i:i + 3]):
            continue  # no overlay drawn here (the background is cleared to black)
        lum = {k: sum(pics[k][i:i + 3]) for k in ("dark", "normals", "flat")}
        if lum["flat"] - lum["dark"] < 30 or max(pics["flat"][i:i + 3]) >= 250 or max(pics["normals"][i:i + 3]) >= 250:
            continue  # too little light to tell, or clipped
        if flat_light[2][i] < 20:
            continue
        faces_isolux = shaded[2][i] > 0
        for k in agree:  # the side Godot lights: more than 5 % of its flat light
            agree[k] += faces_isolux == ((lum[k] - lum["dark"]) > 0.05 * (lum["flat"] - lum["dark"]))
        total += 1
    agreement[frame] = agree["normals"] / max(total, 1)
    agreement["none"] = agree["flat"] / max(total, 1)
    print(f"normal maps {FRAMES[frame]}: Godot and isolux agree on which side faces the light on "
          f"{agreement[frame]:.1%} of {total} sprite pixels (without normal maps: {agreement['none']:.1%})")
if len(agreement) == 3:
    check(total > 10000, f"normal maps: only {total} sprite pixels measured")
    check(agreement["ground"] >= 0.90 > agreement["none"],
          f"normal maps: the importer's maps agree on {agreement['ground']:.1%}, none on {agreement['none']:.1%}")

# ------------------------------------------------------------ 5: hostile maps
# The importer keeps isolux's reader's limits and messages; none crashes Godot.
import struct, zlib  # noqa: E402
def png(w, h):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
    rows = b"".join(b"\0" + b"\x80" * (w * 4) for _ in range(h))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))
hostile = os.path.join(tmp, "hostile")
os.makedirs(hostile)
open(os.path.join(hostile, "sheet.png"), "wb").write(png(64, 64))
MAP = '<map orientation="isometric" width="{w}" height="{h}" tilewidth="64" tileheight="32">'
SHEET = '<tileset firstgid="1" name="s" tilewidth="{tw}" tileheight="32" columns="{cols}"><image source="sheet.png" width="64" height="64"/></tileset>'
GOOD_SHEET = SHEET.format(tw=32, cols=2)
def layer(data, w=2, h=2):
    return f'<layer name="ground" width="{w}" height="{h}"><data encoding="csv">{data}</data></layer>'
def lights(*props):
    objs = "".join(f'<object id="{i + 1}" x="10" y="10"><properties><property name="a" value="{a}"/></properties><point/></object>'
                   for i, a in enumerate(props))
    return f'<objectgroup name="lights">{objs}</objectgroup>'
good = MAP.format(w=2, h=2) + GOOD_SHEET + layer("1,2,3,4")
# A tile with a normal map and a height map (16-bit grey, decoded by the
# importer itself): each row's filter byte cycles through PNG's five, or is
# `filt` for every row; `rows` of the `h` are written.
def png16(w, h, filt=None, rows=None):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
    raw = b"".join(bytes([y % 5 if filt is None else filt]) + bytes((x * 7 + y) % 256 for x in range(w * 2))
                   for y in range(h if rows is None else rows))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 16, 0, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
for name, data in {"h_filters.png": png16(64, 64), "h_small.png": png16(32, 32), "h_cut.png": png16(64, 64)[:100],
                   "h_filter7.png": png16(64, 64, filt=7), "h_rows.png": png16(64, 64, rows=10)}.items():
    open(os.path.join(hostile, name), "wb").write(data)
def relief(height_map):
    return (MAP.format(w=2, h=2) + GOOD_SHEET + '<tileset firstgid="5" name="o" tilewidth="64" tileheight="64" tilecount="1" '
            'columns="0"><tile id="0"><properties><property name="normal_map" type="file" value="sheet.png"/>'
            f'<property name="isolux_height_map" type="file" value="{height_map}"/></properties>'
            '<image source="sheet.png" width="64" height="64"/></tile></tileset>' + layer("1,2,3,4") +
            '<objectgroup name="o"><object id="1" gid="5" x="10" y="10" width="64" height="64"/></objectgroup>' +
            lights("0", "64") + "</map>")
cases = {
    "two_million_columns": (MAP.format(w=2, h=2) + SHEET.format(tw=32, cols=2000000) + layer("1,1,1,1") + "</map>", 'columns="2000000"'),
    "tile_width_zero": (MAP.format(w=2, h=2) + SHEET.format(tw=0, cols=2) + layer("1,1,1,1") + "</map>", 'tilewidth="0"'),
    "csv_too_many": (MAP.format(w=2, h=2) + GOOD_SHEET + layer("1,1,1,1,1") + "</map>", "holds more than 4 tiles"),
    "csv_too_few": (MAP.format(w=2, h=2) + GOOD_SHEET + layer("1,1,1") + "</map>", "holds 3 tiles"),
    "csv_not_numbers": (MAP.format(w=2, h=2) + GOOD_SHEET + layer("1,x,1,1") + "</map>", "not a gid"),
    "csv_gid_beyond_32_bits": (MAP.format(w=2, h=2) + GOOD_SHEET + layer("1,99999999999,1,1") + "</map>", "not a gid"),
    "truncated": ((good + "</map>")[:-40], "ends inside"),
    "truncated_in_a_tag": ((good + "</map>")[:-9], "ends inside"),
    "data_outside_a_layer": (MAP.format(w=2, h=2) + GOOD_SHEET + '<data encoding="csv">1,1,1,1</data></map>', "outside a <layer>"),
    "layer_width_zero": (MAP.format(w=2, h=2) + GOOD_SHEET + layer("", w=0) + "</map>", 'width="0"'),
    "map_too_wide": (MAP.format(w=5000, h=2) + GOOD_SHEET + "</map>", 'width="5000"'),
    "map_too_many_tiles": (MAP.format(w=4096, h=300) + GOOD_SHEET + "</map>", "1048576 tiles"),
    "light_area_not_a_number": (good + lights("wide") + "</map>", 'property a="wide"'),
    "light_area_beyond": (good + lights("99999") + "</map>", 'property a="99999"'),
    "object_gid_beyond_32_bits": (good + '<objectgroup name="o"><object id="1" gid="4294967296" x="1" y="1"/></objectgroup></map>', 'gid="4294967296"'),
    "object_far": (good + '<objectgroup name="o"><object id="1" gid="1" x="1e12" y="1"/></objectgroup></map>', 'x="1e12"'),
    "light_area_zero": (good + lights("0", "64") + "</map>", ""),
    "height_map_every_filter": (relief("h_filters.png"), ""),
    "height_map_8_bit": (relief("sheet.png"), 'sheet.png" is not 16-bit grey'),
    "height_map_missing": (relief("none.png"), 'none.png" cannot be read'),
    "height_map_other_size": (relief("h_small.png"), "is 32x32, its sprite 64x64"),
    "height_map_cut": (relief("h_cut.png"), "ends inside a chunk"),
    "height_map_bad_filter": (relief("h_filter7.png"), "has a row filter 7"),
    "height_map_few_rows": (relief("h_rows.png"), "holds fewer rows than its height"),
}
entries = []
for name, (text, want) in cases.items():
    path = os.path.join(hostile, name + ".tmx")
    open(path, "w").write('<?xml version="1.0"?>' + text)
    entries.append({"tmx": path, "want": want, "lights": 2})
json.dump(entries, open(os.path.join(hostile, "cases.json"), "w"))
p = godot("godot3-server", "import_refusals.gd", {"ISOLUX_CASES": os.path.join(hostile, "cases.json")})
if p:
    print("\n".join(l for l in p.stdout.splitlines() if l.startswith(("ok ", "FAIL ", "refusals"))))
check(p is not None and p.returncode == 0 and "SCRIPT ERROR" not in p.stderr,
      "the importer's refusals of hostile maps\n" + (p.stderr[-2000:] if p else "timed out"))

finish("godot")
