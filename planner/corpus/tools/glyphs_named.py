#!/usr/bin/env python3
"""Writes chosen characters of a font as SVG files named PREFIX-NAME.svg (letters as they
are, lowercase as x-lc, & @ % ? # as amp, at, percent, question, hash): each glyph's outline
exactly as the font stores it, as glyphs.py does (fontTools' SVGPathPen, y flipped by one
transform, the viewBox the advance width by the ascender-to-descender height).

Usage: python3 glyphs_named.py FONT.ttf OUTDIR PREFIX CHARACTERS
  e.g. python3 glyphs_named.py /usr/share/fonts/truetype/liberation/LiberationSerif-Italic.ttf ../glyphs libsi AQ
Needs fontTools (pip install fonttools).
"""
import os, sys
from fontTools.pens.svgPathPen import SVGPathPen
from fontTools.ttLib import TTFont
NAMES = {'&':'amp','@':'at','%':'percent','?':'question','#':'hash'}
def main():
    font_path, out_dir, prefix, chars = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
    font = TTFont(font_path); glyphs = font.getGlyphSet(); cmap = font.getBestCmap()
    ascent, descent = font["hhea"].ascent, font["hhea"].descent
    family = font["name"].getDebugName(4); version = font["name"].getDebugName(5)
    for ch in chars:
        name = cmap[ord(ch)]; pen = SVGPathPen(glyphs); glyphs[name].draw(pen)
        width = glyphs[name].width; height = ascent - descent
        svg = (f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {width} {height}" '
               f'width="{width / 20:g}" height="{height / 20:g}">\n'
               f"<!-- {family} ({version}), glyph {name} ({ch}), outline as stored in the font -->\n"
               f'<path transform="matrix(1 0 0 -1 0 {ascent})" d="{pen.getCommands()}"/>\n</svg>\n')
        n = NAMES.get(ch, ch if not ch.islower() else ch + '-lc')
        with open(os.path.join(out_dir, f"{prefix}-{n}.svg"), "w") as f: f.write(svg)
main()
