#!/usr/bin/env python3
"""Generates viqu's textures (assets/*.png) with the Python standard library only.

The robot's camera sits about 7 cm above the floor and its SLAM front end finds ORB/FAST corners,
so every texture carries corners at many scales: random overlapping rectangles, blobs, text-like
marks and speckles, never a pure periodic pattern. Every image comes from a seeded generator, so
running this script again reproduces the committed files byte for byte.

Usage: python3 tools/make_textures.py [OUTPUT_DIR]   (default: assets/ beside this folder)
"""
import os
import random
import struct
import sys
import zlib


class Canvas:
    """An RGB image in a bytearray, with a few drawing primitives that wrap around the edges
    (so that textures tile without visible seams)."""

    def __init__(self, width, height, color):
        self.w = width
        self.h = height
        self.px = bytearray(bytes(color) * (width * height))

    def _span(self, y, x0, x1, color):
        """Fills row y (wrapped) from x0 to x1 (exclusive, wrapped)."""
        y %= self.h
        length = x1 - x0
        if length <= 0:
            return
        if length >= self.w:
            x0, length = 0, self.w
        x0 %= self.w
        first = min(length, self.w - x0)
        row = y * self.w
        self.px[3 * (row + x0):3 * (row + x0 + first)] = bytes(color) * first
        if length > first:
            rest = length - first
            self.px[3 * row:3 * (row + rest)] = bytes(color) * rest

    def rect(self, x0, y0, x1, y1, color):
        for y in range(y0, y1):
            self._span(y, x0, x1, color)

    def frame(self, x0, y0, x1, y1, t, color):
        self.rect(x0, y0, x1, y0 + t, color)
        self.rect(x0, y1 - t, x1, y1, color)
        self.rect(x0, y0, x0 + t, y1, color)
        self.rect(x1 - t, y0, x1, y1, color)

    def ellipse(self, cx, cy, rx, ry, color):
        ry = max(ry, 1)
        for dy in range(-ry, ry + 1):
            f = 1.0 - (dy / ry) ** 2
            if f < 0:
                continue
            half = int(rx * f ** 0.5 + 0.5)
            self._span(cy + dy, cx - half, cx + half + 1, color)

    def get(self, x, y):
        i = 3 * ((y % self.h) * self.w + (x % self.w))
        return self.px[i], self.px[i + 1], self.px[i + 2]

    def put(self, x, y, color):
        i = 3 * ((y % self.h) * self.w + (x % self.w))
        self.px[i:i + 3] = bytes(color)

    def png(self):
        raw = bytearray()
        stride = 3 * self.w
        for y in range(self.h):
            raw.append(0)  # filter: none
            raw += self.px[y * stride:(y + 1) * stride]

        def chunk(kind, data):
            body = kind + data
            return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

        header = struct.pack(">IIBBBBB", self.w, self.h, 8, 2, 0, 0, 0)
        return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
                chunk(b"IDAT", zlib.compress(bytes(raw), 9)) + chunk(b"IEND", b""))


def clamp(v):
    return max(0, min(255, int(v)))


def shade(color, k):
    return tuple(clamp(c * k) for c in color)


def jitter(rng, color, amount):
    return tuple(clamp(c + rng.randint(-amount, amount)) for c in color)


# ---------------------------------------------------------------- reusable marks
def speckles(c, rng, count, rmin, rmax, palette):
    for _ in range(count):
        r = rng.randint(rmin, rmax)
        c.ellipse(rng.randrange(c.w), rng.randrange(c.h), r + rng.randint(0, 1), r,
                  rng.choice(palette))


def chips(c, rng, count, smin, smax, palette):
    """Small irregular polygons made of 2-3 overlapping rectangles: corner-rich speckle."""
    for _ in range(count):
        x, y = rng.randrange(c.w), rng.randrange(c.h)
        col = rng.choice(palette)
        for _ in range(rng.randint(2, 3)):
            w, h = rng.randint(smin, smax), rng.randint(smin, smax)
            dx, dy = rng.randint(-smax // 2, smax // 2), rng.randint(-smax // 2, smax // 2)
            c.rect(x + dx, y + dy, x + dx + w, y + dy + h, col)


def text_line(c, rng, x, y, height, length, color):
    """A line of pseudo-text: glyphs made from a random 3x5 bit pattern of blocks."""
    cell = max(1, height // 5)
    gx = x
    while gx < x + length:
        if rng.random() < 0.15:  # word gap
            gx += 3 * cell
            continue
        bits = rng.getrandbits(15) | 0b100000000000001
        for i in range(15):
            if bits >> i & 1:
                bx, by = i % 3, i // 3
                c.rect(gx + bx * cell, y + by * cell, gx + (bx + 1) * cell, y + (by + 1) * cell,
                       color)
        gx += 4 * cell


def barcode(c, rng, x, y, w, h, color):
    gx = x
    while gx < x + w:
        bw = rng.randint(1, 3)
        if rng.random() < 0.55:
            c.rect(gx, y, gx + bw, y + h, color)
        gx += bw


def logo(c, rng, cx, cy, r, fg, bg):
    c.ellipse(cx, cy, r, r, fg)
    c.ellipse(cx, cy, r * 2 // 3, r * 2 // 3, bg)
    c.rect(cx - r // 4, cy - r, cx + r // 4, cy + r // 3, fg)
    c.rect(cx - r, cy + r // 3, cx + r // 2, cy + r // 2 + 2, fg)


def poster(c, rng, x, y, w, h):
    bg = rng.choice([(240, 236, 220), (30, 40, 70), (200, 60, 50), (250, 200, 60),
                     (70, 140, 90), (235, 235, 240), (20, 20, 24)])
    ink = (20, 20, 20) if sum(bg) > 380 else (240, 240, 235)
    c.rect(x, y, x + w, y + h, bg)
    c.frame(x, y, x + w, y + h, max(2, w // 60), shade(bg, 0.5))
    # picture area: overlapping rectangles and blobs at several scales
    ph = h * rng.randint(35, 60) // 100
    for _ in range(rng.randint(6, 14)):
        rw, rh = rng.randint(w // 12, w // 2), rng.randint(ph // 10, ph // 2)
        rx, ry = x + rng.randint(4, max(5, w - rw - 4)), y + rng.randint(4, max(5, ph - rh))
        col = (rng.randrange(256), rng.randrange(256), rng.randrange(256))
        if rng.random() < 0.5:
            c.rect(rx, ry, rx + rw, ry + rh, col)
        else:
            c.ellipse(rx + rw // 2, ry + rh // 2, rw // 2, rh // 2, col)
    # text block
    ty = y + ph + 8
    size = rng.randint(10, 20)
    text_line(c, rng, x + 8, ty, size, w - 24, ink)
    ty += size + 8
    while ty + 8 < y + h - 8:
        lh = rng.randint(5, 9)
        text_line(c, rng, x + 8, ty, lh, rng.randint(w // 3, w - 20), ink)
        ty += lh + rng.randint(4, 8)


# ---------------------------------------------------------------- textures
def floor_wood(rng, size=1024):
    """Wooden planks of random lengths, grain lines, knots, scuffs and scattered grit."""
    c = Canvas(size, size, (150, 105, 60))
    area = (size // 512) ** 2
    plank_h = 64
    for row in range(size // plank_h):
        y0 = row * plank_h
        x = rng.randrange(size)
        start = x
        while x < start + size:
            length = rng.randint(size // 4, size * 3 // 4)
            length = min(length, start + size - x)
            base = jitter(rng, rng.choice([(168, 118, 70), (128, 84, 46), (186, 140, 88),
                                           (110, 72, 40), (150, 100, 58)]), 14)
            c.rect(x, y0, x + length, y0 + plank_h, base)
            for _ in range(rng.randint(4, 9)):  # grain
                gy = y0 + rng.randint(2, plank_h - 3)
                gx = x + rng.randint(0, length // 3)
                gl = rng.randint(length // 4, length)
                c.rect(gx, gy, min(gx + gl, x + length), gy + rng.randint(1, 2), shade(base, 0.72))
            for _ in range(rng.randint(0, 2)):  # knots
                kx, ky = x + rng.randint(8, max(9, length - 8)), y0 + rng.randint(6, plank_h - 6)
                c.ellipse(kx, ky, rng.randint(5, 10), rng.randint(3, 5), shade(base, 0.55))
                c.ellipse(kx, ky, 2, 1, shade(base, 0.3))
            c.rect(x, y0, x + 2, y0 + plank_h, (50, 32, 18))  # butt joint
            x += length
        c.rect(0, y0, size, y0 + 2, (45, 28, 15))  # seam between plank rows
    chips(c, rng, 700 * area, 1, 4, [(35, 25, 20), (230, 220, 200), (20, 20, 20), (90, 90, 95)])
    speckles(c, rng, 80 * area, 3, 9, [(70, 50, 35), (210, 190, 160), (40, 60, 90)])
    return c


def terrazzo(rng, base, palette, size=1024, count=10400):
    c = Canvas(size, size, base)
    chips(c, rng, count, 2, 9, palette)
    speckles(c, rng, count // 3, 1, 3, palette)
    return c


def wall_posters(rng, size=1024):
    """Painted wall with blotches, overlapping posters, notes and scribbles at several scales."""
    c = Canvas(size, size, (205, 198, 182))
    area = (size // 512) ** 2
    for _ in range(40 * area):  # large faint blotches
        c.ellipse(rng.randrange(size), rng.randrange(size), rng.randint(20, 70),
                  rng.randint(15, 50), jitter(rng, (195, 188, 170), 18))
    for _ in range(9 * area):
        w, h = rng.randint(90, 200), rng.randint(110, 230)
        poster(c, rng, rng.randrange(size), rng.randrange(size), w, h)
    for _ in range(40 * area):  # sticky notes and small cards
        w, h = rng.randint(12, 40), rng.randint(12, 40)
        x, y = rng.randrange(size), rng.randrange(size)
        col = rng.choice([(250, 230, 90), (120, 200, 240), (250, 140, 160), (255, 255, 255)])
        c.rect(x, y, x + w, y + h, col)
        text_line(c, rng, x + 2, y + 3, 5, w - 6, (30, 30, 60))
    chips(c, rng, 500 * area, 1, 4, [(60, 55, 50), (20, 20, 20), (240, 240, 240), (150, 40, 40)])
    return c


def brick(rng, size=1024):
    """Irregular brick bond: bricks of varying length and colour, dark mortar, chipped corners."""
    c = Canvas(size, size, (70, 66, 62))
    area = (size // 512) ** 2
    bh = 32
    for row in range(size // bh):
        y0 = row * bh
        x = rng.randrange(size)
        start = x
        while x < start + size:
            length = min(rng.randint(bh * 2, bh * 4), start + size - x)
            col = jitter(rng, rng.choice([(150, 60, 45), (175, 85, 60), (120, 50, 40),
                                          (190, 120, 90), (100, 45, 35)]), 18)
            c.rect(x + 3, y0 + 3, x + length - 2, y0 + bh - 2, col)
            for _ in range(rng.randint(2, 6)):
                sx, sy = x + rng.randint(4, max(5, length - 6)), y0 + rng.randint(4, bh - 5)
                c.rect(sx, sy, sx + rng.randint(2, 6), sy + rng.randint(1, 4), shade(col, 0.6))
            x += length
    chips(c, rng, 400 * area, 1, 3, [(40, 38, 36), (220, 210, 200), (90, 30, 25)])
    for _ in range(3 * area):
        w, h = rng.randint(80, 150), rng.randint(100, 180)
        poster(c, rng, rng.randrange(size), rng.randrange(size), w, h)
    return c


def wood_grain(rng, size=512):
    """Furniture wood: long wavy grain lines, knots, dents and a few stickers."""
    base = (165, 112, 62)
    c = Canvas(size, size, base)
    for _ in range(260):
        y = rng.randrange(size)
        x = rng.randrange(size)
        length = rng.randint(size // 6, size)
        col = shade(jitter(rng, base, 20), rng.uniform(0.55, 1.15))
        thick = rng.randint(1, 3)
        step = rng.randint(20, 60)
        pos = 0
        while pos < length:
            seg = min(step, length - pos)
            c.rect(x + pos, y, x + pos + seg, y + thick, col)
            y += rng.choice([-1, 0, 0, 1])
            pos += seg
    for _ in range(14):
        kx, ky = rng.randrange(size), rng.randrange(size)
        rx, ry = rng.randint(8, 18), rng.randint(4, 9)
        for k in range(4, 0, -1):
            c.ellipse(kx, ky, rx * k // 4, ry * k // 4, shade(base, 0.35 + 0.12 * k))
    chips(c, rng, 500, 1, 4, [(60, 40, 25), (220, 190, 150), (30, 20, 15)])
    for _ in range(6):  # stickers / labels
        w, h = rng.randint(20, 60), rng.randint(14, 36)
        x, y = rng.randrange(size), rng.randrange(size)
        c.rect(x, y, x + w, y + h, (240, 240, 230))
        text_line(c, rng, x + 3, y + 3, 6, w - 6, (20, 20, 80))
    return c


def cardboard(rng, size=512):
    """Corrugated cardboard with tape, printed labels, logos, barcodes and arrows."""
    base = (190, 150, 100)
    c = Canvas(size, size, base)
    for _ in range(60):  # stains
        c.ellipse(rng.randrange(size), rng.randrange(size), rng.randint(10, 40),
                  rng.randint(6, 25), jitter(rng, (175, 135, 88), 12))
    for x in range(0, size, 7):  # faint corrugation, irregular
        if rng.random() < 0.6:
            c.rect(x, 0, x + 1, size, (176, 138, 92))
    tape = rng.randint(size // 3, size // 2)
    c.rect(tape, 0, tape + 40, size, (205, 175, 120))
    for _ in range(6):  # labels
        w, h = rng.randint(70, 150), rng.randint(45, 100)
        x, y = rng.randrange(size), rng.randrange(size)
        c.rect(x, y, x + w, y + h, (245, 245, 240))
        c.frame(x, y, x + w, y + h, 2, (20, 20, 20))
        text_line(c, rng, x + 6, y + 6, 10, w - 14, (10, 10, 10))
        text_line(c, rng, x + 6, y + 22, 6, w - 20, (10, 10, 10))
        barcode(c, rng, x + 6, y + h - 24, w // 2, 18, (0, 0, 0))
    for _ in range(5):
        r = rng.randint(18, 40)
        col = rng.choice([(30, 30, 30), (160, 30, 30), (30, 60, 140)])
        logo(c, rng, rng.randrange(size), rng.randrange(size), r, col, base)
    for _ in range(8):  # printed handling text
        text_line(c, rng, rng.randrange(size), rng.randrange(size), rng.randint(8, 22),
                  rng.randint(60, 200), (40, 30, 25))
    chips(c, rng, 300, 1, 3, [(90, 70, 45), (240, 230, 210)])
    return c


def shirt(rng, size=256):
    """Irregular plaid with random stripe widths and colours, buttons, pocket and a print."""
    base = jitter(rng, (60, 90, 160), 20)
    c = Canvas(size, size, base)
    x = 0
    while x < size:
        w = rng.randint(3, 22)
        col = rng.choice([(230, 230, 225), (200, 40, 40), (20, 30, 60), (240, 200, 70)])
        if rng.random() < 0.55:
            c.rect(x, 0, x + w, size, col)
        x += w + rng.randint(4, 30)
    y = 0
    while y < size:
        h = rng.randint(3, 20)
        col = rng.choice([(20, 20, 20), (250, 250, 250), (40, 140, 60), (150, 30, 120)])
        if rng.random() < 0.55:
            c.rect(0, y, size, y + h, col)
        y += h + rng.randint(4, 30)
    speckles(c, rng, 120, 2, 5, [(250, 250, 250), (10, 10, 10), (250, 220, 40)])
    for _ in range(3):
        poster(c, rng, rng.randrange(size), rng.randrange(size), rng.randint(40, 80),
               rng.randint(40, 80))
    return c


def trousers(rng, size=256):
    """Denim: dark blue with diagonal weave marks, seams, patches and rivets."""
    base = (40, 55, 95)
    c = Canvas(size, size, base)
    for _ in range(1800):
        x, y = rng.randrange(size), rng.randrange(size)
        for k in range(rng.randint(2, 5)):
            c.put(x + k, y + k, jitter(rng, (80, 100, 150), 25))
    for _ in range(6):  # seams
        x = rng.randrange(size)
        c.rect(x, 0, x + 2, size, (200, 160, 70))
    for _ in range(7):  # patches and pockets
        w, h = rng.randint(20, 60), rng.randint(20, 60)
        x, y = rng.randrange(size), rng.randrange(size)
        col = rng.choice([(120, 140, 190), (20, 25, 45), (150, 110, 70), (200, 200, 210)])
        c.rect(x, y, x + w, y + h, col)
        c.frame(x, y, x + w, y + h, 2, (210, 170, 80))
    speckles(c, rng, 60, 2, 3, [(220, 190, 80), (230, 230, 230)])
    return c


def skin(rng, size=128):
    c = Canvas(size, size, (215, 170, 140))
    speckles(c, rng, 120, 1, 4, [(180, 130, 100), (235, 195, 170), (120, 80, 60)])
    return c


def dark_tile(rng, size=256):
    """Shiny dark tiles of uneven size with light flecks: the slippery patch."""
    c = Canvas(size, size, (20, 22, 28))
    y = 0
    while y < size:
        h = rng.randint(30, 70)
        x = rng.randrange(size)
        start = x
        while x < start + size:
            w = min(rng.randint(30, 80), start + size - x)
            c.rect(x + 2, y + 2, x + w - 2, min(y + h, size) - 2,
                   jitter(rng, (45, 50, 60), 15))
            x += w
        y += h
    chips(c, rng, 500, 1, 4, [(200, 200, 210), (120, 130, 150), (250, 250, 250), (10, 10, 10)])
    return c


def rug(rng, size=256):
    """A patterned rug: nested frames, random motifs and speckle."""
    c = Canvas(size, size, (130, 30, 35))
    for k in range(5):
        m = 6 + k * 14
        c.frame(m, m, size - m, size - m, 4, rng.choice([(220, 180, 90), (20, 30, 60),
                                                         (240, 230, 210)]))
    for _ in range(40):
        r = rng.randint(4, 16)
        col = rng.choice([(220, 180, 90), (20, 30, 60), (240, 230, 210), (40, 110, 80)])
        if rng.random() < 0.5:
            c.ellipse(rng.randint(80, size - 80), rng.randint(80, size - 80), r, r, col)
        else:
            x, y = rng.randint(80, size - 80), rng.randint(80, size - 80)
            c.rect(x - r, y - r // 2, x + r, y + r // 2, col)
    chips(c, rng, 300, 1, 3, [(250, 240, 220), (10, 10, 10)])
    return c


TEXTURES = {
    "floor_wood": floor_wood,
    "floor_terrazzo": lambda rng: terrazzo(
        rng, (175, 170, 160),
        [(40, 40, 45), (230, 225, 215), (150, 60, 40), (60, 90, 120), (100, 95, 90)]),
    "wall_posters": wall_posters,
    "brick": brick,
    "wood": wood_grain,
    "cardboard": cardboard,
    "shirt": shirt,
    "trousers": trousers,
    "skin": skin,
    "dark_tile": dark_tile,
    "rug": rug,
}


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "assets")
    os.makedirs(out_dir, exist_ok=True)
    total = 0
    for index, (name, make) in enumerate(sorted(TEXTURES.items())):
        rng = random.Random(20240 + index * 7919)  # one fixed seed per texture
        data = make(rng).png()
        path = os.path.join(out_dir, name + ".png")
        with open(path + ".tmp", "wb") as f:
            f.write(data)
        os.replace(path + ".tmp", path)
        total += len(data)
        print(f"{path}: {len(data)} bytes")
    print(f"total {total} bytes")


if __name__ == "__main__":
    main()
