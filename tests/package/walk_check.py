#!/usr/bin/env python3
"""examples/walk's frames against isolux-cli: every pixel outside the
character's figure must be the byte isolux-cli renders for the same view,
level and lights (the character's light at its feet). Checks frames 0, the
middle one and the last; every frame must exist.

Usage: walk_check.py ISOLUX_CLI LEVEL FRAMES_DIR
"""
import os, subprocess, sys, tempfile

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "capi"))
from png_rgba import png_rgba  # noqa: E402 (tests/capi/png_rgba.py)
cli, level, frames_dir = sys.argv[1:4]
tmp = tempfile.mkdtemp(prefix="isolux_walk_")


def pam(path):
    data = open(path, "rb").read()
    head, body = data.split(b"ENDHDR\n", 1)
    f = dict(l.split(b" ", 1) for l in head.split(b"\n")[1:] if b" " in l)
    return int(f[b"WIDTH"]), int(f[b"HEIGHT"]), body


rows = [list(map(int, l.split())) for l in open(os.path.join(frames_dir, "frames.txt")) if not l.startswith("#")]
failures = []
if len(rows) < 3:
    failures.append(f"only {len(rows)} frames")
for r in rows:
    if not os.path.exists(os.path.join(frames_dir, f"frame-{r[0]:03d}.pam")):
        failures.append(f"frame {r[0]} missing")
for r in [rows[0], rows[len(rows) // 2], rows[-1]] if len(rows) >= 3 else []:
    f, vx, vy, vw, vh, lx, ly, fx, fy, fw, fh = r
    out = os.path.join(tmp, f"cli-{f}.png")
    p = subprocess.run([cli, "render", "--scene", level, "--view", f"{vx},{vy},{vw},{vh}",
                        "--light", f"{lx},{ly},160,160,ffecc8,h=28", "--out", out],
                       capture_output=True, text=True, timeout=300)
    if p.returncode:
        failures.append(f"frame {f}: isolux-cli: {p.stderr}")
        continue
    w, h, cli_px = png_rgba(out)
    ww, wh, walk_px = pam(os.path.join(frames_dir, f"frame-{f:03d}.pam"))
    if (w, h) != (ww, wh):
        failures.append(f"frame {f}: {ww}x{wh}, isolux-cli {w}x{h}")
        continue
    differ = figure = 0
    for y in range(h):
        for x in range(w):
            i = (y * w + x) * 4
            if fx <= x < fx + fw and fy <= y < fy + fh:
                figure += walk_px[i:i + 4] != cli_px[i:i + 4]
            elif walk_px[i:i + 4] != cli_px[i:i + 4]:
                differ += 1
    print(f"frame {f}: view {vx},{vy} light {lx},{ly}: {differ} pixels differ outside the figure; "
          f"{figure} figure pixels drawn")
    if differ:
        failures.append(f"frame {f}: {differ} pixels differ from isolux-cli outside the figure")
    if figure < 50:
        failures.append(f"frame {f}: the figure is not drawn ({figure} pixels)")
for line in failures:
    print("FAIL", line)
print(f"walk: {len(rows)} frames, {len(failures)} failures")
sys.exit(1 if failures else 0)
