#!/usr/bin/env bash
# Makes the corpus' Inkscape files: each source below is opened and saved by Inkscape
# (Debian's inkscape 1.2.2, `apt-get install inkscape`), which converts its text and
# shapes to paths (`object-to-path`) and writes an Inkscape SVG (sodipodi/inkscape
# metadata, layers as inkscape:groupmode="layer", mm/cm units, its own path syntax).
# Text is set in DejaVu Sans Bold (Debian's fonts-dejavu-core).
#   bash inkscape.sh OUTDIR
set -euo pipefail
out=$(realpath -m "${1:?usage: inkscape.sh OUTDIR}")
mkdir -p "$out"
src=$(mktemp -d)
trap 'rm -rf "$src"' EXIT
declare -A actions
NS='xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"'

# A logo (a disc and a bar, overlapping, in three colours) and the letter G on top, made
# into a clip the way Inkscape's Object > Clip > Set does (text to path, then the topmost
# object clips the logo): what a browser shows is the letter cut from the logo.
cat > "$src/ink-clip-logo.svg" <<SVG
<svg $NS width="80mm" height="80mm" viewBox="0 0 80 80">
  <g inkscape:groupmode="layer" inkscape:label="Logo" id="layer1">
    <g id="logo">
      <circle cx="40" cy="42" r="33" fill="#fc3"/>
      <rect x="2" y="32" width="76" height="22" fill="#d33"/>
      <circle cx="40" cy="42" r="12" fill="#36c"/>
    </g>
    <text id="glyph" x="6" y="72" style="font-family:'DejaVu Sans';font-weight:bold;font-size:90px">G</text>
  </g>
</svg>
SVG
actions[ink-clip-logo.svg]="select-by-id:glyph;object-to-path;selection-ungroup;select-by-id:logo;object-set-clip"

# A house in two layers with their own transforms, in mm; a hidden layer (a large
# rectangle, display:none) that is not part of the drawing.
cat > "$src/ink-layers-house.svg" <<SVG
<svg $NS width="120mm" height="110mm" viewBox="0 0 120 110">
  <g inkscape:groupmode="layer" inkscape:label="Guides" style="display:none">
    <rect x="-50" y="-50" width="300" height="300" fill="#ccc"/>
  </g>
  <g inkscape:groupmode="layer" inkscape:label="Walls" transform="translate(10,45)">
    <rect x="0" y="0" width="100" height="60" fill="#a63"/>
  </g>
  <g inkscape:groupmode="layer" inkscape:label="Roof" transform="translate(60,5) scale(1.1,1)">
    <polygon points="0,0 52,45 -52,45" fill="#733"/>
    <rect x="22" y="5" width="12" height="30" fill="#733"/>
  </g>
</svg>
SVG

# A disc under a mask (Object > Mask > Set: the topmost object, white showing and black
# hiding, masks the disc): what shows is a crescent.
cat > "$src/ink-mask-crescent.svg" <<SVG
<svg $NS width="100mm" height="100mm" viewBox="0 0 100 100">
  <g inkscape:groupmode="layer" inkscape:label="Moon" id="layer1">
    <circle id="moon" cx="50" cy="50" r="42" fill="#fd5"/>
    <g id="bite">
      <rect x="0" y="0" width="100" height="100" fill="#fff"/>
      <circle cx="66" cy="40" r="33" fill="#000"/>
    </g>
  </g>
</svg>
SVG
actions[ink-mask-crescent.svg]="select-by-id:moon;object-to-path;select-by-id:bite;object-set-mask"

# A star used twice through <use>, under nested transforms (rotate, scale, skew, a mirror),
# in cm.
cat > "$src/ink-transforms-star.svg" <<SVG
<svg $NS width="12cm" height="12cm" viewBox="0 0 1200 1200">
  <defs>
    <polygon id="star" points="0,-400 94,-129 380,-124 152,49 235,324 0,160 -235,324 -152,49 -380,-124 -94,-129"/>
  </defs>
  <g inkscape:groupmode="layer" inkscape:label="Star" transform="translate(600 620) rotate(12) scale(1.1)">
    <g transform="skewX(8)">
      <use xlink:href="#star" fill="#e80"/>
    </g>
    <g transform="scale(-0.45 0.45)">
      <use xlink:href="#star" fill="#c60"/>
    </g>
  </g>
</svg>
SVG

# A snowman of overlapping shapes on two layers (three discs, a hat): one piece only as
# their union.
cat > "$src/ink-snowman-union.svg" <<SVG
<svg $NS width="90mm" height="150mm" viewBox="0 0 90 150">
  <g inkscape:groupmode="layer" inkscape:label="Body">
    <circle cx="45" cy="112" r="34"/>
    <circle cx="45" cy="66" r="24"/>
    <circle cx="45" cy="33" r="17"/>
  </g>
  <g inkscape:groupmode="layer" inkscape:label="Hat" transform="rotate(-8 45 18)">
    <rect x="27" y="14" width="36" height="6"/>
    <rect x="33" y="0" width="24" height="16"/>
  </g>
</svg>
SVG

for f in "$src"/*.svg; do
  name=$(basename "$f")
  # the file's own actions, or every shape to a path; then save as Inkscape SVG
  inkscape "$f" --actions="${actions[$name]:-select-all:all;object-to-path}" \
    --export-type=svg --export-filename="$out/$name" 2>/dev/null
done
