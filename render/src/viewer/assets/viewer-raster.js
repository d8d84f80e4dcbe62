// foldchain viewer, many tiles at once: the chain rasterised in the page straight into a
// pixel buffer (convex polygons and discs by scan lines, no anti-aliasing) and put on its
// canvas in one call. Chromium's own canvas and its software WebGL both take hundreds of
// milliseconds for 10^4 tiles on a headless machine; this takes a few. Used when many tiles
// are in view; a few are drawn by the canvas with smooth edges (viewer-2d.js).

// Tiles in view above which the chain is rasterised here.
const RASTER_ABOVE = 1500;
const QUARTER_PI = Math.PI / 4;

function rgba32(hex) {
  const n = parseInt(hex.slice(1), 16);
  // little-endian RGBA bytes
  return ((255 << 24) | ((n & 255) << 16) | (n & 0xff00) | (n >> 16 & 255)) >>> 0;
}

function makeRaster(canvas) {
  const ctx = canvas.getContext('2d');
  let img = null, px = null, W = 0, H = 0;
  const xs = new Float64Array(16), ys = new Float64Array(16);
  const C = {};
  Object.keys(COL).forEach(function (k) { if (COL[k][0] === '#') C[k] = rgba32(COL[k]); });
  const fill = [C.tile, C.moving, C.folding, C.hit];

  function span(y, x0, x1, c) {
    if (y < 0 || y >= H) return;
    let a = Math.ceil(x0 - 0.5), b = Math.floor(x1 - 0.5);
    if (a < 0) a = 0;
    if (b >= W) b = W - 1;
    if (a <= b) px.fill(c, y * W + a, y * W + b + 1);
  }
  function dot(x, y, c) {
    const i = Math.floor(x), j = Math.floor(y);
    if (i >= 0 && i < W && j >= 0 && j < H) px[j * W + i] = c;
  }
  // the pixel rows of the convex polygon xs[0..m), ys[0..m), from row `min` to row `max` at
  // the most: onRow(row, lo, hi) for every row whose centre line crosses it, lo and hi where
  // that line enters and leaves; whether onRow returned true for any row
  function polygonRows(m, min, max, onRow) {
    let y0 = Infinity, y1 = -Infinity;
    for (let q = 0; q < m; q++) { if (ys[q] < y0) y0 = ys[q]; if (ys[q] > y1) y1 = ys[q]; }
    const ra = Math.max(Math.ceil(y0 - 0.5), min), rb = Math.min(Math.floor(y1 - 0.5), max);
    let drawn = false;
    for (let row = ra; row <= rb; row++) {
      const yc = row + 0.5;
      let lo = Infinity, hi = -Infinity;
      for (let q = 0; q < m; q++) {
        const q2 = q + 1 === m ? 0 : q + 1;
        const ya = ys[q], yb = ys[q2];
        if ((ya <= yc && yc < yb) || (yb <= yc && yc < ya)) {
          const x = xs[q] + (yc - ya) * (xs[q2] - xs[q]) / (yb - ya);
          if (x < lo) lo = x;
          if (x > hi) hi = x;
        }
      }
      if (lo <= hi && onRow(row, lo, hi)) drawn = true;
    }
    return drawn;
  }
  // the convex polygon xs[0..m), ys[0..m), at least its centre pixel
  function polygon(m, c) {
    const drawn = polygonRows(m, 0, H - 1, function (row, lo, hi) {
      span(row, lo, hi, c);
      return true;
    });
    if (!drawn) {
      let cx = 0, cy = 0;
      for (let q = 0; q < m; q++) { cx += xs[q]; cy += ys[q]; }
      dot(cx / m, cy / m, c);
    }
  }
  function disc(cx, cy, r, c) {
    if (r < 0.75) { dot(cx, cy, c); return; }
    const ra = Math.max(Math.ceil(cy - r - 0.5), 0), rb = Math.min(Math.floor(cy + r - 0.5), H - 1);
    for (let row = ra; row <= rb; row++) {
      const dy = row + 0.5 - cy, h = r * r - dy * dy;
      if (h >= 0) { const s = Math.sqrt(h); span(row, cx - s, cx + s, c); }
    }
  }
  // the annulus between radii r0 and r1 around (cx, cy)
  function ring(cx, cy, r0, r1, c) {
    const ra = Math.max(Math.ceil(cy - r1 - 0.5), 0), rb = Math.min(Math.floor(cy + r1 - 0.5), H - 1);
    for (let row = ra; row <= rb; row++) {
      const dy = row + 0.5 - cy, h1 = r1 * r1 - dy * dy, h0 = r0 * r0 - dy * dy;
      if (h1 < 0) continue;
      const s1 = Math.sqrt(h1);
      if (h0 <= 0) { span(row, cx - s1, cx + s1, c); continue; }
      const s0 = Math.sqrt(h0);
      span(row, cx - s1, cx - s0, c);
      span(row, cx + s0, cx + s1, c);
    }
  }
  // a straight piece of channel, `half` pixels either side of its line
  function segment(x0, y0, x1, y1, half, c) {
    const dx = x1 - x0, dy = y1 - y0, len = Math.hypot(dx, dy);
    if (half < 0.75 || len === 0) {
      const n = Math.max(Math.ceil(len), 1);
      for (let i = 0; i <= n; i++) dot(x0 + dx * i / n, y0 + dy * i / n, c);
      return;
    }
    const nx = -dy / len * half, ny = dx / len * half;
    xs[0] = x0 + nx; ys[0] = y0 + ny; xs[1] = x1 + nx; ys[1] = y1 + ny;
    xs[2] = x1 - nx; ys[2] = y1 - ny; xs[3] = x0 - nx; ys[3] = y0 - ny;
    polygon(4, c);
  }

  // Sprites: a shape rasterised once per frame size as rows of spans around a pixel
  // (triples dy, x0, x1 with x1 exclusive, relative to the pixel holding the shape's
  // centre), stamped at every tile with one fill per row.
  // the convex polygon xs[0..m), ys[0..m) (pixels, the centre pixel's corner at 0, 0) as
  // spans pushed on `out`, at least the centre pixel
  function polygonSpans(m, out) {
    const drawn = polygonRows(m, -Infinity, Infinity, function (row, lo, hi) {
      const a = Math.ceil(lo - 0.5), b = Math.floor(hi - 0.5);
      if (a > b) return false;
      out.push(row, a, b + 1);
      return true;
    });
    if (!drawn) out.push(0, 0, 1);
  }
  // the tile's octagon turned by `angle`, scaled by `scale` around the pixel centre
  function octagonSpans(r, K, angle, scale) {
    const c = Math.cos(angle), s = Math.sin(angle), o = r.oct, out = [];
    for (let q = 0; q < 8; q++) {
      const a = o[2 * q] * scale, b = o[2 * q + 1] * scale;
      xs[q] = 0.5 + K * (c * a - s * b);
      ys[q] = 0.5 - K * (s * a + c * b);
    }
    polygonSpans(8, out);
    return sprite(out);
  }
  // spans as a sprite with its bounds: x0 the least start, x1 the largest end (exclusive),
  // y0 and y1 the first and last row
  function sprite(spans) {
    const sp = { s: Int32Array.from(spans), x0: Infinity, x1: -Infinity, y0: Infinity, y1: -Infinity };
    for (let q = 0; q < spans.length; q += 3) {
      sp.y0 = Math.min(sp.y0, spans[q]); sp.y1 = Math.max(sp.y1, spans[q]);
      sp.x0 = Math.min(sp.x0, spans[q + 1]); sp.x1 = Math.max(sp.x1, spans[q + 2]);
    }
    return sp;
  }
  // the octagon's sprites for the current size: `turns` turns across its symmetry (45
  // degrees), finer for larger tiles; outline (edge colour) and inside (fill colour)
  let octKey = '', turns = 1, octOut = [], octIn = [];
  function octagons(r, K, outline, inset) {
    const key = r.w * K + ',' + outline + ',' + inset;
    if (key === octKey) return;
    octKey = key;
    turns = Math.min(Math.max(Math.ceil(r.w * K / 3), 1), 32);
    octOut = []; octIn = [];
    for (let b = 0; b < turns; b++) {
      const angle = b / turns * QUARTER_PI;
      octOut.push(octagonSpans(r, K, angle, 1));
      if (outline) octIn.push(octagonSpans(r, K, angle, inset));
    }
  }
  // stamps sprite `sp` at pixel (cx, cy) in colour c
  function stamp(sp, cx, cy, c) {
    const q1 = sp.s.length, s = sp.s;
    if (cx + sp.x0 >= 0 && cx + sp.x1 <= W && cy + sp.y0 >= 0 && cy + sp.y1 < H) {
      for (let q = 0; q < q1; q += 3) {
        const o = (cy + s[q]) * W + cx, a = o + s[q + 1], b = o + s[q + 2];
        // short spans by hand: cheaper than a call
        if (b - a < 12) for (let x = a; x < b; x++) px[x] = c;
        else px.fill(c, a, b);
      }
      return;
    }
    for (let q = 0; q < q1; q += 3) {
      const y = cy + s[q];
      if (y < 0 || y >= H) continue;
      const a = Math.max(cx + s[q + 1], 0), b = Math.min(cx + s[q + 2], W);
      if (a < b) px.fill(c, y * W + a, y * W + b);
    }
  }

  function draw(p, t, opts) {
    const r = p.run, v = p.view, k = v.k, n = r.tiles;
    const dpr = p.dpr, K = k * dpr, OX = v.ox * dpr, OY = v.oy * dpr;
    if (!img || img.width !== canvas.width || img.height !== canvas.height) {
      W = canvas.width; H = canvas.height;
      img = ctx.createImageData(W, H);
      px = new Uint32Array(img.data.buffer);
    }
    px.fill(p.opaque ? C.bg : 0);
    const tilePx = r.w * k;
    const outline = tilePx >= 4;
    const inset = outline ? Math.max(0, 1 - Math.min(Math.max(0.04 * tilePx, 0.6), 1.5) / (0.5 * tilePx)) : 1;
    const margin = r.w * K;
    octagons(r, K, outline, inset);
    const perTurn = turns / QUARTER_PI;
    const pxs = r.px, pys = r.py, pas = r.pa, clss = r.cls;
    for (let i = 0; i < n; i++) {
      const X = OX + pxs[i] * K, Y = OY - pys[i] * K;
      if (X < -margin || X > W + margin || Y < -margin || Y > H + margin) continue;
      const cls = clss[i], cx = Math.floor(X), cy = Math.floor(Y);
      let b = 0;
      if (turns > 1) {
        b = Math.round((pas[i] + 4 * Math.PI) * perTurn) % turns;
      }
      if (outline) {
        stamp(octOut[b], cx, cy, cls === 3 ? C.hitEdge : C.edge);
        stamp(octIn[b], cx, cy, fill[cls]);
      } else {
        stamp(octOut[b], cx, cy, cls === 0 ? C.line : fill[cls]);
      }
    }
    if (n <= DETAIL_TILES && (opts.detailAll || tilePx >= DETAIL_PX)) {
      placeDetail(r, t);
      const half = 1.1 * r.magnetR * K;
      for (let i = 0; i < n; i++) {
        const X = OX + r.px[i] * K, Y = OY - r.py[i] * K;
        if (X < -margin || X > W + margin || Y < -margin || Y > H + margin) continue;
        const c = r.pc[i], s = r.ps[i];
        for (let m = 2 * i; m <= 2 * i + 1; m++) {
          const L = r.pathLines[r.mPath[m]];
          let x0 = X + K * (c * L[0] - s * L[1]), y0 = Y - K * (s * L[0] + c * L[1]);
          for (let q = 2; q < L.length; q += 2) {
            const x1 = X + K * (c * L[q] - s * L[q + 1]), y1 = Y - K * (s * L[q] + c * L[q + 1]);
            segment(x0, y0, x1, y1, half, C.path);
            x0 = x1; y0 = y1;
          }
        }
      }
      const hr = Math.max(0.06 * r.w * K, 1.5 * dpr), mr = Math.max(r.magnetR * K, dpr);
      for (let q = 0; q < r.joint.length; q++) {
        disc(OX + r.hx[q] * K, OY - r.hy[q] * K, hr, r.turning[r.joint[q]] ? C.hingeTurning : C.hinge);
      }
      for (let m = 0; m < 2 * n; m++) {
        const X = OX + r.mx[m] * K, Y = OY - r.my[m] * K;
        if (r.magnetMoving[m]) disc(X, Y, mr + Math.max(0.5 * mr, 1.5 * dpr), C.movingRing);
        disc(X, Y, mr, m & 1 ? C.poleB : C.poleA);
      }
    }
    // the RI and the collision ring over the chain (the overlay canvas stays empty)
    const mk = overMarks(p);
    disc(mk.x * dpr, mk.y * dpr, mk.r * dpr, C.ri);
    if (mk.ring) ring(mk.ring.x * dpr, mk.ring.y * dpr, (mk.ring.r - 0.5 * RING_PX) * dpr, (mk.ring.r + 0.5 * RING_PX) * dpr, C.hit);
    ctx.putImageData(img, 0, 0);
  }
  return { draw: draw };
}
