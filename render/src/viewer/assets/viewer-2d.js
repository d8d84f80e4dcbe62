// foldchain viewer, Canvas 2D drawing: the background and the target outline under the
// chain, the RI and the collision ring over it, and the chain with smooth edges when few of
// its tiles are in view (Chromium's canvas slows down sharply on paths of thousands of
// parts, so tiles go in batches).

const BATCH = 200;
// the collision ring's width, CSS pixels
const RING_PX = 2.5;

function sx(v, x) { return v.ox + x * v.k; }
function sy(v, y) { return v.oy - y * v.k; }

// background and target outline
function drawUnder(p) {
  const r = p.run, ctx = p.ctx, v = p.view;
  ctx.setTransform(p.dpr, 0, 0, p.dpr, 0, 0);
  ctx.fillStyle = COL.bg;
  ctx.fillRect(0, 0, p.cssW, p.cssH);
  if (!r.target.length) return;
  ctx.beginPath();
  for (const ring of r.target) {
    ring.forEach(function (q, i) {
      if (i === 0) ctx.moveTo(sx(v, q[0]), sy(v, q[1])); else ctx.lineTo(sx(v, q[0]), sy(v, q[1]));
    });
    ctx.closePath();
  }
  ctx.fillStyle = COL.targetFill;
  ctx.fill('evenodd');
  ctx.lineWidth = 1.5;
  ctx.strokeStyle = COL.targetEdge;
  ctx.stroke();
}

// the RI and the collision ring where they are drawn, CSS pixels: the RI's centre and
// radius, the ring's centre and radius (null without a collision); places the RI's label
// (text in the page: the canvas's first text costs tens of milliseconds)
function overMarks(p) {
  const r = p.run, v = p.view, k = v.k;
  const rx = r.px[0] + r.pc[0] * r.ri[0] - r.ps[0] * r.ri[1];
  const ry = r.py[0] + r.ps[0] * r.ri[0] + r.pc[0] * r.ri[1];
  const m = { x: sx(v, rx), y: sy(v, ry), r: Math.max(r.magnetR * k, 3), ring: null };
  p.riLabel.style.transform = 'translate(' + (m.x - m.r - 3).toFixed(1) + 'px,' +
    m.y.toFixed(1) + 'px) translate(-100%,-50%)';
  if (r.hit) {
    const a = r.hit[0], b = r.hit[1];
    const span = Math.hypot(r.px[a] - r.px[b], r.py[a] - r.py[b]) * k;
    m.ring = { x: sx(v, 0.5 * (r.px[a] + r.px[b])), y: sy(v, 0.5 * (r.py[a] + r.py[b])),
      r: Math.max(0.5 * span + r.w * k, 14) };
  }
  return m;
}

// the RI and the collision ring on the overlay canvas
function drawOver(p) {
  const ctx = p.overCtx, m = overMarks(p);
  ctx.setTransform(p.dpr, 0, 0, p.dpr, 0, 0);
  ctx.clearRect(0, 0, p.cssW, p.cssH);
  p.overDrawn = true;
  ctx.beginPath();
  ctx.arc(m.x, m.y, m.r, 0, 2 * Math.PI);
  ctx.fillStyle = COL.ri;
  ctx.fill();
  if (m.ring) {
    ctx.beginPath();
    ctx.arc(m.ring.x, m.ring.y, m.ring.r, 0, 2 * Math.PI);
    ctx.lineWidth = RING_PX;
    ctx.strokeStyle = COL.hit;
    ctx.stroke();
  }
}

function octagonPath(ctx, r, i, v) {
  const c = r.pc[i], s = r.ps[i], x = r.px[i], y = r.py[i], o = r.oct;
  for (let q = 0; q < 16; q += 2) {
    const X = sx(v, x + c * o[q] - s * o[q + 1]), Y = sy(v, y + s * o[q] + c * o[q + 1]);
    if (q === 0) ctx.moveTo(X, Y); else ctx.lineTo(X, Y);
  }
  ctx.closePath();
}

// every tile of class c that `visible` accepts, filled and outlined in batches
function tilesOfClass(p, c, visible, limit) {
  const r = p.run, ctx = p.ctx, v = p.view;
  const small = r.w * v.k < OUTLINE_PX;
  ctx.fillStyle = small && c === 0 ? COL.line : TILE_FILL[c];
  ctx.strokeStyle = c === 3 ? COL.hitEdge : COL.edge;
  ctx.lineWidth = c === 3 ? 2 : Math.min(Math.max(0.04 * r.w * v.k, 0.3), 1.5);
  let inPath = 0, shown = 0;
  const flush = function () {
    ctx.fill();
    if (!small || c === 3) ctx.stroke();
    inPath = 0;
  };
  ctx.beginPath();
  for (let i = 0; i < r.tiles && shown < limit; i++) {
    if (r.cls[i] !== c || !visible(i)) continue;
    octagonPath(ctx, r, i, v);
    shown++;
    if (++inPath === BATCH) { flush(); ctx.beginPath(); }
  }
  if (inPath) flush();
}

// the chain drawn by the canvas
function drawChain2d(p, t, opts) {
  const r = p.run, ctx = p.ctx, v = p.view, k = v.k, n = r.tiles;
  const full = opts.detailAll;
  const margin = r.w * 0.8 * k;
  const visible = function (i) {
    if (full) return true;
    const X = sx(v, r.px[i]), Y = sy(v, r.py[i]);
    return X > -margin && X < p.cssW + margin && Y > -margin && Y < p.cssH + margin;
  };
  if (full || r.w * k >= OUTLINE_PX) {
    for (let c = 0; c < 4; c++) tilesOfClass(p, c, visible, Infinity);
  } else {
    // tiles too small to outline: the chain as a line through the centres, the tiles that
    // move over it
    ctx.beginPath();
    let last = -1;
    for (let i = 0; i < n; i++) {
      const X = sx(v, r.px[i]);
      if (last >= 0 && Math.abs(X - last) < 0.25 && i + 1 < n && r.cls[i] === 0) continue;
      if (i === 0) ctx.moveTo(X, sy(v, r.py[i])); else ctx.lineTo(X, sy(v, r.py[i]));
      last = X;
    }
    ctx.lineWidth = Math.max(r.w * k, 1.2);
    ctx.lineJoin = 'round';
    ctx.lineCap = 'round';
    ctx.strokeStyle = COL.line;
    ctx.stroke();
    for (let c = 1; c < 4; c++) tilesOfClass(p, c, visible, MAX_HIGHLIGHTS);
  }
  if (n <= DETAIL_TILES && (full || r.w * k >= DETAIL_PX)) {
    placeDetail(r, t);
    drawDetail2d(p, t, visible);
  }
}

function drawDetail2d(p, t, visible) {
  const r = p.run, ctx = p.ctx, v = p.view, k = v.k, n = r.tiles;
  // channels
  ctx.beginPath();
  for (let i = 0; i < n; i++) {
    if (!visible(i)) continue;
    const c = r.pc[i], s = r.ps[i], x = r.px[i], y = r.py[i];
    for (let m = 2 * i; m <= 2 * i + 1; m++) {
      const L = r.pathLines[r.mPath[m]];
      for (let q = 0; q < L.length; q += 2) {
        const X = sx(v, x + c * L[q] - s * L[q + 1]), Y = sy(v, y + s * L[q] + c * L[q + 1]);
        if (q === 0) ctx.moveTo(X, Y); else ctx.lineTo(X, Y);
      }
    }
  }
  ctx.lineWidth = Math.max(2.2 * r.magnetR * k, 1);
  ctx.lineCap = 'round';
  ctx.lineJoin = 'round';
  ctx.strokeStyle = COL.path;
  ctx.stroke();
  // hinges of the joints that fold, then magnets by pole, moving ones ringed
  const disc = function (X, Y, rad) { ctx.moveTo(X + rad, Y); ctx.arc(X, Y, rad, 0, 2 * Math.PI); };
  const hr = Math.max(0.06 * r.w * k, 1.5);
  for (let pass = 0; pass < 2; pass++) {
    ctx.beginPath();
    for (let q = 0; q < r.joint.length; q++) {
      const j = r.joint[q];
      if (r.turning[j] === pass && visible(j)) disc(sx(v, r.hx[q]), sy(v, r.hy[q]), hr);
    }
    ctx.fillStyle = pass ? COL.hingeTurning : COL.hinge;
    ctx.fill();
  }
  const mr = Math.max(r.magnetR * k, 1);
  ctx.beginPath();
  for (let m = 0; m < 2 * n; m++) {
    if (r.magnetMoving[m] && visible(m >> 1)) disc(sx(v, r.mx[m]), sy(v, r.my[m]), mr + Math.max(0.5 * mr, 1.5));
  }
  ctx.fillStyle = COL.movingRing;
  ctx.fill();
  for (let pole = 0; pole < 2; pole++) {
    ctx.beginPath();
    for (let i = 0; i < n; i++) {
      const m = 2 * i + pole;
      if (visible(i)) disc(sx(v, r.mx[m]), sy(v, r.my[m]), mr);
    }
    ctx.fillStyle = pole ? COL.poleB : COL.poleA;
    ctx.fill();
  }
}
