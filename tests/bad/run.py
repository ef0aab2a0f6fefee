#!/usr/bin/env python3
"""The bad-input corpus: named hostile or broken inputs run through isolux-cli,
each with its expected exit code and a fragment of the expected one-line
message. Every case must end in a clean refusal (exit 2, one line naming the
file or field) or a correct result (exit 0), within 10 s and 1 GB, and never
crash, hang or print a sanitizer report.
Usage: run.py PATH/TO/isolux-cli SOURCE_DIR [--instrumented] [--only TEXT] [--times] [--jobs N]
(--only: the cases whose names hold TEXT; --times: each case's seconds and peak memory;
--jobs: N cases at once)"""
import json, os, resource, shutil, struct, subprocess, sys, tempfile, time, zlib

cli, src = sys.argv[1], sys.argv[2]
if os.sep in cli:
    cli = os.path.abspath(cli)  # some cases run in a folder of their own
tmp = tempfile.mkdtemp(prefix="isolux_bad_")
T = lambda *p: os.path.join(tmp, *p)
LIMIT_S, LIMIT_MB = 10.0, 1024
if "--instrumented" in sys.argv[3:]:
    # AddressSanitizer's shadow memory and checks: the same cases, budgets for an instrumented binary.
    LIMIT_S, LIMIT_MB = 60.0, 4096
cases = []  # (name, args, want_exit, fragment, max_lines, cwd)


def case(name, args, want, fragment="", max_lines=None, cwd=None):
    cases.append((name, args, want, fragment, max_lines, cwd))


def write(name, data):
    path = T(name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())
    return path


def png(width, height, rows=None, depth=8, colour=6):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
    ihdr = struct.pack(">IIBBBBB", width, height, depth, colour, 0, 0, 0)
    if rows is None:
        rows = b"".join(b"\0" + b"\x80" * (width * 4) for _ in range(height))
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")


R = ["render", "--size", "3x3", "--out", T("out.png")]

# 1. Every parameter flag beyond its range, and not a number at all. Under
# the sanitizers, the first parameter of each type only: every flag's value
# goes through the same table-driven check (params.cpp), and each case costs
# an instrumented process's start (about 0.7 s).
rows = subprocess.run([cli, "params"], capture_output=True, text=True, check=True).stdout.strip().splitlines()
keys = rows[0].split("\t")
types_seen = set()
for line in rows[1:]:
    r = dict(zip(keys, line.split("\t")))
    if "--instrumented" in sys.argv[3:] and r["type"] in types_seen:
        continue
    types_seen.add(r["type"])
    if r["type"] in ("integer", "real"):
        lo = float(r["min"].split()[0])
        hi = float(r["max"])
        for label, value in (("below", str(int(lo) - 1) if r["type"] == "integer" else repr(lo - 1)),
                             ("above", str(int(hi) + 1) if r["type"] == "integer" else repr(hi * 2 + 1)),
                             ("text", "abc"), ("nan", "nan"), ("huge", "1e999")):
            case(f"flag_{r['name']}_{label}", R + [r["flag"], value], 2, r["name"])
    elif r["type"] == "choice":
        case(f"flag_{r['name']}_unknown", R + [r["flag"], "no_such_choice"], 2, r["name"])

# 2. Other flags.
for name, args, frag in [
    ("size_zero", ["render", "--size", "0x5"], "--size"),
    ("size_huge", ["render", "--size", "2000x2000"], "--size"),
    ("size_side_beyond", ["render", "--size", "4097x2"], "4096"),
    ("size_tiles_beyond", ["render", "--size", "4096x257"], "1048576 tiles"),
    ("size_text", ["render", "--size", "axb"], "--size"),
    ("size_overflow", ["render", "--size", "99999999999999999999x2"], "--size"),
    ("view_huge", ["render", "--size", "3x3", "--view", "0,0,65536,65536"], "megapixel"),
    ("view_far", ["render", "--size", "3x3", "--view", "1000000000000,0,10,10"], "--view"),
    ("light_text", ["render", "--size", "3x3", "--light", "a,b"], "--light"),
    ("light_far", ["render", "--size", "3x3", "--light", "1e18,0"], "--light"),
    ("endless_view_far", ["render", "--size", "endless", "--view", "200000000000000,0,10,10"], "beyond"),
    ("endless_no_view", ["render", "--size", "endless"], "--view"),
    ("endless_view_huge", ["render", "--size", "endless", "--view", "0,0,20000,13500"], "megapixel"),
    ("endless_view_square_huge", ["render", "--size", "endless", "--view", "-5,-5,65536,65536"], "megapixel"),
    ("light_colour", ["render", "--size", "3x3", "--light", "1,2,3,4,zzzzzz"], "colour"),
    ("light_height_text", ["render", "--size", "3x3", "--light", "1,2,h=tall"], "light_height"),
    ("area_negative", ["render", "--size", "3x3", "--area", "-1,5"], "area_a"),
    ("area_one_number", ["render", "--size", "3x3", "--area", "5"], "--area"),
    ("frames_zero", ["render", "--size", "3x3", "--frames", "0"], "frames"),
    ("layer_unknown", ["render", "--size", "3x3", "--layer", "heat"], "layer"),
    ("reference_unknown", ["render", "--size", "3x3", "--layer", "truth", "--reference", "x"], "reference"),
    ("camera_step_text", ["render", "--size", "3x3", "--frames", "2", "--camera-step", "x"], "--camera-step"),
    ("huge_work", ["render", "--size", "3x3", "--light", "50,50", "--area", "4096,4096", "--rays", "every_pixel"], "allow-huge"),
    ("layout_unknown", ["render", "--size", "3x3", "--layout", "hex"], "layout"),
    ("preset_unknown", ["render", "--size", "3x3", "--preset", "brilliant"], "brilliant"),
]:
    case(name, args + ["--out", T("out.png")], 2, frag)
case("out_folder", ["render", "--size", "3x3", "--out", tmp], 2, "folder")
case("out_extension", ["render", "--size", "3x3", "--out", T("out.bmp")], 2, "extension")
case("out_missing_folder", ["render", "--size", "3x3", "--out", T("no", "such", "out.png")], 2, "out.png")
case("no_subcommand", [], 2, "")
case("sweep_bad_axis", ["sweep", "--scene", os.path.join(src, "assets/scenes/default.json"), "--param", "ray_skip=0",
                        "--out", T("s.csv")], 2, "ray_skip")
case("sweep_unknown_param", ["sweep", "--scene", os.path.join(src, "assets/scenes/default.json"), "--param", "zoom=1",
                             "--out", T("s.csv")], 2, "zoom")

# 3. Presets, scenes and manifests that are broken or hostile.
def preset(name, text, want, frag):
    case("preset_" + name, R + ["--preset", write(name + ".json", text)], want, frag)

preset("wrong_type", '{"delta_y": "big"}', 2, "delta_y")
preset("huge_number", '{"delta_y": 1e999}', 2, "malformed JSON")
preset("negative_zero_window", '{"noise_window": -0}', 2, "noise_window")
preset("float_for_int", '{"ray_skip": 1.5}', 2, "ray_skip")
preset("int_beyond_64_bits", '{"ray_skip": 99999999999999999999999}', 2, "ray_skip")
preset("array", "[1, 2, 3]", 2, "object")
preset("string", '"paper"', 2, "object")
preset("empty", "", 2, "malformed")
preset("truncated", '{"delta_y": 2', 2, "malformed")
preset("nan_literal", '{"delta_y": NaN}', 2, "malformed")
preset("deep_nesting", "[" * 100000 + "]" * 100000, 2, "object")
preset("deep_object", '{"a":' * 50000 + "1" + "}" * 50000, 0, "")
preset("duplicate_keys", '{"delta_y": 5, "delta_y": 7}', 0, "")
preset("bom", "\ufeff{\"delta_y\": 5}", 0, "")
preset("nul_bytes", '{"delta_y": 5}\0\0\0', 0, "")  # padding after the object: read as the object
preset("nul_in_string", '{"mode": "light\\u0000x"}', 2, "mode")
preset("newer_schema", '{"schema_version": 99}', 2, "schema_version")
preset("many_unknown", "{" + ",".join(f'"k{i}": 1' for i in range(50000)) + "}", 0, "")
preset("big_string", '{"mode": "' + "x" * (50 << 20) + '"}', 2, "mode")
case("preset_too_large", R + ["--preset", write("too_large.json", " " * (65 << 20) + "{}")], 2, "MB")
preset("invalid_utf8", b'{"mode": "\xff\xfe"}'.decode("latin-1"), 2, "mode")

def scene(name, text, want, frag, extra=()):
    case("scene_" + name, ["render", "--scene", write(name + ".scene.json", text), *extra, "--out", T("out.png")], want, frag)

scene("lights_not_array", '{"lights": 5}', 2, "lights")
scene("light_without_y", '{"lights": [{"x": 1}]}', 2, "lights[0]")
scene("light_far", '{"lights": [{"x": 1e300, "y": 0}]}', 2, "lights[0]")
scene("light_intensity", '{"lights": [{"x": 1, "y": 1, "intensity": -1}]}', 2, "intensity")
scene("light_area_huge", '{"lights": [{"x": 1, "y": 1, "a": 999999}]}', 2, "lights[0]")
scene("light_height_negative", '{"lights": [{"x": 1, "y": 1, "height": -5}]}', 2, "height")
scene("width_zero", '{"width": 0}', 2, "width")
scene("width_huge", '{"width": 100000}', 2, "width")
scene("width_times_height", '{"width": 4096, "height": 300}', 2, "1228800 tiles")
case("size_long_strip", ["render", "--size", "4096x256", "--view", "0,0,64,64", "--out", T("out.png")], 0, "")
scene("layout_unknown", '{"layout": "hex"}', 2, "layout")
scene("camera_huge", '{"width": 3, "height": 3, "camera": {"x": 0, "y": 0, "width": 65536, "height": 65536}}', 2, "megapixel")
scene("camera_far", '{"width": 3, "height": 3, "camera": {"x": 1e18, "y": 0, "width": 10, "height": 10}}', 0, "")
scene("camera_far_endless", '{"width": "endless", "height": "endless", "camera": {"x": 1e300, "y": 0, "width": 10, "height": 10}}', 2, "camera")
scene("edit_beyond_the_world", '{"width": "endless", "height": "endless", "camera": {"x": 0, "y": 0, "width": 10, "height": 10}, "edits": [{"tile": [1000000000001, 0], "floor": "grass"}]}', 2, "edits[0]")
scene("edit_far_endless", '{"width": "endless", "height": "endless", "camera": {"x": 0, "y": 0, "width": 10, "height": 10}, "edits": [{"tile": [999999999999, -999999999999], "floor": "grass"}]}', 0, "")
scene("camera_huge_endless", '{"width": "endless", "height": "endless", "camera": {"x": 0, "y": 0, "width": 30000, "height": 10000}}', 2, "megapixel")
scene("map_and_endless", '{"width": "endless", "height": "endless", "map": "level.tmx", "camera": {"x": 0, "y": 0, "width": 10, "height": 10}}', 2, "map")
scene("endless_and_map", '{"map": "level.tmx", "height": "endless", "width": "endless"}', 2, "endless")
scene("preset_name_unknown", '{"preset": "brilliant"}', 2, "brilliant")
scene("tileset_missing", '{"width": 3, "height": 3, "tileset": "nowhere/tileset.json"}', 2, "tileset.json")
scene("too_many_lights", '{"lights": [' + ",".join('{"x": 1, "y": 1}' for _ in range(100001)) + "]}", 2, "lights")

# 4. Tilesets and images.
os.makedirs(T("ts"), exist_ok=True)
shutil.copy(os.path.join(src, "assets/default/grass.png"), T("ts", "grass.png"))
good = png(16, 16)
write("ts/good.png", good)
write("ts/truncated.png", good[: len(good) // 2])
write("ts/not_an_image.png", "this is text")
write("ts/declared_huge.png", png(100000, 100000, rows=b"\0"))
write("ts/bomb.png", png(8000, 8000, rows=b"\0" * (8000 * (8000 * 4 + 1))))
write("ts/zero.png", b"")
subprocess.run(["oiiotool", "--pattern", "checker", "16x16", "4", "-d", "uint16", "-o", T("ts", "deep.png")], check=True)
subprocess.run(["oiiotool", "--pattern", "constant:color=0.5", "16x16", "1", "-o", T("ts", "grey.png")], check=True)
subprocess.run(["oiiotool", "--pattern", "checker", "16x16", "4", "-d", "half", "-o", T("ts", "image.exr")], check=True)

def tileset(name, overlay, want, frag, extra=None):
    doc = {"sprites": [{"name": "grass", "image": "grass.png", "kind": "floor", "tags": ["grass"]}, overlay]}
    if extra:
        doc.update(extra)
    path = write(f"ts/{name}.json", json.dumps(doc))
    case("tileset_" + name, R + ["--tileset", path], want, frag)

O = lambda **kw: {"name": "o", "image": "good.png", "kind": "overlay", **kw}
tileset("image_missing", O(image="nowhere.png"), 2, "nowhere.png")
tileset("image_truncated", O(image="truncated.png"), 2, "truncated.png")
tileset("image_not_an_image", O(image="not_an_image.png"), 2, "not_an_image.png")
tileset("image_declared_huge", O(image="declared_huge.png"), 2, "declared_huge.png")
tileset("image_bomb", O(image="bomb.png"), 2, "megapixels")
tileset("image_empty_file", O(image="zero.png"), 2, "zero.png")
tileset("image_16bit", O(image="deep.png"), 0, "")
tileset("image_grey", O(image="grey.png"), 0, "")
tileset("image_exr", O(image="image.exr"), 0, "")
tileset("image_folder", O(image="."), 2, "folder")
tileset("image_device", O(image="/dev/zero"), 2, "device")
tileset("image_outside", O(image="../../../../../../etc/hostname"), 2, "hostname")
tileset("rect_outside", O(rect=[10, 10, 16, 16]), 2, "lies outside")
tileset("rect_overflow", O(rect=[2147483640, 0, 16, 16]), 2, "lies outside")
tileset("rect_wrap", O(rect=[4294967297, 0, 16, 16]), 2, "lies outside")
tileset("rect_negative", O(rect=[-1, 0, 4, 4]), 2, "lies outside")
tileset("rect_floats", O(rect=[0.5, 0, 4, 4]), 2, "rect")
tileset("anchor_min", O(anchor=[-2147483648, 0]), 2, "anchor")
tileset("anchor_huge", O(anchor=[0, 18446744073709551615]), 2, "anchor")
tileset("kind_unknown", O(kind="ceiling"), 2, "ceiling")
tileset("threshold_range", O(opacity_threshold=2), 2, "opacity_threshold")
tileset("shape_unknown", O(shape=[{"kind": "pyramid"}]), 2, "pyramid")
tileset("shape_negative", O(shape=[{"kind": "cylinder", "base": [0, 0, 0], "radius": -1, "height": 2}]), 2, "radius")
tileset("footprint_unknown", O(footprint="sideways"), 2, "sideways")
tileset("height_map_wrong_size", O(height_map="grass.png"), 2, "height_map")
tileset("tile_huge", O(), 2, "tile", extra={"tile": {"width": 999999, "height": 64}})
tileset("sprites_not_array", O(), 2, "sprites", extra={"sprites": 5})
# Big work from small files, which must stay within the budgets: tiles of
# 4096 x 2048 on a 1024 x 1024 map seen through a 64 x 64 view (the sprite
# grid once took 3.5 GB), and 500 sprites cut from one 2048 x 2048 sheet.
doc = {"tile": {"width": 4096, "height": 2048},
       "sprites": [{"name": "grass", "image": "grass.png", "kind": "floor", "tags": ["grass"]}, O()]}
case("tileset_tile_4096_on_a_1024_map", ["render", "--size", "1024x1024", "--view", "0,0,64,64", "--out", T("out.png"),
                                          "--tileset", write("ts/big_tiles.json", json.dumps(doc))], 0)
write("ts/sheet.png", png(2048, 2048, rows=b"\0" * (2048 * (2048 * 4 + 1))))
doc = {"sprites": [{"name": "grass", "image": "grass.png", "kind": "floor", "tags": ["grass"]}] +
                  [{"name": f"s{i}", "image": "sheet.png", "rect": [(i % 32) * 64, (i // 32) * 64, 64, 64],
                    "kind": "overlay", "tags": ["tree"]} for i in range(500)]}
case("tileset_500_sprites_from_one_sheet", R + ["--tileset", write("ts/sheet.json", json.dumps(doc))], 0)

# 5. Paths that are not plain files.
os.mkfifo(T("fifo.json"))
os.symlink(T("loop_b.json"), T("loop_a.json"))
os.symlink(T("loop_a.json"), T("loop_b.json"))
os.makedirs(T("folder.json"), exist_ok=True)
for name, path, frag in [("fifo", T("fifo.json"), "FIFO"), ("loop", T("loop_a.json"), "loop_a.json"),
                         ("folder", T("folder.json"), "folder"), ("dev_zero", "/dev/zero", "device"),
                         ("dev_urandom", "/dev/urandom", "device"), ("missing", T("missing.json"), "not found"),
                         ("etc_hostname", "/etc/hostname", "malformed")]:
    case("path_scene_" + name, ["render", "--scene", path, "--out", T("out.png")], 2, frag)
    case("path_preset_" + name, R + ["--preset", path], 2, frag)
case("path_tileset_fifo", R + ["--tileset", T("fifo.json")], 2, "FIFO")
case("path_check_tileset_loop", ["check-tileset", T("loop_a.json")], 2, "loop_a.json")

# 6. Tiled maps (render --map): the TMX reader's refusals, and its paths.
import base64 as _b64, zlib as _zlib
def tmx(name, body, attrs='orientation="isometric" width="2" height="2" tilewidth="64" tileheight="32"', frag=None, want=2,
        max_lines=None):
    path = write(os.path.join("tmx", name + ".tmx"), f'<?xml version="1.0"?><map {attrs}>{body}</map>')
    case("tmx_" + name, ["render", "--map", path, "--out", T("out.png")], want, name if frag is None else frag, max_lines)
TS = '<tileset firstgid="1" name="t" tilewidth="64" tileheight="64" tilecount="1" columns="0"><tile id="0"><image source="t.png" width="2" height="2"/></tile></tileset>'
write(os.path.join("tmx", "t.png"), png(2, 2))
L = lambda data: f'<layer name="g" width="2" height="2">{data}</layer>'
tmx("ok", TS + L('<data encoding="csv">1,1,1,1</data>'), frag="", want=0)
tmx("orthogonal", TS, attrs='orientation="orthogonal" width="2" height="2" tilewidth="64" tileheight="32"')
tmx("hexagonal", TS, attrs='orientation="hexagonal" width="2" height="2" tilewidth="64" tileheight="32"')
tmx("no_map", "", frag="no <map>")
tmx("too_many_tiles", TS, attrs='orientation="isometric" width="2048" height="1024" tilewidth="64" tileheight="32"',
    frag="2048x1024 tiles")
write(os.path.join("tmx", "no_map.tmx"), "<notamap/>")
tmx("huge_side", TS, attrs='orientation="isometric" width="100000" height="2" tilewidth="64" tileheight="32"', frag="width")
tmx("zero_tile", TS, attrs='orientation="isometric" width="2" height="2" tilewidth="0" tileheight="32"', frag="tilewidth")
tmx("missing_tsx", '<tileset firstgid="1" source="nope.tsx"/>' + L('<data encoding="csv">1,1,1,1</data>'), frag="nope.tsx")
tmx("missing_image", TS.replace("t.png", "nope.png") + L('<data encoding="csv">1,1,1,1</data>'), frag="nope.png")
tmx("gid_beyond", TS + L('<data encoding="csv">1,1,1,7</data>'), frag="gid 7")
tmx("short_csv", TS + L('<data encoding="csv">1,1,1</data>'), frag="holds 3 tiles")
tmx("long_csv", TS + L('<data encoding="csv">1,1,1,1,1</data>'), frag="holds 5 tiles")
tmx("csv_junk", TS + L('<data encoding="csv">1,x,1,1</data>'), frag="not a gid")
tmx("base64_junk", TS + L('<data encoding="base64">@@@@</data>'), frag="base64")
tmx("unknown_encoding", TS + L('<data encoding="hex">00</data>'), frag="hex")
tmx("unknown_compression", TS + L('<data encoding="base64" compression="lzma">AAAA</data>'), frag="lzma")
tmx("zlib_corrupt", TS + L('<data encoding="base64" compression="zlib">AAAAAAAA</data>'), frag="corrupt")
tmx("zstd_corrupt", TS + L('<data encoding="base64" compression="zstd">AAAAAAAA</data>'), frag="corrupt")
bomb = _b64.b64encode(_zlib.compress(bytes(256 << 20), 9)).decode()
tmx("zlib_bomb", TS + L(f'<data encoding="base64" compression="zlib">{bomb}</data>'), frag="bomb")
tmx("wrong_layer_size", TS + '<layer name="g" width="3" height="2"><data encoding="csv">1,1,1,1,1,1</data></layer>', frag="is 3x2")
tmx("infinite", TS, attrs='orientation="isometric" infinite="1" width="2" height="2" tilewidth="64" tileheight="32"')
tmx("chunks", TS + L('<data encoding="csv"><chunk x="0" y="0" width="2" height="2">1,1,1,1</chunk></data>'), frag="chunks")
INF = 'orientation="isometric" infinite="1" width="2" height="2" tilewidth="64" tileheight="32"'
def chunk(x, y, w=2, h=2, data=None):
    return f'<chunk x="{x}" y="{y}" width="{w}" height="{h}">{data or ",".join("1" * (w * h))}</chunk>'
tmx("chunks_far_negative", TS + L('<data encoding="csv">' + chunk(-999999998, -999999998) + '</data>'), attrs=INF, frag="1e8 pixels")
tmx("chunks_far_apart_in_x", TS + L('<data encoding="csv">' + chunk(999999000, 0) + chunk(999999990, 6) + '</data>'), attrs=INF, frag="1e8 pixels")
tmx("chunks_overlapping", TS + L('<data encoding="csv">' + chunk(0, 0, 4, 4) + chunk(2, 2, 4, 4) + '</data>'), attrs=INF, frag="overlaps an earlier chunk")
# The same 1024x1024 zlib chunk a hundred times: refused at the second, before it is inflated.
big = _b64.b64encode(_zlib.compress(bytes(4 << 20), 9)).decode()
tmx("chunks_repeated", TS + L('<data encoding="base64" compression="zlib">' +
    "".join(f'<chunk x="0" y="0" width="1024" height="1024">{big}</chunk>' for _ in range(100)) + '</data>'), attrs=INF, frag="overlaps an earlier chunk")
# Three tiny chunks far apart: a 130-megapixel view of mostly nothing, refused by its memory before any pixel.
tmx("chunks_sparse", TS + L('<data encoding="csv">' + chunk(0, 0) + chunk(450, 0) + chunk(0, 130) + '</data>'), attrs=INF, frag="GiB")
case("size_map_whole_memory", ["render", "--size", "128x128", "--out", T("out.png")], 2, "GiB")
case("size_map_whole_light_memory", ["render", "--size", "100x120", "--layer", "light", "--out", T("out.png")], 2, "--allow-huge")
tmx("stagger_x", TS, attrs='orientation="staggered" staggeraxis="x" width="2" height="2" tilewidth="64" tileheight="32"')
tmx("far_object", TS + L('<data encoding="csv">1,1,1,1</data>') + '<objectgroup name="o"><object gid="1" x="1e12" y="0"/></objectgroup>', frag="[-1e9, 1e9]")
tmx("far_object_projected", TS + L('<data encoding="csv">1,1,1,1</data>') + '<objectgroup name="o"><object gid="1" x="9e8" y="-9e8"/></objectgroup>', frag="too far")
tmx("nan_object", TS + L('<data encoding="csv">1,1,1,1</data>') + '<objectgroup name="o"><object gid="1" x="nan" y="0"/></objectgroup>', frag="not a number")
tmx("big_gid", TS + L('<data encoding="csv">1,1,1,99999999999</data>'), frag="not a gid")
# XML-encoded gids take the CSV's one reader: beyond 32 bits, or not a number, refused (not truncated).
tmx("xml_gid_beyond_32_bits", TS + L('<data><tile gid="1"/><tile gid="1"/><tile gid="1"/><tile gid="4294967297"/></data>'), frag="4294967297")
tmx("xml_gid_not_a_number", TS + L('<data><tile gid="1"/><tile gid="one"/><tile/><tile gid="1"/></data>'), frag="not a gid")
tmx("xml_gid_negative", TS + L('<data><tile gid="-1"/><tile gid="1"/><tile/><tile gid="1"/></data>'), frag="not a gid")
tmx("xml_gids_ok", TS + L('<data><tile gid="1"/><tile/><tile gid="1"/><tile gid="1"/></data>'), frag="", want=0)
tmx("floor_above_overlay", TS + L('<data encoding="csv">1,1,1,1</data>') + '<objectgroup name="o"><object gid="1" x="0" y="0"/></objectgroup>' + '<layer name="f" width="2" height="2"><properties><property name="isolux_kind" value="floor"/></properties><data encoding="csv">1,1,1,1</data></layer>', frag="floor layer above")
tmx("bad_light", TS + L('<data encoding="csv">1,1,1,1</data>') + '<objectgroup name="lights"><object x="1" y="1"><properties><property name="a" value="-5"/></properties><point/></object></objectgroup>', frag="property a")
tmx("malformed", TS + "<layer", frag="malformed XML")
case("tmx_fifo", ["render", "--map", T("fifo.json"), "--out", T("out.png")], 2, "FIFO")
case("tmx_loop", ["render", "--map", T("loop_a.json"), "--out", T("out.png")], 2, "loop_a.json")
case("tmx_with_seed", ["render", "--map", T(os.path.join("tmx", "ok.tmx")), "--seed", "x", "--out", T("out.png")], 2, "do not apply")

# 7. What a received file, an output path or an odd environment can still do.
import socket, stat as _stat
SCENE = os.path.join(src, "assets/scenes/default.json")
MANIFEST = os.path.abspath(os.path.join(src, "assets/default/tileset.json"))
keep_special = []  # (path, test): special files that must still be what they were after every case
os.mkfifo(T("out_fifo"))
keep_special.append((T("out_fifo"), _stat.S_ISFIFO))
os.symlink(T("out_fifo"), T("out_link_to_fifo"))
sock = socket.socket(socket.AF_UNIX)
sock.bind(T("out_socket"))
keep_special.append((T("out_socket"), _stat.S_ISSOCK))
specials = [("fifo", T("out_fifo"), "FIFO"), ("link_to_fifo", T("out_link_to_fifo"), "FIFO"), ("socket", T("out_socket"), "socket")]
if os.geteuid() == 0:
    # A device node of our own (a copy of /dev/null's numbers): never the machine's.
    os.mknod(T("out_device"), 0o666 | _stat.S_IFCHR, os.makedev(1, 3))
    keep_special.append((T("out_device"), _stat.S_ISCHR))
    specials.append(("device", T("out_device"), "device"))
else:
    print("bad inputs: not root: the device-node output case needs mknod and is left out")
writers = [
    ("render", lambda out: R[:-1] + [out]),
    ("preset", lambda out: ["preset", "--out", out]),
    ("sweep_out", lambda out: ["sweep", "--scene", SCENE, "--param", "ray_skip=1", "--out", out]),
    ("sweep_chart", lambda out: ["sweep", "--scene", SCENE, "--param", "ray_skip=1", "--out", T("sweep.csv"), "--chart", out]),
    ("check_sheet", lambda out: ["check-tileset", MANIFEST, "--sheet", out]),
    ("export_tiled", lambda out: ["export-tiled", "--scene", SCENE, "--out", out]),
]
for wname, args in writers:
    for sname, target, frag in specials:
        # The sheet and the render check the extension first; give them one the
        # special file carries through a link named for it.
        path = target
        if wname in ("render", "check_sheet", "export_tiled"):
            path = T(f"link_{wname}_{sname}" + (".tmx" if wname == "export_tiled" else ".png"))
            os.symlink(target, path)
        case(f"out_special_{wname}_{sname}", args(path), 2, frag)
# normals: the tileset read as any command reads it; its outputs, named by
# isolux inside the folder chosen, never a special file, a link out of it,
# one of the tileset's own files, or a path a sprite's name makes.
case("normals_tileset_fifo", ["normals", "--tileset", T("fifo.json"), "--out", T("normals")], 2, "FIFO")
case("normals_tileset_loop", ["normals", "--tileset", T("loop_a.json"), "--out", T("normals")], 2, "loop_a.json")
os.makedirs(T("normals_special"), exist_ok=True)
os.mkfifo(T("normals_special", "oak.normal.png"))
keep_special.append((T("normals_special", "oak.normal.png"), _stat.S_ISFIFO))
case("normals_out_fifo", ["normals", "--tileset", MANIFEST, "--out", T("normals_special")], 2, "FIFO")
os.makedirs(T("normals_link"), exist_ok=True)
os.symlink(T("elsewhere.png"), T("normals_link", "oak.height.png"))
case("normals_out_link", ["normals", "--tileset", MANIFEST, "--out", T("normals_link")], 2, "symbolic link")
case("normals_over_own_files", ["normals", "--tileset", MANIFEST, "--out", os.path.dirname(MANIFEST)], 2, "tileset's own files")
grass = os.path.join(os.path.dirname(MANIFEST), "grass.png")
for label, name in (("parent", ".."), ("slash", "../escape"), ("empty", "")):
    m = write(f"normals_names/{label}/tileset.json", json.dumps({"schema_version": 1, "tile": {"width": 128, "height": 64},
        "sprites": [{"name": name, "image": grass, "anchor": [64, 32], "kind": "floor", "tags": ["grass"]}]}))
    case(f"normals_sprite_name_{label}", ["normals", "--tileset", m, "--out", T("normals_names", label, "out")], 2,
         "sprite")
# Outputs checked before the work: a missing folder or a wrong extension is
# refused up front, naming the path.
case("out_sweep_missing_folder", ["sweep", "--scene", SCENE, "--param", "ray_skip=1,2", "--out", T("no", "such", "s.csv")], 2, "does not exist")
case("out_sweep_chart_missing_folder", ["sweep", "--scene", SCENE, "--param", "ray_skip=1,2", "--out", T("s.csv"),
                                        "--chart", T("no", "such", "c.svg")], 2, "c.svg")
case("out_sheet_extension", ["check-tileset", MANIFEST, "--sheet", T("sheet.bmp")], 2, "extension")
case("out_sheet_missing_folder", ["check-tileset", MANIFEST, "--sheet", T("no", "such", "sheet.png")], 2, "does not exist")
case("out_preset_missing_folder", ["preset", "--out", T("no", "such", "p.json")], 2, "No such file")
# Read errors other than "missing": a file that is regular but cannot be read.
case("read_error_tileset", R + ["--tileset", "/proc/self/mem"], 2, "/proc/self/mem")
case("read_error_preset", R + ["--preset", "/proc/self/mem"], 2, "/proc/self/mem")
tmx("tsx_read_error", '<tileset firstgid="1" source="/proc/self/mem"/>' + L('<data encoding="csv">1,1,1,1</data>'), frag="/proc/self/mem")
# Deep nesting: groups a file sets the depth of are walked without recursion.
deep = 20000
tmx("groups_nested_20000", TS + "<group>" * deep + L('<data encoding="csv">1,1,1,1</data>') + "</group>" * deep, frag="", want=0)
tmx("groups_nested_20000_unclosed", "<group>" * deep, frag="malformed XML")
# Control characters from files are printed escaped (the run refuses any raw ESC below).
scene("control_chars_in_colour", '{"lights": [{"x": 1, "y": 1, "color": "\\u001b[2J\\u001b]52;c;aGk=\\u0007"}]}', 2, "\\x1b[2J")
tileset("control_chars_in_image_name", O(image="\u001b[31mred.png"), 2, "\\x1b[31mred.png")
tmx("control_chars_in_layer_name", TS + '<layer name="\u001b[2J" width="3" height="2"><data encoding="csv">1,1,1,1,1,1</data></layer>', frag="\\x1b[2J")
# Warnings capped: a million faulty entries print a dozen lines.
many_edits = json.dumps({"width": 3, "height": 3, "edits": [{"tile": [100 + i, 0], "floor": "grass"} for i in range(200000)]})
case("warnings_capped_edits_outside", ["render", "--scene", write("many_edits.scene.json", many_edits), "--out", T("out.png")],
     0, "more edits outside", max_lines=12)
tmx("warnings_capped_image_layers", TS + L('<data encoding="csv">1,1,1,1</data>') + '<imagelayer name="i"/>' * 200000,
    frag="more image layers", want=0, max_lines=12)
# A map read back exports again (its floors kept: tests/core/formats/tiled_test.cpp checks the pixels).
os.makedirs(T("reexport"), exist_ok=True)  # export-tiled writes into a folder that exists
case("reexport_tiled_map", ["export-tiled", "--scene", write("reexport.scene.json", json.dumps({"map": T("tmx", "ok.tmx")})),
                            "--out", T("reexport", "map.tmx")], 0)
# Sprite names that are paths write nothing outside the export's folder.
names_doc = json.load(open(MANIFEST))
for i, sprite in enumerate(names_doc["sprites"]):
    sprite["image"] = os.path.join(os.path.dirname(MANIFEST), sprite["image"])
    if "height_map" in sprite:
        sprite["height_map"] = os.path.join(os.path.dirname(MANIFEST), sprite["height_map"])
    sprite["name"] = ["../../escaped", "/tmp/isolux_bad_absolute", "same", "same"][i % 4] if i < 8 else sprite["name"]
write("names/tileset.json", json.dumps(names_doc))
os.makedirs(T("names", "out"), exist_ok=True)
case("export_names_are_not_paths", ["export-tiled", "--scene", write("names.scene.json", json.dumps(
    {"width": 4, "height": 4, "tileset": T("names", "tileset.json")})), "--out", T("names", "out", "map.tmx")], 0)
# A name isolux gives a file of its own in the chosen folder that is a link
# out of it is refused by name (tests/core/formats/file_io_test.cpp checks nothing lands outside).
os.makedirs(T("link_out", "elsewhere"))
os.makedirs(T("link_out", "export"))
os.symlink(T("link_out", "elsewhere"), T("link_out", "export", "map_images"))
case("export_images_folder_is_a_link_out", ["export-tiled", "--scene", SCENE, "--out", T("link_out", "export", "map.tmx")],
     2, "map_images: is a symbolic link")
# A first export beside a user's own file under an export's name is refused
# by that name, and the file keeps its bytes (tests/core/formats/tiled_test.cpp).
write("own_tsx/export/map_floors.tsx", "the user's own")
case("export_beside_a_users_own_tsx", ["export-tiled", "--scene", SCENE, "--out", T("own_tsx", "export", "map.tmx")],
     2, "map_floors.tsx: already exists")
# Budgets per input, not per item: a small file that asks for gigabytes is refused with its total.
big_png = write("big/sheet.png", png(4096, 4096, rows=b"".join(b"\0" + b"\0" * (4096 * 4) for _ in range(4096))))
case("budget_100_sprites_one_large_sheet", R + ["--tileset", write("big/tileset.json", json.dumps({"sprites": [
    {"name": "g", "image": "sheet.png", "kind": "floor", "tags": ["grass"]}] + [
    {"name": f"o{i}", "image": "sheet.png", "kind": "overlay"} for i in range(100)]}))], 2, "megapixels")
tiles = "".join(f'<tile id="{i}"><image source="../big/sheet.png" width="4096" height="4096"/></tile>' for i in range(100))
tmx("budget_100_tile_images", f'<tileset firstgid="1" name="t" tilewidth="64" tileheight="64" tilecount="100" columns="0">{tiles}</tileset>'
    + L('<data encoding="csv">1,1,1,1</data>'), frag="megapixels")
layer_bytes = _b64.b64encode(_zlib.compress(b"\x01\0\0\0" * (1024 * 1024), 9)).decode()
tmx("budget_64_layers_of_1024", TS + "".join(f'<layer name="l{i}" width="1024" height="1024"><data encoding="base64" compression="zlib">{layer_bytes}</data></layer>' for i in range(64)),
    attrs='orientation="isometric" width="1024" height="1024" tilewidth="64" tileheight="32"', frag="4194304 sprites")
# A sprite's footprint mask is budgeted with its image: Algorithm 1 marks a
# quarter of a run above and below it, so a sprite W wide may need W x W/2.
write("ts/wide.png", png(65536, 1))
tileset("footprint_mask_65536x1", O(image="wide.png"), 2, "megapixels")
# A 1000-point footprint polygon on a 2048-pixel sprite is filled row by row.
write("ts/large.png", png(2048, 2048, rows=b"".join(b"\0" + b"\0" * (2048 * 4) for _ in range(2048))))
ring = [[1024 + int(1000 * (1 if k % 2 else 0.6) * __import__("math").cos(k * 0.00628318)),
         1024 + int(1000 * (1 if k % 2 else 0.6) * __import__("math").sin(k * 0.00628318))] for k in range(1000)]
poly_ts = {"sprites": [{"name": "grass", "image": "grass.png", "kind": "floor", "tags": ["grass"]},
                       O(image="large.png", footprint={"polygon": ring})]}
case("footprint_polygon_1000_points", ["render", "--scene", write("ts/poly.scene.json", json.dumps(
    {"width": 3, "height": 3, "tileset": write("ts/poly.json", json.dumps(poly_ts)),
     "edits": [{"tile": [1, 1], "overlays": ["o"]}]})), "--layer", "obstacles", "--out", T("out.png")], 0)
# The same polygon scaled to a 4096x4096 sprite, through check-tileset (the
# footprint, the solid and the sheet of a sprite the size of the largest image).
write("ts/large4096.png", png(4096, 4096, rows=b"".join(b"\0" + b"\0" * (4096 * 4) for _ in range(4096))))
poly4096_ts = {"sprites": [{"name": "grass", "image": "grass.png", "kind": "floor", "tags": ["grass"]},
                           O(image="large4096.png", footprint={"polygon": [[2 * x, 2 * y] for x, y in ring]})]}
case("footprint_polygon_1000_points_4096_check", ["check-tileset", write("ts/poly4096.json", json.dumps(poly4096_ts)),
                                                  "--json"], 0)
# An object's height is bounded by its image: a hundred sprites asking for
# solids 65,536 pixels tall are refused as the manifest loads.
write("ts/small64.png", png(64, 64))
tall_ts = {"sprites": [{"name": "grass", "image": "grass.png", "kind": "floor", "tags": ["grass"]}] +
           [O(name=f"o{i}", image="small64.png", footprint={"object": {"foot": [32, 60], "height": 65536}}) for i in range(100)]}
case("object_height_65536_a_hundred_times", ["check-tileset", write("ts/tall.json", json.dumps(tall_ts))], 2, "taller than its 64x64")
tileset("object_height_beyond_image", O(image="small64.png", footprint={"object": {"height": 65}}), 2, "height 65")
# The shapes' solids are a budget of the whole tileset: four sprites of 1000
# boxes each are refused, however each shape alone is within its own limit.
def boxes(n):
    return [{"kind": "box", "min": [k % 20 - 10, k // 20 - 25, 0], "max": [k % 20 - 9, k // 20 - 24, 8]} for k in range(n)]
shapes_ts = {"sprites": [{"name": "grass", "image": "grass.png", "kind": "floor", "tags": ["grass"]}] +
             [O(name=f"s{i}", image="small64.png", shape=boxes(1000)) for i in range(4)]}
case("shapes_4_of_1000_boxes", ["render", "--size", "3x3", "--tileset", write("ts/shapes4.json", json.dumps(shapes_ts)),
                                "--occluders", "shapes", "--out", T("out.png")], 2, "over the 1000")
shapes2_ts = dict(shapes_ts, sprites=shapes_ts["sprites"][:1] + [O(name=f"s{i}", image="small64.png", shape=boxes(600)) for i in range(2)])
case("shapes_2_of_600_boxes_truth", ["render", "--size", "3x3", "--tileset", write("ts/shapes2.json", json.dumps(shapes2_ts)),
                                     "--layer", "truth", "--out", T("out.png")], 2, "solids to 1200")
# A solid estimated from a 2048x2048 opaque sprite, its silhouette drawn
# (check-tileset) and traced against (render): the work follows rows times
# heights, not pixels times heights (minutes before).
write("ts/opaque2048.png", png(2048, 2048, rows=b"".join(b"\0" + b"\x80\x80\x80\xff" * 2048 for _ in range(2048))))
opaque_ts = write("ts/opaque2048.json", json.dumps({"sprites": [{"name": "grass", "image": "grass.png", "kind": "floor", "tags": ["grass"]},
                                                                O(image="opaque2048.png")]}))
case("solid_of_a_2048_opaque_sprite_sheet", ["check-tileset", opaque_ts, "--json", "--sheet", T("sheet.png")], 0)
case("solid_of_a_2048_opaque_sprite_traced", ["render", "--scene", write("ts/opaque.scene.json", json.dumps(
    {"width": 1, "height": 1, "tileset": opaque_ts, "edits": [{"tile": [0, 0], "overlays": ["o"]}],
     "lights": [{"x": 100, "y": 1500}]})), "--occluders", "solids", "--out", T("out.png")], 0)
# A 2048x2048 sprite of 466 000 one-pixel specks: the object's parts are
# found in time linear in its pixels (a mask per component took minutes).
speck_row = b"".join(b"\x80\x80\x80\xff" if x % 3 == 0 else b"\0\0\0\0" for x in range(2048))
write("ts/specks2048.png", png(2048, 2048, rows=b"".join(b"\0" + (speck_row if y % 3 == 0 else b"\0" * 8192) for y in range(2048))))
specks_ts = write("ts/specks2048.json", json.dumps({"sprites": [{"name": "grass", "image": "grass.png", "kind": "floor", "tags": ["grass"]},
                                                                 O(image="specks2048.png")]}))
case("solid_of_2048_specks", ["check-tileset", specks_ts, "--json"], 0)
# A 2048x2048 grove: two trunks on the tile under a canopy of four crowns
# of one colour each, 1000 rows tall: its crowns, hidden trees and their
# solids are found in time linear in its pixels for each tree.
def grove_row(y):
    row = bytearray(2048 * 4)
    for x in range(2048):
        if 1000 <= y < 2000 and 900 <= x < 1148:
            k = (x - 900) // 62
            row[4 * x:4 * x + 4] = bytes((60 + 50 * k, 140, 40, 255))
        if 1990 <= y < 2040 and (978 <= x < 982 or 1068 <= x < 1072):
            row[4 * x:4 * x + 4] = b"\x50\x36\x2a\xff"
    return bytes(row)
write("ts/grove2048.png", png(2048, 2048, rows=b"".join(b"\0" + grove_row(y) for y in range(2048))))
grove_ts = write("ts/grove2048.json", json.dumps({"sprites": [{"name": "grass", "image": "grass.png", "kind": "floor", "tags": ["grass"]},
                                                               O(image="grove2048.png")]}))
case("solid_of_a_2048_grove", ["check-tileset", grove_ts, "--json"], 0)
# A million edits (36 MB) take time in proportion: each sprite name found in a
# sorted index, not by a search per edit.
case("edits_a_million", ["render", "--scene", write("million.scene.json", json.dumps(
    {"width": 8, "height": 8, "edits": [{"tile": [i % 8, (i // 8) % 8], "floor": "grass"} for i in range(1000000)]})),
    "--out", T("out.png")], 0)
# Work counted whole before it starts: frames and view pixels, and the 3D reference.
case("work_frames_and_view", ["render", "--size", "3x3", "--frames", "100000", "--out", T("out.png")], 2, "allow-huge")
case("work_3d_reference", ["render", "--size", "40x40", "--light", "600,400", "--light", "800,500", "--area", "1500,1500",
                           "--layer", "truth", "--out", T("out.png")], 2, "allow-huge")
# A long sweep keeps one frame and a bounded cache of references, not every
# frame nor a reference per value of a long axis.
small_view = json.load(open(os.path.join(src, "assets/scenes/default.json")))
small_view["camera"] = {"x": 500, "y": 300, "width": 320, "height": 240}
small_view_path = write("small_view.scene.json", json.dumps(small_view))
case("sweep_50_frames", ["sweep", "--scene", small_view_path, "--frames", "50", "--repeats", "1",
                         "--param", "ray_skip=1,2", "--out", T("s50.csv")], 0)
case("sweep_40_values", ["sweep", "--scene", small_view_path, "--frames", "1", "--repeats", "1", "--reference", "every_pixel",
                         "--param", "light_height=" + ",".join(str(v) for v in range(1, 41)), "--out", T("s40.csv")], 0)
# Lights of many distinct large areas (each its own ray tree, about 50 MB at
# a = b = 500): the trees kept stay within their caches' budgets, not one a light.
case("lights_of_many_distinct_areas", ["render", "--scene", write("many_areas.scene.json", json.dumps(
    {"width": 16, "height": 16, "lights": [{"x": 1030 + i % 5, "y": 578 + i % 3, "a": 488 + i, "b": 488 + i}
                                           for i in range(25)]})), "--out", T("out.png")], 0)
# A shape of huge solids (tracing against shapes fills each one's ground at
# every instance): refused as the manifest loads, not a frame of minutes.
tileset("shape_beyond_its_sprite", O(shape=[{"kind": "box", "min": [-1e5, -1e5, 0], "max": [1e5, 1e5, 10 + i]}
                                            for i in range(1000)]), 2, "covers")
# Tracing against the manifest's shapes, where a sprite has none: refused naming it.
case("occluders_shapes_without_shapes", ["render", "--size", "4x4", "--tileset",
     os.path.join(src, "tests/data/foreign_tileset/tileset.json"), "--occluders", "shapes", "--out", T("out.png")], 2,
     "has no shape")
# A built-in preset's name is always the built-in, whatever the working folder
# holds (a folder named game, a file named paper); "./paper" reaches the file.
os.makedirs(T("shadow", "game"), exist_ok=True)
write("shadow/paper", "this is not a preset")
case("preset_name_beside_a_folder_of_that_name", ["render", "--size", "3x3", "--preset", "game", "--out", T("shadow.png")], 0,
     cwd=T("shadow"))
case("preset_name_beside_a_file_of_that_name", ["render", "--size", "3x3", "--preset", "paper", "--out", T("shadow.png")], 0,
     cwd=T("shadow"))
case("preset_path_to_a_file_of_a_builtins_name", ["render", "--size", "3x3", "--preset", "./paper", "--out", T("shadow.png")], 2,
     "paper", cwd=T("shadow"))
# export-tiled into a folder that does not exist: refused before the work,
# as every other output is, and nothing made.
small_scene = write("export_small.scene.json", json.dumps({"seed": "export", "width": 3, "height": 3}))
case("export_tiled_into_a_missing_folder", ["export-tiled", "--scene", small_scene, "--out", T("no_such_dir", "level.tmx")],
     2, "does not exist")
case("export_tiled_into_a_missing_folder_two_deep", ["export-tiled", "--scene", small_scene, "--out",
                                                      T("no", "such", "level.tmx")], 2, "does not exist")
# export-tiled of a map whose export would hold over 1 GiB: refused with the
# estimate before any file, a whole map and a lit frame of it (--images).
os.makedirs(T("big_export"), exist_ok=True)
case("export_tiled_whole_256_map", ["export-tiled", "--scene", write("export_256.scene.json", json.dumps(
    {"seed": "big", "width": 256, "height": 256})), "--out", T("big_export", "level.tmx")], 2, "GiB")
case("export_tiled_images_of_a_large_map", ["export-tiled", "--images", "--scene", write("export_80.scene.json", json.dumps(
    {"seed": "big", "width": 80, "height": 80})), "--out", T("big_export", "level.tmx")], 2, "--allow-huge")
case("export_tiled_endless_region_too_large", ["export-tiled", "--scene", write("export_endless.scene.json", json.dumps(
    {"width": "endless", "height": "endless"})), "--view", "0,0,16000,12000", "--out", T("big_export", "level.tmx")], 2, "GiB")
must_not_exist = [T("big_export", "level.tmx"), T("big_export", "level_images"), T("no_such_dir"), T("no"), T("escaped.png"), T("names", "escaped.png"), "/tmp/isolux_bad_absolute.png"]

# Run them all (or those --only names).
if "--only" in sys.argv[3:]:
    only = sys.argv[sys.argv.index("--only") + 1]
    cases = [c for c in cases if only in c[0]]
    must_not_exist = []
times = "--times" in sys.argv[3:]
jobs = int(sys.argv[sys.argv.index("--jobs") + 1]) if "--jobs" in sys.argv[3:] else 1


def run_case(name, args, want, fragment, max_lines, cwd):
    """One case: its problems (empty when handled), seconds and the peak memory of any case so far."""
    start = time.monotonic()
    proc = subprocess.Popen([cli, *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=cwd)
    try:
        _, err = proc.communicate(timeout=LIMIT_S * 3)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        return [f"hung (killed after {LIMIT_S * 3:.0f} s)"], "", LIMIT_S * 3, 0.0
    seconds = time.monotonic() - start
    mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    err = err.decode("utf-8", "replace")
    lines = [l for l in err.splitlines() if l.strip()]
    problems = []
    if proc.returncode != want:
        problems.append(f"exit {proc.returncode}, want {want}")
    if "Sanitizer" in err or "runtime error" in err:
        problems.append("sanitizer report")
    if want == 2 and name != "no_subcommand" and len([l for l in lines if not l.startswith("isolux-cli: warning")]) != 1:
        problems.append(f"{len(lines)} lines of message, want one")
    if fragment and fragment not in err:
        problems.append(f"message lacks {fragment!r}")
    if "\x1b" in err or "\x07" in err:
        problems.append("a raw control character reached the terminal")
    if max_lines is not None and len(lines) > max_lines:
        problems.append(f"{len(lines)} lines of message, want at most {max_lines}")
    if seconds > LIMIT_S:
        problems.append(f"took {seconds:.1f} s")
    return problems, err, seconds, mb


# --jobs N: N cases at once (each case's budget holds under that load too).
from concurrent.futures import ThreadPoolExecutor  # noqa: E402
failures = []
worst_s = worst_mb = 0.0
with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
    results = list(pool.map(lambda c: run_case(*c), cases))
for (name, *_), (problems, err, seconds, mb) in zip(cases, results):
    worst_s, worst_mb = max(worst_s, seconds), max(worst_mb, mb)
    if times:
        print(f"{seconds:6.2f} s {mb:6.0f} MB (peak so far)  {name}")
    if problems:
        failures.append(f"{name}: {'; '.join(problems)}: {err.strip()[:300]}")
for path, is_kind in keep_special:
    if not is_kind(os.lstat(path).st_mode):
        failures.append(f"{path}: a special file was replaced by a save")
for path in must_not_exist:
    if os.path.exists(path):
        failures.append(f"{path}: written outside the export's folder")
        os.remove(path)
sock.close()
shutil.rmtree(tmp, ignore_errors=True)
for f in failures:
    print("FAIL", f)
print(f"bad inputs: {len(cases) - len(failures)} of {len(cases)} cases handled; slowest {worst_s:.2f} s; "
      f"largest peak memory of any case so far {worst_mb:.0f} MB")
sys.exit(1 if failures or worst_mb > LIMIT_MB else 0)
