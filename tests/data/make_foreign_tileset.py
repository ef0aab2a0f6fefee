#!/usr/bin/env python3
"""Writes tests/data/foreign_tileset/: art drawn by neither isolux's generator
nor its team's style, in the PNG flavours users bring: a palette sheet with
transparency, 16-bit RGBA, 8-bit grey+alpha and 16-bit grey, at 64x32 floor
diamonds with 64x128 trees. Standard library only (zlib + struct), so the
bytes are reproducible. Run from anywhere: python3 make_foreign_tileset.py"""
import os, struct, zlib

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "foreign_tileset")


def chunk(kind, data):
    c = struct.pack(">I", len(data)) + kind + data
    return c + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def write_png(name, width, height, bit_depth, color_type, rows, palette=None, trns=None):
    raw = b"".join(b"\x00" + r for r in rows)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, color_type, 0, 0, 0))
    if palette:
        png += chunk(b"PLTE", b"".join(bytes(c) for c in palette))
    if trns is not None:
        png += chunk(b"tRNS", bytes(trns))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(png)


def in_diamond(x, y, cx, cy, hw, hh):
    return abs(x + 0.5 - cx) / hw + abs(y + 0.5 - cy) / hh <= 1.0


def main():
    os.makedirs(OUT, exist_ok=True)
    # Palette sheet 128x48: two 64x48 floor blocks (diamond top 64x32 + 16 px side).
    palette = [(0, 0, 0), (90, 170, 60), (60, 120, 40), (120, 80, 40), (40, 90, 200), (30, 60, 140), (200, 190, 120)]
    trns = [0] + [255] * (len(palette) - 1)  # index 0 is transparent
    rows = []
    for y in range(48):
        row = bytearray()
        for x in range(128):
            lx, floor = x % 64, x // 64
            idx = 0
            if in_diamond(lx, y, 32, 16, 32, 16):
                idx = (1 if (lx + y) % 7 else 2) if floor == 0 else (4 if (lx * 3 + y) % 11 else 6)
            elif y >= 16 and abs(lx + 0.5 - 32) <= 32 - max(0, y - 32) * 2 and y < 48 and in_diamond(lx, y - 16, 32, 16, 32, 16):
                idx = 3 if floor == 0 else 5
            row.append(idx)
        rows.append(bytes(row))
    write_png("floors_palette.png", 128, 48, 8, 3, rows, palette, trns)

    # 16-bit RGBA tree, 64x128: a round canopy on a thin trunk, soft edges.
    rows = []
    for y in range(128):
        row = bytearray()
        for x in range(64):
            r = g = b = a = 0
            dx, dy = x + 0.5 - 32, y + 0.5 - 40
            d = (dx * dx + dy * dy) ** 0.5
            if d < 26:
                edge = min(1.0, 26 - d)
                r, g, b, a = 0.2, 0.5 + 0.2 * (dy < 0), 0.15, edge
            elif abs(x + 0.5 - 32) < 4 and 60 <= y < 120:
                r, g, b, a = 0.45, 0.3, 0.15, 1.0
            for v in (r, g, b, a):
                row += struct.pack(">H", int(v * 65535 + 0.5))
        rows.append(bytes(row))
    write_png("tree_rgba16.png", 64, 128, 16, 6, rows)

    # 8-bit grey+alpha rock, 40x24: an ellipse.
    rows = []
    for y in range(24):
        row = bytearray()
        for x in range(40):
            ex, ey = (x + 0.5 - 20) / 18, (y + 0.5 - 14) / 9
            inside = ex * ex + ey * ey <= 1
            row += bytes([150 - y * 2 if inside else 0, 255 if inside else 0])
        rows.append(bytes(row))
    write_png("rock_grey_alpha.png", 40, 24, 8, 4, rows)

    # 16-bit grey post, 6x40: fully opaque (no alpha channel at all).
    rows = [b"".join(struct.pack(">H", 20000 + 1000 * x) for x in range(6)) for _ in range(40)]
    write_png("post_grey16.png", 6, 40, 16, 0, rows)


if __name__ == "__main__":
    main()
