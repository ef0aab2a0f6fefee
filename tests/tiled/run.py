#!/usr/bin/env python3
"""Tiled maps out and in, judged by Tiled's own renderer (tmxrasterizer).

1. Scenes exported with `isolux-cli export-tiled` (diamond with edits, and
   staggered; finite, and infinite with --infinite 4) are drawn by tmxrasterizer; isolux-cli's `--layer map` of the
   same scene over the same pixels must match: at most 0.5 % of pixels
   differing by more than 2/255 (idiff).
2. Exported then imported (`render --map`): the same `--layer final` bytes.
3. Maps written here by hand (every encoding and compression, external and
   embedded tilesets, sheets and image collections, tile offsets, flips, tile
   objects, a group with an offset; isometric and staggered) and Tiled's own
   example maps (isometric, and staggered infinite): isolux's `--layer map`
   against tmxrasterizer's picture. Infinite versions of the hand maps
   (chunks from a negative tile) draw the finite maps' bytes.
4. Bad maps: a clear error naming the file and the element, exit 2.

Usage: run.py ISOLUX_CLI SOURCE_DIR
"""
import base64, gzip, os, re, shutil, struct, subprocess, sys, tempfile, zlib

cli, src = sys.argv[1], sys.argv[2]
tmp = tempfile.mkdtemp(prefix="isolux_tiled_")
env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from checks import check, failures, finish  # noqa: E402 (tests/checks.py)


def run(*args, expect=0):
    p = subprocess.run([str(a) for a in args], capture_output=True, text=True, env=env, timeout=120)
    if p.returncode != expect:
        print("command:", " ".join(map(str, args)), "exit", p.returncode, "\n", p.stdout, p.stderr)
    return p


def png_size(path):
    with open(path, "rb") as f:
        return struct.unpack(">II", f.read(24)[16:24])


def judge(tmx, what, scene=None):
    """tmxrasterizer's picture of `tmx` against isolux-cli's --layer map of the same pixels."""
    tiled = os.path.join(tmp, what + ".tiled.png")
    p = run("tmxrasterizer", "--hide-layer", "lights", "--hide-layer", "obstacles", tmx, tiled)
    if p.returncode != 0 or not os.path.exists(tiled):
        check(False, what + ": tmxrasterizer failed: " + p.stderr)
        return
    w, h = png_size(tiled)
    # The world pixel of Tiled's (0, 0): printed by render --map.
    p = run(cli, "render", "--map", tmx, "--layer", "map", "--out", os.path.join(tmp, "probe.png"))
    m = re.search(r"world \((-?\d+), (-?\d+)\)", p.stdout)
    if not m:
        check(False, what + ": no origin in " + p.stdout + p.stderr)
        return
    ox, oy = int(m.group(1)), int(m.group(2))
    # tmxrasterizer widens its picture by the layers' offsets (left and top
    # by the most negative): its pixel (0, 0) is then Tiled's (-left, -top).
    text = open(tmx).read()
    left = max([0] + [-float(v) for v in re.findall(r'offsetx="(-?[0-9.]+)"', text)])
    top = max([0] + [-float(v) for v in re.findall(r'offsety="(-?[0-9.]+)"', text)])
    ox, oy = ox - int(left), oy - int(top)
    ours = os.path.join(tmp, what + ".isolux.png")
    args = ["render", "--layer", "map", "--view", f"{ox},{oy},{w},{h}", "--out", ours]
    run(cli, *(args + (["--scene", scene] if scene else ["--map", tmx])))
    d = subprocess.run(["idiff", "-fail", "0.0079", "-warn", "0.0079", "-failpercent", "0.5", tiled, ours],
                       capture_output=True, text=True)
    check(d.returncode in (0, 1), f"{what}: isolux and tmxrasterizer differ\n{d.stdout[-600:]}")
    over = re.search(r"(\d+) pixels \(([0-9.]+)%\) over", d.stdout)
    print(f"{what}: {w}x{h}, {over.group(1) if over else 0} pixels over 2/255")


# ---------------------------------------------------------------- 1, 2: export
scenes = {
    "diamond": {"schema_version": 2, "seed": "tiled", "width": 10, "height": 8, "layout": "diamond",
                "lights": [{"x": 600, "y": 300, "color": "ffd8a0"}, {"x": 900, "y": 420, "a": 90, "b": 60, "height": 50}],
                "edits": [{"tile": [0, 0], "overlays": ["pine", "pine", "oak"]}, {"tile": [3, 3], "floor": "water", "overlays": []},
                          {"tile": [4, 3], "floor": "water"}, {"tile": [9, 7], "overlays": ["wall"]}]},
    "staggered": {"schema_version": 2, "seed": "tiled", "width": 6, "height": 12, "layout": "staggered",
                  "lights": [{"x": 400, "y": 250}], "edits": [{"tile": [2, 5], "overlays": ["oak", "bush"]}]},
}
for name, scene in scenes.items():
    sp = os.path.join(tmp, name + ".json")
    with open(sp, "w") as f:
        import json
        json.dump(scene, f)
    tmx = os.path.join(tmp, "out_" + name, name + ".tmx")
    os.makedirs(os.path.dirname(tmx), exist_ok=True)  # export-tiled writes into a folder that exists
    p = run(cli, "export-tiled", "--scene", sp, "--out", tmx)
    check(p.returncode == 0 and os.path.exists(tmx), name + ": export-tiled")
    text = open(tmx).read()
    check('name="lights"' in text and text.count("<point") == len(scene["lights"]), name + ": a lights layer with each light")
    check('name="obstacles"' in text and "<polygon" in text, name + ": an obstacles layer of polygons")
    check('name="delta_y"' in text and 'name="ambient_clarity"' in text, name + ": the preset as map properties")
    check(os.path.exists(os.path.join(tmp, "out_" + name, name + "_overlays.tsx")), name + ": external TSX")
    judge(tmx, "export_" + name, scene=sp)
    a, b = os.path.join(tmp, name + ".scene.png"), os.path.join(tmp, name + ".map.png")
    run(cli, "render", "--scene", sp, "--out", a)
    run(cli, "render", "--map", tmx, "--out", b)
    check(open(a, "rb").read() == open(b, "rb").read(), name + ": exported and imported, --layer final differs")
    # As an infinite map (chunks of 4 tiles, the last ones cut at the map's
    # edge): tmxrasterizer draws it as isolux does, and it reads back to the
    # same lit frame.
    inf = os.path.join(tmp, "inf_" + name, name + ".tmx")
    os.makedirs(os.path.dirname(inf), exist_ok=True)  # export-tiled writes into a folder that exists
    p = run(cli, "export-tiled", "--scene", sp, "--out", inf, "--infinite", "4")
    text = open(inf).read() if os.path.exists(inf) else ""
    check(p.returncode == 0 and 'infinite="1"' in text and text.count("<chunk") >= 4, name + ": export-tiled --infinite")
    judge(inf, "export_infinite_" + name, scene=sp)
    c = os.path.join(tmp, name + ".inf.png")
    run(cli, "render", "--map", inf, "--out", c)
    check(os.path.exists(c) and open(a, "rb").read() == open(c, "rb").read(),
          name + ": exported as an infinite map and imported, --layer final differs")

# An endless world's region: the window of chunks a view far out needs, as an
# infinite map; tmxrasterizer draws it as isolux reads it, and it reads back
# to the endless render's pixels of that view.
endless = os.path.join(tmp, "endless.json")
X, Y = 64000000000, 32000000000
with open(endless, "w") as f:
    json.dump({"schema_version": 2, "seed": "tiled", "width": "endless", "height": "endless",
               "lights": [{"x": X + 300, "y": Y + 200, "color": "ffd8a0"}]}, f)
etmx = os.path.join(tmp, "out_endless", "endless.tmx")
os.makedirs(os.path.dirname(etmx), exist_ok=True)  # export-tiled writes into a folder that exists
p = run(cli, "export-tiled", "--scene", endless, "--view", f"{X},{Y},600,400", "--infinite", "16", "--out", etmx)
text = open(etmx).read() if os.path.exists(etmx) else ""
check(p.returncode == 0 and 'infinite="1"' in text and text.count("<chunk") >= 16, "endless: export-tiled --view --infinite")
judge(etmx, "export_endless")
m = re.search(r"world \((-?\d+), (-?\d+)\).*the world's \((-?\d+) \+ x, (-?\d+) \+ y\)", p.stdout)
q = run(cli, "render", "--map", etmx, "--layer", "map", "--out", os.path.join(tmp, "probe.png"))
n = re.search(r"world \((-?\d+), (-?\d+)\)", q.stdout)
check(bool(m and n), "endless: the export and the import say where Tiled's (0, 0) is\n" + p.stdout + q.stdout)
if m and n:
    ox, oy, wx, wy = (int(v) for v in m.groups())
    lx, ly = int(n.group(1)), int(n.group(2))
    vx, vy = X - wx - ox + lx, Y - wy - oy + ly  # the endless view's pixels in the imported map
    a, b = os.path.join(tmp, "endless.render.png"), os.path.join(tmp, "endless.map.png")
    run(cli, "render", "--scene", endless, "--view", f"{X},{Y},600,400", "--out", a)
    run(cli, "render", "--map", etmx, "--view", f"{vx},{vy},600,400", "--out", b)
    check(os.path.exists(a) and os.path.exists(b) and open(a, "rb").read() == open(b, "rb").read(),
          "endless: the exported region read back differs from the endless render of its view")

# ---------------------------------------------------------------- 3: maps by hand
art = os.path.join(src, "assets", "default")
hand = os.path.join(tmp, "hand")
os.makedirs(hand)
for n in ["grass", "water", "sand", "oak", "pine", "rock"]:
    shutil.copy(os.path.join(art, n + ".png"), hand)
# A sheet of two floors (128x128 each, 2 px spacing) through oiiotool.
subprocess.run(["oiiotool", os.path.join(hand, "grass.png"), os.path.join(hand, "sand.png"), "--mosaic:pad=2", "2x1",
                "-o", os.path.join(hand, "sheet.png")], check=True, capture_output=True)
sw, sh = png_size(os.path.join(hand, "sheet.png"))

collection = """<?xml version="1.0" encoding="UTF-8"?>
<tileset version="1.8" name="objects" tilewidth="128" tileheight="128" tilecount="3" columns="0">
 <tileoffset x="0" y="32"/>
 <tile id="0"><image width="128" height="128" source="oak.png"/></tile>
 <tile id="1"><image width="128" height="128" source="pine.png"/></tile>
 <tile id="2"><image width="128" height="128" source="rock.png"/></tile>
</tileset>
"""
open(os.path.join(hand, "objects.tsx"), "w").write(collection)
W, H = 6, 5
F1, F2, WATER = 1, 2, 3  # sheet tiles 0 and 1, and the water tile of an embedded collection
OAK, PINE, ROCK = 11, 12, 13
floors = [[F1 if (x + y) % 3 else F2 for x in range(W)] for y in range(H)]
floors[2][2] = WATER
overlay = [[0] * W for _ in range(H)]
overlay[1][1] = OAK
overlay[3][4] = PINE | 0x80000000  # flipped horizontally
overlay[0][5] = ROCK | 0x40000000  # flipped vertically


def data(gids, encoding):
    flat = [g for row in gids for g in row]
    if encoding == "csv":
        return '<data encoding="csv">\n' + ",".join(map(str, flat)) + "\n</data>"
    raw = b"".join(struct.pack("<I", g) for g in flat)
    comp = ""
    if encoding == "zlib":
        raw, comp = zlib.compress(raw), ' compression="zlib"'
    elif encoding == "gzip":
        raw, comp = gzip.compress(raw), ' compression="gzip"'
    elif encoding == "zstd":
        raw = subprocess.run(["zstd", "-q", "-c"], input=raw, capture_output=True, check=True).stdout
        comp = ' compression="zstd"'
    return f'<data encoding="base64"{comp}>\n' + base64.b64encode(raw).decode() + "\n</data>"


def hand_map(orientation, encoding, extra=""):
    stagger = ' staggeraxis="y" staggerindex="odd"' if orientation == "staggered" else ""
    return f"""<?xml version="1.0" encoding="UTF-8"?>
<map version="1.8" orientation="{orientation}" renderorder="right-down" width="{W}" height="{H}" tilewidth="128" tileheight="64" infinite="0"{stagger}>
 <tileset firstgid="1" name="floors" tilewidth="128" tileheight="128" spacing="2" tilecount="2" columns="2">
  <tileoffset x="0" y="64"/>
  <image source="sheet.png" width="{sw}" height="{sh}"/>
 </tileset>
 <tileset firstgid="3" name="water" tilewidth="128" tileheight="128" tilecount="1" columns="0">
  <tileoffset x="0" y="64"/>
  <tile id="0"><image width="128" height="128" source="water.png"/></tile>
 </tileset>
 <tileset firstgid="11" source="objects.tsx"/>
 <layer id="1" name="ground" width="{W}" height="{H}">{data(floors, encoding)}</layer>
 <layer id="2" name="trees" width="{W}" height="{H}">{data(overlay, encoding)}</layer>
 <group id="3" name="group" offsetx="6" offsety="-4">
  <objectgroup id="4" name="things">
   <object id="1" gid="{OAK}" x="200" y="180" width="128" height="128"/>
   <object id="2" gid="{ROCK}" x="260" y="120" width="128" height="128"/>
  </objectgroup>
 </group>
 {extra}
</map>
"""


for orientation in ["isometric", "staggered"]:
    for encoding in ["csv", "base64", "zlib", "gzip", "zstd"]:
        if orientation == "staggered" and encoding not in ("csv", "zstd"):
            continue
        tmx = os.path.join(hand, f"{orientation}_{encoding}.tmx")
        open(tmx, "w").write(hand_map(orientation, encoding))
        judge(tmx, f"hand_{orientation}_{encoding}")

# Infinite maps: chunked layers (4x4 chunks whose first tile is Tiled's
# (-3, -5), or (-3, -6) on a staggered map, whose rows' shift follows their
# parity) hold the same tiles as the finite map, so isolux draws the same
# bytes (its world starts at what the sprites cover).
def chunked(gids, encoding, x0, y0, size=4):
    cells = {(x0 + x, y0 + y): g for y, row in enumerate(gids) for x, g in enumerate(row)}
    cx0, cy0 = (x0 // size) * size, (y0 // size) * size
    out = []
    for cy in range(cy0, y0 + len(gids), size):
        for cx in range(cx0, x0 + len(gids[0]), size):
            part = [[cells.get((cx + i, cy + j), 0) for i in range(size)] for j in range(size)]
            body = data(part, encoding)
            body = body[body.index(">") + 1:body.rindex("<")]
            out.append(f'<chunk x="{cx}" y="{cy}" width="{size}" height="{size}">{body}</chunk>')
    head = data([[0]], encoding)
    return head[:head.index(">") + 1] + "".join(out) + "</data>"


for orientation in ["isometric", "staggered"]:
    for encoding in ["csv", "zlib"]:
        finite = hand_map(orientation, encoding)
        finite = finite[:finite.index(" <group")] + finite[finite.index(" </group>") + len(" </group>"):]
        infinite = finite.replace('infinite="0"', 'infinite="1"')
        y0 = -6 if orientation == "staggered" else -5
        infinite = infinite.replace(data(floors, encoding), chunked(floors, encoding, -3, y0))
        infinite = infinite.replace(data(overlay, encoding), chunked(overlay, encoding, -3, y0))
        pair = []
        for kind, text in (("finite", finite), ("infinite", infinite)):
            path = os.path.join(hand, f"{kind}_{orientation}_{encoding}.tmx")
            open(path, "w").write(text)
            out = os.path.join(tmp, f"{kind}_{orientation}_{encoding}.png")
            p = run(cli, "render", "--map", path, "--layer", "map", "--out", out)
            pair.append(open(out, "rb").read() if p.returncode == 0 and os.path.exists(out) else None)
        check(pair[0] is not None and pair[0] == pair[1],
              f"infinite {orientation} {encoding}: the chunked map does not draw the finite one's bytes")

# Lights in a hand-written map light it.
lit = os.path.join(hand, "lit.tmx")
open(lit, "w").write(hand_map("isometric", "csv", """<objectgroup id="9" name="lights">
  <object id="9" name="lamp" x="128" y="128"><properties><property name="color" type="color" value="#ffffc080"/>
   <property name="a" type="int" value="100"/><property name="b" type="int" value="80"/></properties><point/></object>
 </objectgroup>"""))
p = run(cli, "render", "--map", lit, "--out", os.path.join(tmp, "lit.png"))
check(p.returncode == 0 and "1 lights" in p.stdout, "a hand-written lights layer is read: " + p.stdout)
dark = os.path.join(tmp, "dark.png")
run(cli, "render", "--map", os.path.join(hand, "isometric_csv.tmx"), "--out", dark)
check(open(dark, "rb").read() != open(os.path.join(tmp, "lit.png"), "rb").read(), "the light changes the render")

# Tiled's own example map (made by Tiled's authors, shipped in Debian's tiled package).
example = "/usr/share/doc/tiled/examples/isometric_grass_and_water.tmx"
check(os.path.exists(example), "Tiled's example map is installed (the tiled package)")
if os.path.exists(example):
    ex = os.path.join(tmp, "example")
    os.makedirs(ex)
    for f in ["isometric_grass_and_water.tmx", "isometric_grass_and_water.png"]:
        shutil.copy(os.path.join(os.path.dirname(example), f), ex)
    judge(os.path.join(ex, "isometric_grass_and_water.tmx"), "tiled_example_isometric")

# Tiled's own infinite staggered example (chunks, base64 with zlib).
stag = "/usr/share/doc/tiled/examples/isometric_staggered_grass_and_water.tmx.gz"
check(os.path.exists(stag), "Tiled's infinite staggered example is installed (the tiled package)")
if os.path.exists(stag):
    ex = os.path.join(tmp, "example_staggered")
    os.makedirs(ex, exist_ok=True)
    shutil.copy("/usr/share/doc/tiled/examples/isometric_grass_and_water.png", ex)
    open(os.path.join(ex, "staggered.tmx"), "wb").write(gzip.open(stag).read())
    judge(os.path.join(ex, "staggered.tmx"), "tiled_example_staggered_infinite")

# Tiled's own orthogonal example is refused by name.
desert = "/usr/share/doc/tiled/examples/desert.tmx"
if os.path.exists(desert):
    p = run(cli, "render", "--map", desert, "--out", os.path.join(tmp, "desert.png"), expect=2)
    check(p.returncode == 2 and "desert.tmx" in p.stderr and "orthogonal" in p.stderr,
          "an orthogonal map is refused with a clear message: " + p.stderr)

# ---------------------------------------------------------------- 4: bad maps
good = hand_map("isometric", "csv")
bomb = base64.b64encode(zlib.compress(b"\0" * (64 << 20), 9)).decode()
bad = {
    "orthogonal": (good.replace('orientation="isometric"', 'orientation="orthogonal"'), "orthogonal"),
    "missing_tsx": (good.replace("objects.tsx", "missing.tsx"), "missing.tsx"),
    "unknown_encoding": (good.replace('encoding="csv"', 'encoding="base32"', 1), "base32"),
    "gid_beyond": (good.replace(f"{F1},", "999,", 1), "beyond the tilesets"),
    "wrong_size": (good.replace(f'name="ground" width="{W}"', f'name="ground" width="{W + 1}"'), "ground"),
    "short_data": (good.replace(f"{F1},{F1},", "", 1), "holds"),
    "bomb": (good.replace(data(floors, "csv"), f'<data encoding="base64" compression="zlib">{bomb}</data>', 1), "bomb"),
    "malformed": (good[: len(good) // 2], "malformed XML"),
    "infinite_without_chunks": (good.replace('infinite="0"', 'infinite="1"'), "no chunks"),
    "chunks_in_a_finite_map": (good.replace(data(floors, "csv"), chunked(floors, "csv", 0, 0), 1), "not infinite"),
}
for name, (text, needle) in bad.items():
    path = os.path.join(hand, "bad_" + name + ".tmx")
    open(path, "w").write(text)
    p = run(cli, "render", "--map", path, "--out", os.path.join(tmp, "bad.png"), expect=2)
    msg = p.stderr
    check(p.returncode == 2 and "bad_" + name in msg or (name == "missing_tsx" and "missing.tsx" in msg),
          f"bad map {name}: exit {p.returncode}, {msg.strip()}")
    check(needle in msg, f"bad map {name}: the message should say '{needle}': {msg.strip()}")

if not failures: shutil.rmtree(tmp, ignore_errors=True)
else: print("kept", tmp)
finish("tiled")
