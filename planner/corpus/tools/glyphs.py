#!/usr/bin/env python3
"""Writes the letters A-Z of a font as SVG files: each glyph's outline exactly as the font
stores it (TrueType quadratic contours, via fontTools' SVGPathPen), nothing simplified.

Usage: python3 glyphs.py FONT.ttf OUTDIR [LETTERS]
  e.g. python3 glyphs.py /usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf ../letters

The font's units are kept as SVG user units (y flipped by one transform on the path, so
the letter stands upright); the viewBox is the glyph's advance width by the font's
ascender-to-descender height. Needs fontTools (pip install fonttools).
"""
import os
import sys

from fontTools.pens.svgPathPen import SVGPathPen
from fontTools.ttLib import TTFont


def main():
    font_path, out_dir = sys.argv[1], sys.argv[2]
    letters = sys.argv[3] if len(sys.argv) > 3 else "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
    font = TTFont(font_path)
    glyphs = font.getGlyphSet()
    cmap = font.getBestCmap()
    ascent, descent = font["hhea"].ascent, font["hhea"].descent
    family = font["name"].getDebugName(4)
    version = font["name"].getDebugName(5)
    os.makedirs(out_dir, exist_ok=True)
    for ch in letters:
        name = cmap[ord(ch)]
        pen = SVGPathPen(glyphs)
        glyphs[name].draw(pen)
        width = glyphs[name].width
        height = ascent - descent
        svg = (
            f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {width} {height}" '
            f'width="{width / 20:g}" height="{height / 20:g}">\n'
            f"<!-- {family} ({version}), glyph {name} ({ch}), outline as stored in the font -->\n"
            f'<path transform="matrix(1 0 0 -1 0 {ascent})" d="{pen.getCommands()}"/>\n'
            "</svg>\n"
        )
        with open(os.path.join(out_dir, f"{ch}.svg"), "w") as f:
            f.write(svg)


if __name__ == "__main__":
    main()
