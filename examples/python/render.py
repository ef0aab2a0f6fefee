#!/usr/bin/env python3
"""Renders a scene JSON or a Tiled map through libisolux with ctypes alone (the
standard library) and writes the final picture (and, when asked, the light
texture) as PAM images: what `isolux-cli render` writes, byte for byte.

Usage: render.py SCENE.json|MAP.tmx OUT.pam [LIGHT.pam]
The library: $ISOLUX_LIB, else the system's libisolux (ctypes.util).
"""
import ctypes
import ctypes.util
import os
import sys

API_VERSION = 2  # isolux.h's ISOLUX_API_VERSION


class Rect(ctypes.Structure):
    _fields_ = [("x", ctypes.c_int32), ("y", ctypes.c_int32), ("width", ctypes.c_int32), ("height", ctypes.c_int32)]


def load_library():
    path = os.environ.get("ISOLUX_LIB") or ctypes.util.find_library("isolux")
    if not path:
        sys.exit("render.py: libisolux not found: set ISOLUX_LIB to its path")
    lib = ctypes.CDLL(path)
    lib.isolux_api_version.restype = ctypes.c_int
    lib.isolux_last_error.restype = ctypes.c_char_p
    world_p = ctypes.POINTER(ctypes.c_void_p)
    for name in ("isolux_world_open_scene", "isolux_world_open_tmx"):
        getattr(lib, name).argtypes = [ctypes.c_char_p, world_p]
    lib.isolux_world_default_view.argtypes = [ctypes.c_void_p, ctypes.POINTER(Rect)]
    lib.isolux_world_render.argtypes = [ctypes.c_void_p, Rect, ctypes.c_int, ctypes.c_void_p, ctypes.c_size_t,
                                        ctypes.c_void_p, ctypes.c_size_t]
    lib.isolux_world_free.argtypes = [ctypes.c_void_p]
    lib.isolux_world_free.restype = None
    if lib.isolux_api_version() != API_VERSION:
        sys.exit(f"render.py: libisolux speaks API {lib.isolux_api_version()}, this script {API_VERSION}")
    return lib


def write_pam(path, data, w, h):
    with open(path, "wb") as f:
        f.write(f"P7\nWIDTH {w}\nHEIGHT {h}\nDEPTH 4\nMAXVAL 255\nTUPLTYPE RGB_ALPHA\nENDHDR\n".encode())
        f.write(data)


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: render.py SCENE.json|MAP.tmx OUT.pam [LIGHT.pam]")
    lib = load_library()

    def check(status, what):
        if status != 0:
            sys.exit(f"render.py: {what}: {lib.isolux_last_error().decode(errors='replace')}")

    path = sys.argv[1]
    world = ctypes.c_void_p()
    opener = lib.isolux_world_open_tmx if path.endswith(".tmx") else lib.isolux_world_open_scene
    check(opener(path.encode(), ctypes.byref(world)), "open")
    try:
        view = Rect()
        check(lib.isolux_world_default_view(world, ctypes.byref(view)), "view")
        size = view.width * view.height * 4
        rgba = ctypes.create_string_buffer(size)
        light = ctypes.create_string_buffer(size) if len(sys.argv) > 3 else None
        check(lib.isolux_world_render(world, view, 0, rgba, size, light, size if light else 0), "render")
        write_pam(sys.argv[2], rgba.raw, view.width, view.height)
        if light:
            write_pam(sys.argv[3], light.raw, view.width, view.height)
        print(f"rendered {path}: {view.width}x{view.height} at ({view.x}, {view.y})")
    finally:
        lib.isolux_world_free(world)


if __name__ == "__main__":
    main()
