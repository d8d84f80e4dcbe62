#!/usr/bin/env python3
"""All empty parts of a plan by issue 26's measure (as planner/src/empty.rs samples them:
an eighth of a tile width, at least half a tile inside the outline, farther than 0.95 w
from every tile centre, four-neighbour groups over 2 tile areas), with a zoomed render of
each (the preview cropped to the part, its samples in red) for classifying them by eye.
Usage: python3 tools/empty_parts.py PLAN.json PREVIEW.svg OUTPREFIX, from
`fold-plan F --tiles N --json --preview PREVIEW.svg > PLAN.json`; needs rsvg-convert."""
import json, sys, re, math, subprocess
NEAR, EDGE, STEP, MIN = 0.95, 0.5, 0.125, 2.0
TA = 2 * (math.sqrt(2) - 1)
d = json.load(open(sys.argv[1])); svg = open(sys.argv[2]).read(); out = sys.argv[3]
w = d['tile_size']
path = re.search(r'<path d="([^"]*)"', svg).group(1)
rings = []
for sub in re.split(r'[Mm]', path)[1:]:
    pts = [tuple(map(float, p.split(','))) for p in re.findall(r'-?[\d.e+-]+,-?[\d.e+-]+', sub)]
    rings.append([(x / w, y / w) for x, y in pts])
edges = [(r[i], r[(i + 1) % len(r)]) for r in rings for i in range(len(r))]
def intervals(y):
    xs = []
    for (x0, y0), (x1, y1) in edges:
        if (y0 <= y) != (y1 <= y):
            xs.append(x0 + (y - y0) * (x1 - x0) / (y1 - y0))
    xs.sort()
    return [(xs[i], xs[i + 1]) for i in range(0, len(xs) - 1, 2)]
cs = [(p['x'] / w, p['y'] / w, p['heading_deg']) for p in d['poses']]
allx = [p[0] for r in rings for p in r]; ally = [p[1] for r in rings for p in r]
x0, y0, x1, y1 = min(allx), min(ally), max(allx), max(ally)
nx, ny = int((x1 - x0) / STEP) + 1, int((y1 - y0) / STEP) + 1
reached = bytearray(nx * ny)
for cx, cy, _ in cs:
    for i in range(ny):
        dy = y1 - (i + .5) * STEP - cy
        if abs(dy) > NEAR: continue
        h2 = NEAR * NEAR - dy * dy
        if h2 < 0: continue
        h = math.sqrt(h2)
        for j in range(max(0, math.ceil((cx - h - x0) / STEP - .5)), min(nx, math.floor((cx + h - x0) / STEP - .5) + 1)):
            reached[i * nx + j] = 1
empty = set()
for i in range(ny):
    y = y1 - (i + .5) * STEP
    lines = None
    for a, e in intervals(y):
        for j in range(max(0, math.ceil((a - x0) / STEP - .5)), min(nx, math.floor((e - x0) / STEP - .5) + 1)):
            if reached[i * nx + j]: continue
            if lines is None:
                lines = [(EDGE * math.sqrt(1 - f * f), intervals(y + f * EDGE)) for f in (-1, -.5, 0, .5, 1)]
            x = x0 + (j + .5) * STEP
            if all(any(a2 <= x - hw and x + hw <= e2 for a2, e2 in iv) for hw, iv in lines):
                empty.add(i * nx + j)
parts = []
seen = set()
for s in sorted(empty):
    if s in seen: continue
    comp = []; st = [s]; seen.add(s)
    while st:
        c = st.pop(); comp.append(c)
        i, j = divmod(c, nx)
        for n in ((c - 1) if j > 0 else None, (c + 1) if j + 1 < nx else None, c - nx, c + nx):
            if n is not None and n in empty and n not in seen:
                seen.add(n); st.append(n)
    area = len(comp) * STEP * STEP / TA
    if area > MIN:
        pts = [(x0 + (c % nx + .5) * STEP, y1 - (c // nx + .5) * STEP) for c in comp]
        parts.append((area, pts))
parts.sort(key=lambda p: -p[0])
print(f"{sys.argv[1]}: tiles {d['tiles']} U {d['u_turns']} Q {d['quarter_turns']} cells {d['cells']} largest(json) {d['metrics']['largest_empty_tiles']:.2f}")
vb = re.search(r'viewBox="([^"]*)"', svg)
for k, (area, pts) in enumerate(parts):
    xs = [p[0] for p in pts]; ys = [p[1] for p in pts]
    cx, cy = sum(xs) / len(xs), sum(ys) / len(ys)
    # nearby tiles' headings
    near = [h for (tx, ty, h) in cs if min((tx - x) ** 2 + (ty - y) ** 2 for x, y in pts[::4]) < 2.5 ** 2]
    hd = {}
    for h in near: hd[round(h) % 180] = hd.get(round(h) % 180, 0) + 1
    print(f"  part {k}: {area:.2f} tile areas at ({cx*w:.0f},{cy*w:.0f}) size {max(xs)-min(xs):.1f}x{max(ys)-min(ys):.1f} w; nearby tile headings mod 180 {hd}")
    m = 4
    bx0, by0, bx1, by1 = (min(xs) - m) * w, (min(ys) - m) * w, (max(xs) + m) * w, (max(ys) + m) * w
    z = re.sub(r'viewBox="[^"]*"', f'viewBox="{bx0} {by0} {bx1-bx0} {by1-by0}"', svg, 1)
    z = re.sub(r'width="\d+"', 'width="500"', z, 1); z = re.sub(r'height="\d+"', f'height="{int(500*(by1-by0)/(bx1-bx0))}"', z, 1)
    dots = ''.join(f'<circle cx="{x*w:.2f}" cy="{y*w:.2f}" r="{0.05*w:.2f}" fill="red"/>' for x, y in pts[::2])
    z = z.replace('</svg>', dots + '</svg>')
    open(f'{out}-p{k}.svg', 'w').write(z)
    subprocess.run(['rsvg-convert', f'{out}-p{k}.svg', '-o', f'{out}-p{k}.png'])
