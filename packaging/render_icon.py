#!/usr/bin/env python3
"""Renders packaging/motionstyle.svg to a square PNG (default 256 px) with the system's librsvg and
cairo through ctypes, so no converter program is needed (Debian 12 ships librsvg2-2 and libcairo2 with
the desktop stack). Usage: render_icon.py [SVG] [PNG] [SIZE]. The PNG is committed; rerun after editing
the SVG."""
import ctypes
import ctypes.util
import os
import sys


def load(name, soname):
    path = ctypes.util.find_library(name) or soname
    return ctypes.CDLL(path)


class RsvgRectangle(ctypes.Structure):
    _fields_ = [("x", ctypes.c_double), ("y", ctypes.c_double),
                ("width", ctypes.c_double), ("height", ctypes.c_double)]


def render(svg_path, png_path, size):
    rsvg = load("rsvg-2", "librsvg-2.so.2")
    cairo = load("cairo", "libcairo.so.2")
    rsvg.rsvg_handle_new_from_file.restype = ctypes.c_void_p
    rsvg.rsvg_handle_new_from_file.argtypes = [ctypes.c_char_p, ctypes.c_void_p]
    rsvg.rsvg_handle_render_document.argtypes = [ctypes.c_void_p, ctypes.c_void_p,
                                                 ctypes.POINTER(RsvgRectangle), ctypes.c_void_p]
    cairo.cairo_image_surface_create.restype = ctypes.c_void_p
    cairo.cairo_image_surface_create.argtypes = [ctypes.c_int, ctypes.c_int, ctypes.c_int]
    cairo.cairo_create.restype = ctypes.c_void_p
    cairo.cairo_create.argtypes = [ctypes.c_void_p]
    cairo.cairo_surface_write_to_png.argtypes = [ctypes.c_void_p, ctypes.c_char_p]
    cairo.cairo_surface_write_to_png.restype = ctypes.c_int
    cairo.cairo_destroy.argtypes = [ctypes.c_void_p]
    cairo.cairo_surface_destroy.argtypes = [ctypes.c_void_p]

    handle = rsvg.rsvg_handle_new_from_file(os.fsencode(svg_path), None)
    if not handle:
        sys.exit(f"render_icon: librsvg could not read {svg_path}")
    surface = cairo.cairo_image_surface_create(0, size, size)  # CAIRO_FORMAT_ARGB32
    context = cairo.cairo_create(surface)
    viewport = RsvgRectangle(0, 0, size, size)
    if not rsvg.rsvg_handle_render_document(handle, context, ctypes.byref(viewport), None):
        sys.exit(f"render_icon: librsvg could not render {svg_path}")
    tmp = png_path + ".tmp"
    if cairo.cairo_surface_write_to_png(surface, os.fsencode(tmp)) != 0:
        sys.exit(f"render_icon: could not write {png_path}")
    os.replace(tmp, png_path)  # atomic: a failed run never leaves a half-written icon
    cairo.cairo_destroy(context)
    cairo.cairo_surface_destroy(surface)


if __name__ == "__main__":
    here = os.path.dirname(os.path.abspath(__file__))
    svg = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "motionstyle.svg")
    png = sys.argv[2] if len(sys.argv) > 2 else os.path.join(here, "motionstyle.png")
    size = int(sys.argv[3]) if len(sys.argv) > 3 else 256
    render(svg, png, size)
    print(f"render_icon: wrote {png} ({size}x{size})")
