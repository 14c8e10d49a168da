#!/usr/bin/env python3
"""Writes viqu's indoor worlds (room.xml, room_blank_wall.xml, corridor.xml, room_large.xml) as MJCF pieces.

Edit the layouts here, not the XML. Every world is an MJCF piece for the scene composer
(<asset> + <worldbody>, no <compiler>/<option>/<visual>), with a floor plane named `floor`, at
most two lights without shadows (software rendering), walls and furniture that carry texture
down to floor level (the robot's camera is about 7 cm above the floor), and furniture as bodies
named `furniture:NAME` so that segmentation labels them (docs/CONVENTIONS.md).

Texture mapping in MuJoCo 2.2.2: a 2D texture on a box is projected along the box's local z, so
walls and panels are boxes whose local z is their thin dimension (texuniform: texrepeat/2 tiles
per metre). Furniture uses cube textures, which map the image onto every face of a box.

Usage: python3 models/worlds/make_worlds.py   (writes beside this script; seeded, reproducible)
"""
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))
ASSETS = "../../assets/"


def f(v):
    return ("%.4f" % v).rstrip("0").rstrip(".") if v != 0 else "0"


def vec(*v):
    return " ".join(f(x) for x in v)


class World:
    def __init__(self, name, seed):
        self.name = name
        self.rng = random.Random(seed)
        self.assets = []
        self.body = []   # worldbody lines
        self.count = 0

    # ------------------------------------------------------------------ assets
    def texture2d(self, mat, png, repeat, **extra):
        self.assets.append(f'  <texture name="{self.name}_{mat}" type="2d" file="{ASSETS}{png}.png"/>')
        attrs = " ".join(f'{k}="{v}"' for k, v in extra.items())
        self.assets.append(f'  <material name="{self.name}_{mat}" texture="{self.name}_{mat}" '
                           f'texrepeat="{f(repeat)} {f(repeat)}" texuniform="true" {attrs}/>')

    def texture_cube(self, mat, png, **extra):
        self.assets.append(f'  <texture name="{self.name}_{mat}" type="cube" file="{ASSETS}{png}.png"/>')
        attrs = " ".join(f'{k}="{v}"' for k, v in extra.items())
        self.assets.append(f'  <material name="{self.name}_{mat}" texture="{self.name}_{mat}" {attrs}/>')

    def mat(self, m):
        return f'material="{self.name}_{m}"'

    # ------------------------------------------------------------------ geometry
    def geom_box(self, out, pos, half, look, xyaxes=None, indent="    "):
        """look: a material name or an 'r g b' colour string."""
        attr = self.mat(look) if not look[0].isdigit() else f'rgba="{look} 1"'
        orient = f' xyaxes="{vec(*xyaxes)}"' if xyaxes else ""
        out.append(f'{indent}<geom type="box" pos="{vec(*pos)}" size="{vec(*half)}"{orient} {attr}/>')

    def panel(self, out, x0, y0, x1, y1, z0, z1, thick, look, indent="    "):
        """A vertical slab from (x0, y0) to (x1, y1), floor heights z0..z1, whose textured face is
        the local x-y plane (local z = horizontal normal)."""
        dx, dy = x1 - x0, y1 - y0
        length = math.hypot(dx, dy)
        ux, uy = dx / length, dy / length
        self.geom_box(out, ((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2),
                      (length / 2, (z1 - z0) / 2, thick / 2), look, (ux, uy, 0, 0, 0, 1), indent)

    def wall(self, x0, y0, x1, y1, height, look, thick=0.1):
        self.panel(self.body, x0, y0, x1, y1, 0, height, thick, look)

    def furniture(self, name, x, y, yaw_deg, parts):
        """parts: list of (pos, half, look) in the body frame (box geoms)."""
        q = math.radians(yaw_deg) / 2
        lines = [f'    <body name="furniture:{name}" pos="{vec(x, y, 0)}" '
                 f'quat="{vec(math.cos(q), 0, 0, math.sin(q))}">']
        for pos, half, look in parts:
            self.geom_box(lines, pos, half, look, indent="      ")
        lines.append("    </body>")
        self.body += lines

    # ------------------------------------------------------------------ furniture pieces
    def table(self, name, x, y, yaw, w=1.2, d=0.7, h=0.74, look="wood"):
        t = 0.035
        parts = [((0, 0, h - t / 2), (w / 2, d / 2, t / 2), look),
                 ((0, d / 2 - 0.05, h - t - 0.05), (w / 2 - 0.06, 0.015, 0.05), look),
                 ((0, -d / 2 + 0.05, h - t - 0.05), (w / 2 - 0.06, 0.015, 0.05), look)]
        for sx in (-1, 1):
            for sy in (-1, 1):
                parts.append(((sx * (w / 2 - 0.05), sy * (d / 2 - 0.05), (h - t) / 2),
                              (0.025, 0.025, (h - t) / 2), "0.25 0.2 0.16"))
        self.furniture(name, x, y, yaw, parts)

    def chair(self, name, x, y, yaw, look="wood"):
        s, h = 0.44, 0.45
        parts = [((0, 0, h), (s / 2, s / 2, 0.02), look),
                 ((-s / 2 + 0.02, 0, h + 0.25), (0.02, s / 2, 0.2), look),
                 ((0, 0, 0.12), (s / 2 - 0.03, 0.012, 0.012), "0.15 0.15 0.18")]
        for sx in (-1, 1):
            for sy in (-1, 1):
                parts.append(((sx * (s / 2 - 0.03), sy * (s / 2 - 0.03), h / 2),
                              (0.018, 0.018, h / 2), "0.15 0.15 0.18"))
        self.furniture(name, x, y, yaw, parts)

    def shelf(self, name, x, y, yaw, w=1.4, d=0.35, h=1.8, levels=5, look="wood"):
        """Open bookshelf; its back faces -x in the body frame. Books and boxes on every level,
        including one just above the floor."""
        parts = [((-d / 2 + 0.01, 0, h / 2), (0.01, w / 2, h / 2), "0.85 0.82 0.75")]
        for sy in (-1, 1):
            parts.append(((0, sy * (w / 2 - 0.01), h / 2), (d / 2, 0.01, h / 2), look))
        zs = [0.04 + i * (h - 0.06) / (levels - 1) for i in range(levels)]
        for z in zs:
            parts.append(((0, 0, z), (d / 2, w / 2 - 0.02, 0.012), look))
        for z in zs[:-1]:
            yy = -w / 2 + 0.04
            while yy < w / 2 - 0.08:
                bw = self.rng.uniform(0.02, 0.06)
                bh = self.rng.uniform(0.14, 0.26)
                bd = self.rng.uniform(0.16, d - 0.05)
                if self.rng.random() < 0.15:  # a gap, or a box of files
                    if self.rng.random() < 0.5:
                        yy += self.rng.uniform(0.04, 0.12)
                        continue
                    bw, bh = self.rng.uniform(0.15, 0.25), self.rng.uniform(0.1, 0.2)
                    parts.append(((d / 2 - bd / 2 - 0.01, yy + bw / 2, z + 0.012 + bh / 2),
                                  (bd / 2, bw / 2, bh / 2), "cardboard"))
                else:
                    col = vec(*[self.rng.uniform(0.05, 0.95) for _ in range(3)])
                    parts.append(((d / 2 - bd / 2 - 0.01, yy + bw / 2, z + 0.012 + bh / 2),
                                  (bd / 2, bw / 2, bh / 2), col))
                yy += bw + 0.004
        self.furniture(name, x, y, yaw, parts)

    def cabinet(self, name, x, y, yaw, w=0.9, d=0.45, h=0.75, drawers=3, look="wood"):
        """Chest of drawers; its front faces +x in the body frame."""
        parts = [((0, 0, h / 2 + 0.04), (d / 2, w / 2, h / 2 - 0.04), look),
                 ((0, 0, 0.02), (d / 2 - 0.03, w / 2 - 0.03, 0.02), "0.1 0.08 0.06")]
        dh = (h - 0.08) / drawers
        for i in range(drawers):
            zc = 0.06 + dh * (i + 0.5)
            parts.append(((d / 2 + 0.008, 0, zc), (0.008, w / 2 - 0.03, dh / 2 - 0.012),
                          "0.82 0.78 0.7"))
            parts.append(((d / 2 + 0.022, 0, zc), (0.008, 0.08, 0.012), "0.1 0.1 0.1"))
        self.furniture(name, x, y, yaw, parts)

    def crates(self, name, x, y, yaw, n=4):
        """A loose stack of cardboard boxes of random sizes."""
        parts = []
        yy = 0.0
        for _ in range(n):
            sx, sy, sz = (self.rng.uniform(0.2, 0.4), self.rng.uniform(0.25, 0.45),
                          self.rng.uniform(0.18, 0.4))
            parts.append(((self.rng.uniform(-0.03, 0.03), yy + sy / 2, sz / 2),
                          (sx / 2, sy / 2, sz / 2), "cardboard"))
            if self.rng.random() < 0.6:
                tx, ty, tz = sx * 0.8, sy * 0.7, self.rng.uniform(0.12, 0.25)
                parts.append(((0, yy + sy / 2 + self.rng.uniform(-0.05, 0.05), sz + tz / 2),
                              (tx / 2, ty / 2, tz / 2), "cardboard"))
            yy += sy + self.rng.uniform(0.0, 0.08)
        parts = [((p[0], p[1] - yy / 2, p[2]), h, l) for p, h, l in parts]
        self.furniture(name, x, y, yaw, parts)

    def radiator(self, name, x, y, yaw, w=1.0, h=0.6):
        """Ribbed radiator on feet, front faces +x."""
        parts = [((0, 0, 0.12 + h / 2), (0.03, w / 2, h / 2), "0.92 0.92 0.9")]
        n = int(w / 0.05)
        for i in range(n):
            parts.append(((0.035, -w / 2 + (i + 0.5) * w / n, 0.12 + h / 2),
                          (0.008, 0.008, h / 2 - 0.03), "0.6 0.6 0.62"))
        for sy in (-1, 1):
            parts.append(((0, sy * (w / 2 - 0.08), 0.06), (0.03, 0.02, 0.06), "0.3 0.3 0.3"))
        parts.append(((0.05, w / 2 - 0.05, 0.09), (0.02, 0.02, 0.02), "0.8 0.1 0.1"))
        self.furniture(name, x, y, yaw, parts)

    def bench(self, name, x, y, yaw, w=1.4, look="wood"):
        parts = [((0, 0, 0.44), (0.18, w / 2, 0.025), look),
                 ((0, 0, 0.12), (0.15, w / 2 - 0.1, 0.01), look)]
        for sy in (-1, 1):
            parts.append(((0, sy * (w / 2 - 0.1), 0.21), (0.16, 0.03, 0.21), "0.2 0.2 0.22"))
        for i in range(int(w / 0.3)):  # shoes and bags under the bench
            col = vec(*[self.rng.uniform(0.05, 0.9) for _ in range(3)])
            parts.append(((self.rng.uniform(-0.05, 0.05), -w / 2 + 0.2 + i * 0.3, 0.05),
                          (0.13, 0.05, 0.05), col))
        self.furniture(name, x, y, yaw, parts)

    def bin(self, name, x, y):
        self.body += [f'    <body name="furniture:{name}" pos="{vec(x, y, 0)}">',
                      f'      <geom type="cylinder" size="0.16 0.22" pos="0 0 0.22" {self.mat("cardboard")}/>',
                      '      <geom type="cylinder" size="0.17 0.015" pos="0 0 0.44" rgba="0.1 0.3 0.15 1"/>',
                      '    </body>']

    def plant(self, name, x, y):
        lines = [f'    <body name="furniture:{name}" pos="{vec(x, y, 0)}">',
                 f'      <geom type="cylinder" size="0.16 0.17" pos="0 0 0.17" {self.mat("brick")}/>']
        for _ in range(9):
            lines.append(f'      <geom type="ellipsoid" size="{vec(0.12, 0.06, 0.2)}" '
                         f'pos="{vec(self.rng.uniform(-.1, .1), self.rng.uniform(-.1, .1), self.rng.uniform(0.45, 0.8))}" '
                         f'euler="{vec(self.rng.uniform(-40, 40), self.rng.uniform(-40, 40), self.rng.uniform(0, 180))}" '
                         f'rgba="{vec(0.1, self.rng.uniform(0.3, 0.6), 0.1)} 1"/>')
        lines.append('    </body>')
        self.body += lines

    def door(self, name, x0, y0, x1, y1, inward):
        """A door in a wall line (x0, y0)-(x1, y1): panel, frame and handle, `inward` the unit
        normal pointing into the room (m). The door stands just in front of the wall."""
        nx, ny = inward
        lines = [f'    <body name="furniture:{name}">']
        off = lambda d: (nx * d, ny * d)  # noqa: E731
        o = off(0.05)
        self.panel(lines, x0 + o[0], y0 + o[1], x1 + o[0], y1 + o[1], 0.01, 2.05, 0.04, "door",
                   indent="      ")
        dx, dy = x1 - x0, y1 - y0
        length = math.hypot(dx, dy)
        ux, uy = dx / length, dy / length
        o = off(0.07)
        for s in (-0.04, length + 0.04):  # frame posts
            cx, cy = x0 + ux * s + o[0], y0 + uy * s + o[1]
            self.panel(lines, cx - ux * 0.04, cy - uy * 0.04, cx + ux * 0.04, cy + uy * 0.04,
                       0, 2.12, 0.08, "0.9 0.9 0.88", indent="      ")
        self.panel(lines, x0 - ux * 0.08 + o[0], y0 - uy * 0.08 + o[1], x1 + ux * 0.08 + o[0],
                   y1 + uy * 0.08 + o[1], 2.05, 2.13, 0.08, "0.9 0.9 0.88", indent="      ")
        # kick plate and handle
        o = off(0.075)
        self.panel(lines, x0 + ux * 0.05 + o[0], y0 + uy * 0.05 + o[1], x1 - ux * 0.05 + o[0],
                   y1 - uy * 0.05 + o[1], 0.02, 0.22, 0.006, "0.7 0.7 0.72", indent="      ")
        hx, hy = x0 + ux * (length - 0.12) + nx * 0.1, y0 + uy * (length - 0.12) + ny * 0.1
        lines.append(f'      <geom type="box" pos="{vec(hx, hy, 1.0)}" size="0.06 0.06 0.012" '
                     f'rgba="0.15 0.15 0.15 1"/>')
        lines.append("    </body>")
        self.body += lines

    # ------------------------------------------------------------------ output
    def common_assets(self, floor_png, floor_repeat):
        self.texture2d("floor", floor_png, floor_repeat)
        self.texture2d("wall", "wall_posters", 0.8)
        self.texture2d("brick", "brick", 1.0)
        self.texture2d("door", "wood", 1.2)
        self.texture2d("rug", "rug", 1.0)
        self.texture_cube("wood", "wood")
        self.texture_cube("cardboard", "cardboard")

    def write(self, filename, comment, floor_half, lights, floor_centre=(0.0, 0.0)):
        """floor_half, floor_centre: the floor plane's half-size and centre (m). MuJoCo collides
        with a plane everywhere but draws it only over its size, so it must cover the walls."""
        hx, hy = floor_half
        cx, cy = floor_centre
        lines = [f"<!-- {comment}", "     Generated by make_worlds.py: edit the layout there, not here. -->",
                 "<mujoco>", "  <asset>"] + self.assets + ["  </asset>", "  <worldbody>"]
        for i, (pos, diffuse) in enumerate(lights):
            lines.append(f'    <light name="{self.name}_light{i}" pos="{vec(*pos)}" dir="0 0 -1" '
                         f'directional="false" cutoff="90" exponent="0" castshadow="false" diffuse="{vec(diffuse, diffuse, diffuse)}" '
                         f'ambient="0.25 0.25 0.25" specular="0.1 0.1 0.1" attenuation="1 0 0"/>')
        centre = f'pos="{vec(cx, cy, 0)}" ' if (cx, cy) != (0.0, 0.0) else ""
        lines.append(f'    <geom name="floor" type="plane" {centre}size="{vec(hx, hy, 0.1)}" '
                     f'{self.mat("floor")} friction="1 0.005 0.0001"/>')
        lines += self.body + ["  </worldbody>", "</mujoco>", ""]
        with open(os.path.join(HERE, filename), "w") as out:
            out.write("\n".join(lines))


def rug(w, x, y, sx, sy):
    """A thin rug, 3 mm high: keep it off the robot's paths."""
    w.geom_box(w.body, (x, y, 0.0015), (sx / 2, sy / 2, 0.0015), "rug")


def room(partition=False):
    """6 m x 5 m room, x in [-3, 3], y in [-2.5, 2.5]. The free middle (|x| < 1.5, |y| < 1.5)
    leaves room for a 2 m x 2 m square of waypoints 0.4 m or more from everything.
    partition: the same room with a plain painted board standing in the free middle (room_blank_wall)."""
    w = World("room", 11)
    w.common_assets("floor_wood", 1.0)
    H = 2.5
    w.wall(-3, 2.5, 3, 2.5, H, "wall")
    w.wall(-3, -2.5, 3, -2.5, H, "wall")
    w.wall(3, -2.5, 3, 2.5, H, "brick")
    w.wall(-3, -2.5, -3, 2.5, H, "wall")
    w.door("door_south", -1.6, -2.45, -0.7, -2.45, (0, 1))
    w.door("door_east", 2.95, 0.2, 2.95, 1.1, (-1, 0))
    w.shelf("shelf_west", -2.77, 0.3, 0, w=1.6)
    w.cabinet("cabinet_west", -2.72, -1.6, 0)
    w.table("table", 1.95, 1.75, 0)
    w.chair("chair_1", 1.75, 1.05, 90)
    w.chair("chair_2", 2.45, 1.2, 120)
    w.crates("crates_ne", 0.3, 2.2, 90, n=4)
    w.crates("crates_se", 2.55, -1.0, 0, n=3)
    w.radiator("radiator_north", -1.6, 2.42, -90, w=1.2)
    w.bench("bench_south", 0.9, -2.25, 90, w=1.3)
    w.bin("bin", -2.6, 2.1)
    w.plant("plant", 2.6, -2.1)
    w.plant("plant_2", -2.55, -2.15)
    rug(w, 2.0, 1.9, 1.6, 0.9)
    lights = [((-1.2, 0, 2.4), 0.45), ((1.2, 0, 2.4), 0.45)]
    if not partition:
        w.write("room.xml", "room: a 6 m x 5 m furnished room (shelf, table and chairs, doors, "
                "boxes, radiator, bench). Free space |x| < 1.5, |y| < 1.5.", (3, 2.5), lights)
        return
    # A board painted one flat colour, no texture: 2.4 m long along y at x = 1.0 (face at
    # x = 0.99), 1 m high, 2 cm thick. Close up it fills the view with nothing to track.
    w.panel(w.body, 1.0, -1.2, 1.0, 1.2, 0, 1.0, 0.02, "0.82 0.8 0.76")
    w.write("room_blank_wall.xml", "room_blank_wall: the room with a plain painted board (2.4 m x 1 m, "
            "no texture) standing along y at x = 1.0.", (3, 2.5), lights)


def corridor():
    """15 m x 3 m corridor, x in [-0.5, 14.5], y in [-1.5, 1.5]. Props stay within 0.45 m of the
    side walls (|y| >= 1.05), so lanes at y = +-0.55 keep 0.5 m clear; 0.9 m free at both ends."""
    w = World("corridor", 23)
    w.common_assets("floor_terrazzo", 1.2)
    H = 2.6
    w.wall(-0.5, 1.5, 14.5, 1.5, H, "wall")
    w.wall(-0.5, -1.5, 14.5, -1.5, H, "wall")
    w.wall(14.5, -1.5, 14.5, 1.5, H, "brick")
    w.wall(-0.5, -1.5, -0.5, 1.5, H, "brick")
    # brick wainscot sections, 1 m high, on the side walls
    for x0, x1, y in ((3.0, 5.5, 1.435), (8.5, 11.0, 1.435), (0.5, 2.5, -1.435), (6.0, 8.2, -1.435)):
        w.panel(w.body, x0, y, x1, y, 0, 1.0, 0.02, "brick")
    for i, (x, side) in enumerate(((2.0, 1), (6.4, 1), (11.5, 1), (4.0, -1), (9.3, -1), (13.2, -1))):
        y = side * 1.45
        w.door(f"door_{i}", x - 0.45, y, x + 0.45, y, (0, -side))
    w.door("door_end", 14.45, -0.45, 14.45, 0.45, (-1, 0))
    w.crates("crates_0", 0.6, 1.2, 90, n=2)
    w.crates("crates_1", 7.6, 1.22, 90, n=3)
    w.crates("crates_2", 3.0, -1.22, 90, n=2)
    w.crates("crates_3", 12.2, -1.22, 90, n=3)
    w.bench("bench_0", 4.7, 1.3, 90, w=1.3)
    w.bench("bench_1", 10.4, -1.3, 90, w=1.2)
    w.radiator("radiator_0", 9.7, 1.44, -90, w=1.0)
    w.radiator("radiator_1", 5.5, -1.44, 90, w=1.2)
    w.cabinet("cabinet_0", 13.0, 1.25, -90, w=0.9, d=0.4)
    w.cabinet("cabinet_1", 1.4, -1.25, 90, w=0.8, d=0.4)
    w.shelf("shelf_end", -0.32, 0.7, 0, w=0.9, d=0.3)
    w.bin("bin_0", 8.6, -1.28)
    w.bin("bin_1", 3.4, 1.28)
    w.plant("plant_0", 14.2, 1.2)
    w.plant("plant_1", -0.2, -1.2)
    w.write("corridor.xml", "corridor: a 15 m x 3 m corridor with doors, posters, brick, boxes, "
            "benches and radiators along its walls. Lanes at y = +-0.55 are clear for x in [0.4, 13.6].",
            (7.5, 1.5), [((3.5, 0, 2.5), 0.5), ((10.5, 0, 2.5), 0.5)], floor_centre=(7.0, 0.0))


def room_large():
    """10 m x 7 m hall, x in [-5, 5], y in [-3.5, 3.5], with a central island of furniture
    (|x| < 2, |y| < 0.8). A loop at |x| = 3.2, |y| = 2.2 keeps 0.4 m or more from everything
    and is 2 * (6.4 + 4.4) = 21.6 m long."""
    w = World("hall", 37)
    w.common_assets("floor_wood", 1.0)
    H = 2.8
    w.wall(-5, 3.5, 5, 3.5, H, "wall")
    w.wall(-5, -3.5, 5, -3.5, H, "wall")
    w.wall(5, -3.5, 5, 3.5, H, "brick")
    w.wall(-5, -3.5, -5, 3.5, H, "wall")
    w.door("door_n", -2.0, 3.45, -1.1, 3.45, (0, -1))
    w.door("door_s", 1.5, -3.45, 2.4, -3.45, (0, 1))
    w.door("door_w", -4.95, -0.5, -4.95, 0.4, (1, 0))
    # central island: two shelves back to back, a table with chairs, boxes
    w.shelf("island_shelf_a", -1.1, 0.19, 180, w=1.6, d=0.35, h=1.4, levels=4)
    w.shelf("island_shelf_b", -0.75, 0.19, 0, w=1.6, d=0.35, h=1.4, levels=4)
    w.table("island_table", 1.0, 0.0, 0, w=1.4, d=0.8)
    w.chair("island_chair_1", 1.0, 0.55, -90)
    w.chair("island_chair_2", 1.0, -0.55, 90)
    w.crates("island_crates", -1.75, -0.25, 0, n=2)
    # along the walls
    w.shelf("shelf_east", 4.77, -1.5, 180, w=1.6)
    w.cabinet("cabinet_east", 4.7, 1.5, 180)
    w.crates("crates_n", 1.5, 3.2, 90, n=4)
    w.crates("crates_w", -4.7, 2.2, 0, n=3)
    w.radiator("radiator_s", -1.8, -3.42, 90, w=1.4)
    w.bench("bench_n", -3.4, 3.25, 90, w=1.4)
    w.bench("bench_s", 3.6, -3.25, 90, w=1.2)
    w.cabinet("cabinet_w", -4.72, -2.3, 0)
    w.table("table_ne", 3.6, 2.95, 0, w=1.2, d=0.6)
    w.bin("bin_sw", -4.5, -3.1)
    w.plant("plant_ne", 4.6, 3.1)
    w.plant("plant_nw", -4.6, 3.1)
    w.plant("plant_se", 4.6, -3.1)
    w.write("room_large.xml", "room_large: a 10 m x 7 m hall with a central island of shelves, "
            "a table and boxes, and furniture along the walls. A loop at |x| = 3.2, |y| = 2.2 is "
            "clear (21.6 m).",
            (5, 3.5), [((-2.5, 0, 2.7), 0.5), ((2.5, 0, 2.7), 0.5)])


if __name__ == "__main__":
    room()
    room(partition=True)
    corridor()
    room_large()
