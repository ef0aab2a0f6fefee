#!/usr/bin/env python3
"""Other languages through the C API: examples/c/render.c (C, linked with
libisolux) and examples/python/render.py (Python, ctypes only) render the
default scene, the showcase scene and Tiled's own example map; each picture
and light texture must have the same bytes as `isolux-cli render`.

Usage: run.py ISOLUX_CLI C_RENDER LIBISOLUX SOURCE_DIR [--preload=LIB:LIB]
With --preload (the AddressSanitizer build), Python runs with the sanitizer's
runtime preloaded, so the instrumented library loads into it; its leak check
is off there (the interpreter keeps its allocations to exit by design).
"""
import os, subprocess, sys, tempfile

from png_rgba import png_rgba  # noqa: E402 (tests/capi/png_rgba.py)

cli, c_render, lib, src = sys.argv[1:5]
tmp = tempfile.mkdtemp(prefix="isolux_capi_")
env = dict(os.environ, ISOLUX_LIB=lib, ISOLUX_ASSETS=os.path.join(src, "assets"))
py_env = dict(env)
for arg in sys.argv[5:]:
    if arg.startswith("--preload="):
        py_env["LD_PRELOAD"] = arg.split("=", 1)[1]
        py_env["ASAN_OPTIONS"] = os.environ.get("ASAN_OPTIONS", "") + ":detect_leaks=0"
        print("Python runs with", py_env["LD_PRELOAD"], "preloaded")
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from checks import check, failures, finish  # noqa: E402 (tests/checks.py)


def run(*args):
    e = py_env if args[0] == sys.executable else env
    p = subprocess.run([str(a) for a in args], capture_output=True, text=True, env=e, timeout=300)
    if p.returncode != 0:
        print("command:", " ".join(map(str, args)), "exit", p.returncode, "\n", p.stdout, p.stderr)
    return p


def pam_rgba(path):
    data = open(path, "rb").read()
    head, body = data.split(b"ENDHDR\n", 1)
    fields = dict(l.split(b" ", 1) for l in head.split(b"\n")[1:] if b" " in l)
    return int(fields[b"WIDTH"]), int(fields[b"HEIGHT"]), body


def same(png, pam, what):
    a, b = png_rgba(png), pam_rgba(pam)
    if a[:2] != b[:2]:
        check(False, f"{what}: {b[0]}x{b[1]}, isolux-cli {a[0]}x{a[1]}")
        return
    diff = sum(1 for i in range(0, len(a[2]), 4) if a[2][i:i + 4] != b[2][i:i + 4])
    check(diff == 0, f"{what}: {diff} of {a[0] * a[1]} pixels differ from isolux-cli's")
    print(f"{what}: {a[0]}x{a[1]}, {diff} pixels differ")


def tiled_example():
    for d in ("/usr/share/doc/tiled/examples", "/usr/share/tiled/examples"):
        p = os.path.join(d, "isometric_grass_and_water.tmx")
        if os.path.exists(p):
            return p
    check(False, "Tiled's isometric_grass_and_water.tmx not found (Debian's tiled package)")
    return None


inputs = [("default", ["--scene", os.path.join(src, "assets/scenes/default.json")]),
          ("showcase", ["--scene", os.path.join(src, "assets/scenes/showcase.json")])]
tmx = tiled_example()
if tmx:
    # Tiled's map with two lights of its own: the example has none.
    lit = os.path.join(tmp, "grass_and_water.tmx")
    text = open(tmx).read().replace('source="', 'source="' + os.path.dirname(tmx) + "/")
    lights = ('<objectgroup name="lights">'
              '<object id="900" name="a" type="light" x="200" y="200"><point/></object>'
              '<object id="901" name="b" type="light" x="500" y="600"><properties>'
              '<property name="color" value="#ffd49a"/></properties><point/></object></objectgroup>')
    open(lit, "w").write(text.replace("</map>", lights + "</map>"))
    inputs.append(("tiled-example", ["--map", lit]))

for name, args in inputs:
    path = args[1]
    final, light = os.path.join(tmp, name + ".png"), os.path.join(tmp, name + ".light.png")
    if run(cli, "render", *args, "--out", final).returncode or run(cli, "render", *args, "--layer", "light",
                                                                      "--out", light).returncode:
        check(False, name + ": isolux-cli failed")
        continue
    for lang, cmd in (("C", [c_render]), ("Python", [sys.executable, os.path.join(src, "examples/python/render.py")])):
        out, out_light = os.path.join(tmp, f"{name}.{lang}.pam"), os.path.join(tmp, f"{name}.{lang}.light.pam")
        p = run(*cmd, path, out, out_light)
        check(p.returncode == 0, f"{name} through {lang}: exit {p.returncode} {p.stderr}")
        if p.returncode == 0:
            same(final, out, f"{name} through {lang}, final")
            same(light, out_light, f"{name} through {lang}, light texture")
            texture = pam_rgba(out_light)[2]
            lit = sum(1 for i in range(0, len(texture), 4) if any(texture[i:i + 3]))
            check(lit > 1000, f"{name} through {lang}: only {lit} lit pixels in the light texture")

# A refusal names the file, through both languages.
missing = os.path.join(tmp, "no such scene.json")
for lang, cmd in (("C", [c_render]), ("Python", [sys.executable, os.path.join(src, "examples/python/render.py")])):
    p = subprocess.run(cmd + [missing, os.path.join(tmp, "x.pam")], capture_output=True, text=True,
                       env=py_env if cmd[0] == sys.executable else env, timeout=60)
    check(p.returncode != 0 and "no such scene.json" in p.stderr, f"{lang}: a missing scene is named: {p.stderr!r}")

finish("capi")
