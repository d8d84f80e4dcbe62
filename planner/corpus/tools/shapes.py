#!/usr/bin/env python3
"""Writes the corpus' geometric test shapes (made for this corpus, CC0): a round annulus
whose outer radius is twice the inner, a U, a plus sign, plates with round and several
holes, and two separate discs (deliberately not one piece).

Usage: python3 shapes.py OUTDIR
Circles are written as <circle> elements or as SVG arcs, as a drawing program would.
"""
import os
import sys

HEAD = '<svg xmlns="http://www.w3.org/2000/svg" width="{w}mm" height="{h}mm" viewBox="0 0 {w} {h}">\n'


def circle_path(cx, cy, r, clockwise=False):
    """A circle as two SVG arcs (sweep flag 1 = clockwise on the page)."""
    s = 1 if clockwise else 0
    return (f"M{cx + r:g} {cy:g}A{r:g} {r:g} 0 1 {s} {cx - r:g} {cy:g}"
            f"A{r:g} {r:g} 0 1 {s} {cx + r:g} {cy:g}Z")


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    shapes = {
        # outer radius 40, inner 20: twice the inner
        "annulus": (100, 100, f'<path fill-rule="evenodd" d="{circle_path(50, 50, 40)} {circle_path(50, 50, 20)}"/>'),
        # a U: two arms 30 wide, 90 tall, joined by a bar 30 tall
        "u-shape": (120, 100, '<path d="M5 5H35V65H85V5H115V95H5Z"/>'),
        # a plus sign: arms 30 wide, 90 across
        "plus": (100, 100, '<path d="M35 5H65V35H95V65H65V95H35V65H5V35H35Z"/>'),
        # a rounded plate (drawn clockwise on the page) with three round holes of different sizes
        # (drawn counter-clockwise: holes by the non-zero rule)
        "plate-round-holes": (140, 90, '<path d="M15 5H125A10 10 0 0 1 135 15V75A10 10 0 0 1 125 85H15A10 10 0 0 1 5 75V15A10 10 0 0 1 15 5Z'
                              + circle_path(35, 45, 18) + circle_path(80, 30, 10) + circle_path(105, 60, 14) + '"/>'),
        # a disc with five holes: a round one in the middle, four square ones around it (even-odd)
        "disc-several-holes": (120, 120, '<path fill-rule="evenodd" d="' + circle_path(60, 60, 55)
                               + circle_path(60, 60, 12) + "M25 52h16v16h-16zM79 52h16v16h-16zM52 25h16v16h-16zM52 79h16v16h-16z" + '"/>'),
        # two separate discs: no one chain fills both (deliberately not connected)
        "two-discs": (140, 70, '<circle cx="35" cy="35" r="30"/><circle cx="105" cy="35" r="30"/>'),
    }
    for name, (w, h, body) in shapes.items():
        with open(os.path.join(out, name + ".svg"), "w") as f:
            f.write(HEAD.format(w=w, h=h) + body + "\n</svg>\n")


if __name__ == "__main__":
    main()
