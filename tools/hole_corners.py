#!/usr/bin/env python3
"""The corners of a shape's holes that rows and columns cannot fill at large tile counts.

Usage: tools/hole_corners.py PREVIEW.svg TILE_WIDTH [AXIS_DEG[,AXIS_DEG...]]

PREVIEW.svg is a preview written by `fold-plan ... --preview PREVIEW.svg` (its outline, the
path filled #f2e6b8, in drawing units); TILE_WIDTH is the plan's tile width in the same
units ("tile W units" in fold-plan's summary); AXIS_DEG the plan's axis ("axis A deg"),
0 by default. Under the sequential fold check a row (or column) whose line crosses a hole
may be laid only while the part across the hole on that line is empty, so the points of
the shape whose row line and column line both cross one hole fall into four corners that
need a cycle of orders (BENCHMARKS.md, "What a thin ring allows"): one corner of every hole
is left empty, less what the chain's last stretch (about a hole's width of tiles) fills.
Prints the shape's area in tile areas and, per axis, each hole's four corners (tile areas,
on a raster of about 260 pixels across) and the sum over the holes of the smallest corner.
Pure Python, no packages.
"""
import math
import re
import sys

RASTER = 260


def outline(svg):
    """The outline's rings (lists of points) from a fold-plan preview."""
    d = re.search(r'<path d="([^"]*)" fill="#f2e6b8"', svg).group(1)
    return [
        [tuple(map(float, xy.split(","))) for xy in re.findall(r"(-?[\d.e-]+,-?[\d.e-]+)", part)]
        for part in d.split("M")[1:]
    ]


def raster(rings):
    """Pixel centres inside the outline (even-odd), the pixel size and the grid origin."""
    xs = [p[0] for r in rings for p in r]
    ys = [p[1] for r in rings for p in r]
    h = max(max(xs) - min(xs), max(ys) - min(ys)) / RASTER
    x0, y0 = min(xs) - h, min(ys) - h
    nx, ny = int((max(xs) - x0) / h) + 2, int((max(ys) - y0) / h) + 2
    grid = [[False] * nx for _ in range(ny)]
    for j in range(ny):
        y = y0 + (j + 0.5) * h
        cross = sorted(
            xa + (y - ya) * (xb - xa) / (yb - ya)
            for r in rings
            for (xa, ya), (xb, yb) in zip(r, r[1:] + r[:1])
            if (ya > y) != (yb > y)
        )
        for a, b in zip(cross[::2], cross[1::2]):
            for i in range(max(0, math.ceil((a - x0) / h - 0.5)), min(nx - 1, math.floor((b - x0) / h - 0.5)) + 1):
                grid[j][i] = True
    return grid, h, x0, y0


def holes(grid):
    """The connected pieces of the outside of the shape that do not touch the grid's border."""
    ny, nx = len(grid), len(grid[0])
    seen = [[False] * nx for _ in range(ny)]
    out = []
    for j in range(ny):
        for i in range(nx):
            if grid[j][i] or seen[j][i]:
                continue
            seen[j][i] = True
            stack, cells, border = [(j, i)], [], False
            while stack:
                a, b = stack.pop()
                cells.append((a, b))
                border |= a in (0, ny - 1) or b in (0, nx - 1)
                for c, d in ((a + 1, b), (a - 1, b), (a, b + 1), (a, b - 1)):
                    if 0 <= c < ny and 0 <= d < nx and not grid[c][d] and not seen[c][d]:
                        seen[c][d] = True
                        stack.append((c, d))
            if not border:
                out.append(cells)
    return out


def corners(grid, h, origin, hole, axis):
    """The four corners of `hole` (pixel counts) at the axis `axis` (radians)."""
    cu, su = math.cos(axis), math.sin(axis)

    def uv(j, i):
        x, y = origin[0] + (i + 0.5) * h, origin[1] + (j + 0.5) * h
        return x * cu + y * su, -x * su + y * cu

    rows, cols = {}, {}
    for j, i in hole:
        u, v = uv(j, i)
        for key, at, val in ((rows, round(v / h), u), (cols, round(u / h), v)):
            lo, hi = key.get(at, (val, val))
            key[at] = (min(lo, val), max(hi, val))
    count = [0, 0, 0, 0]
    for j, row in enumerate(grid):
        for i, inside in enumerate(row):
            if not inside:
                continue
            u, v = uv(j, i)
            r, c = rows.get(round(v / h)), cols.get(round(u / h))
            if not r or not c:
                continue
            side_u = 1 if u < r[0] else (-1 if u > r[1] else 0)
            side_v = 1 if v < c[0] else (-1 if v > c[1] else 0)
            if side_u and side_v:
                count[(side_u > 0) * 2 + (side_v > 0)] += 1
    return count


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__.split("\n\n")[1])
    rings = outline(open(sys.argv[1]).read())
    w = float(sys.argv[2])
    axes = [float(a) for a in sys.argv[3].split(",")] if len(sys.argv) > 3 else [0.0]
    grid, h, x0, y0 = raster(rings)
    tile = h * h / (w * w)
    pieces = [c for c in holes(grid) if len(c) * h * h >= 0.5 * w * w]
    print(f"shape {sum(map(sum, grid)) * tile:.0f} tile areas, {len(pieces)} holes of half a tile area or more")
    for a in axes:
        each = [[n * tile for n in corners(grid, h, (x0, y0), c, math.radians(a))] for c in pieces]
        shown = "; ".join(" ".join(f"{x:.1f}" for x in cs) for cs in each)
        print(f"axis {a:g} deg: smallest corners {sum(min(cs) for cs in each):.1f} tile areas (each hole's four: {shown})")


main()
