// foldchain viewer, data: the packed run decoded, and the chain at a time t. Tile poses are
// composed from the joint angles as foldchain::kinematics::poses_at_angles does; magnets
// are placed on their paths in closed form (foldchain::viewer::PathForm).


// Tiles drawn as outlines when at least this many pixels wide; below, as a line through
// their centres.
const OUTLINE_PX = 2.5;
// Paths, magnets and hinges drawn when tiles are at least this many pixels wide.
const DETAIL_PX = 7;
// Chains longer than this are drawn as tiles only.
const DETAIL_TILES = 20000;
// Highlighted tiles drawn over the centre line, at most.
const MAX_HIGHLIGHTS = 4000;
const HALF_PI = Math.PI / 2;
const COL = {
  bg: '#fbfbf8', tile: '#e9e6df', moving: '#e4eefb', folding: '#c6dbf7', edge: '#55524c',
  line: '#b9b3a6', path: '#9c968a', hinge: '#333333', hingeTurning: '#1a56b8',
  poleA: '#d93025', poleB: '#188038', movingRing: '#ff9800', ri: '#7b1fa2',
  hit: '#ff2020', hitEdge: '#a00000', targetFill: 'rgba(242,230,184,0.55)',
  targetEdge: '#806000',
};
// tile fill by class: 0 at rest, 1 a magnet moving, 2 next to a turning joint, 3 collided
const TILE_FILL = [COL.tile, COL.moving, COL.folding, COL.hit];

// ---------- data ----------
function bytes(s) {
  const bin = atob(s);
  const u = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) u[i] = bin.charCodeAt(i);
  return u.buffer;
}
function ints(p) {
  const b = bytes(p.data);
  return p.width === 1 ? new Uint8Array(b) : p.width === 2 ? new Uint16Array(b) : new Uint32Array(b);
}

function pathPoint(p, u, out) {
  u = Math.min(Math.max(u, 0), p.length);
  if (p.arc && u > p.straight) {
    const a = p.arc;
    const phi = a[3] + a[4] * (u - p.straight) / a[2];
    out[0] = a[0] + a[2] * Math.cos(phi);
    out[1] = a[1] + a[2] * Math.sin(phi);
  } else {
    out[0] = p.rest + p.dir * Math.min(u, p.straight);
    out[1] = 0;
  }
}

function decode(d) {
  const r = {
    label: d.label, title: d.title, note: d.note, tiles: d.tiles, w: d.w, ri: d.ri,
    magnetR: d.magnet_r, end: d.end, collision: d.collision, box: d.view, target: d.target,
    paths: d.paths,
    mPath: ints(d.magnet_path), mShape: ints(d.magnet_shape),
    mStart: new Float64Array(bytes(d.magnet_start)),
    joint: ints(d.joint), jShape: ints(d.joint_shape),
    jStart: new Float64Array(bytes(d.joint_start)),
    sOff: ints(d.shape_offset), sDt: new Float32Array(bytes(d.shape_dt)),
    sVal: new Float32Array(bytes(d.shape_value)),
  };
  const n = r.tiles;
  r.angle = new Float64Array(Math.max(n - 1, 0));
  r.px = new Float64Array(n); r.py = new Float64Array(n);
  r.pa = new Float64Array(n); r.pc = new Float64Array(n); r.ps = new Float64Array(n);
  r.cls = new Uint8Array(n);
  r.turning = new Uint8Array(Math.max(n - 1, 0));
  r.magnetMoving = new Uint8Array(2 * n);
  r.mx = new Float64Array(2 * n); r.my = new Float64Array(2 * n);
  r.hx = new Float64Array(r.joint.length); r.hy = new Float64Array(r.joint.length);
  // when each magnet stops moving (-Infinity for those that never move)
  r.mEnd = new Float64Array(2 * n);
  for (let k = 0; k < 2 * n; k++) {
    const s = r.mShape[k];
    r.mEnd[k] = s !== 0 && shapeMoves(r, s) ? r.mStart[k] + shapeLength(r, s) : -Infinity;
  }
  // the magnets that move, by start time, with the latest end so far: those moving at t are
  // among the ones after the first whose latest end so far is past t and that have started
  const movers = [];
  for (let k = 0; k < 2 * n; k++) if (r.mEnd[k] > -Infinity) movers.push(k);
  movers.sort(function (a, b) { return r.mStart[a] - r.mStart[b]; });
  r.mOrder = Uint32Array.from(movers);
  r.mOrderStart = new Float64Array(movers.length);
  r.mOrderEnd = new Float64Array(movers.length);
  let latest = -Infinity;
  movers.forEach(function (k, q) {
    latest = Math.max(latest, r.mEnd[k]);
    r.mOrderStart[q] = r.mStart[k];
    r.mOrderEnd[q] = latest;
  });
  // a joint's fold direction: the sign of its largest angle
  r.jSign = new Float64Array(r.joint.length);
  for (let i = 0; i < r.joint.length; i++) {
    const s = r.jShape[i];
    let best = 0;
    for (let q = r.sOff[s]; q < r.sOff[s + 1]; q++) if (Math.abs(r.sVal[q]) > Math.abs(best)) best = r.sVal[q];
    r.jSign[i] = best >= 0 ? 1 : -1;
  }
  // each path as a polyline in its tile's frame, for drawing the channel
  const pt = [0, 0];
  r.pathLines = r.paths.map(function (p) {
    const pts = [];
    const steps = p.arc ? 12 : 1;
    pathPoint(p, 0, pt); pts.push(pt[0], pt[1]);
    if (p.arc) { pathPoint(p, p.straight, pt); pts.push(pt[0], pt[1]); }
    for (let i = 1; i <= steps; i++) {
      pathPoint(p, p.straight + (p.length - p.straight) * i / steps, pt);
      pts.push(pt[0], pt[1]);
    }
    return pts;
  });
  // octagon vertices and hinges in the tile frame
  const h = 0.5 * r.w * (Math.SQRT2 - 1);
  const hw = 0.5 * r.w;
  r.oct = [hw, -h, hw, h, h, hw, -h, hw, -hw, h, -hw, -h, -h, -hw, h, -hw];
  r.hingeY = h;
  return r;
}

// the value of shape s, dt seconds after its start (Track::value_at)
function shapeAt(r, s, dt) {
  const a = r.sOff[s], b = r.sOff[s + 1];
  if (b - a < 2 || dt <= r.sDt[a]) return r.sVal[a];
  if (dt >= r.sDt[b - 1]) return r.sVal[b - 1];
  let lo = a, hi = b - 1;
  while (hi - lo > 1) {
    const m = (lo + hi) >> 1;
    if (r.sDt[m] < dt) lo = m; else hi = m;
  }
  const t0 = r.sDt[lo], t1 = r.sDt[hi];
  return t1 > t0 ? r.sVal[lo] + (r.sVal[hi] - r.sVal[lo]) * (dt - t0) / (t1 - t0) : r.sVal[hi];
}
function shapeLength(r, s) { return r.sDt[r.sOff[s + 1] - 1]; }
function shapeMoves(r, s) { return r.sOff[s + 1] - r.sOff[s] >= 2; }

function wrap(a) {
  if (a >= -Math.PI && a < Math.PI) return a;
  const t = 2 * Math.PI;
  return ((a + Math.PI) % t + t) % t - Math.PI;
}

// ---------- the chain at time t ----------
function update(r, t) {
  const n = r.tiles;
  r.angle.fill(0);
  r.turning.fill(0);
  let folded = 0;
  for (let i = 0; i < r.joint.length; i++) {
    const j = r.joint[i], s = r.jShape[i], dt = t - r.jStart[i];
    const a = shapeAt(r, s, dt);
    r.angle[j] = a;
    if (Math.abs(a) >= HALF_PI * (1 - 1e-6)) folded++;
    if (shapeMoves(r, s) && dt >= 0 && dt < shapeLength(r, s)) r.turning[j] = 1;
  }
  // poses: kinematics::poses_at_angles; tiles before the first joint still to settle are
  // where they end (once prepareCamera has recorded the final poses)
  const w = r.w, hw = 0.5 * w, h = r.hingeY;
  let x = 0, y = 0, ang = 0, c = 1, s = 0, from = 0;
  r.px[0] = 0; r.py[0] = 0; r.pa[0] = 0; r.pc[0] = 1; r.ps[0] = 0;
  if (r.settle) {
    from = settledAt(r, t);
    const e = from + 1;
    r.px.set(r.fx.subarray(0, e)); r.py.set(r.fy.subarray(0, e)); r.pa.set(r.fa.subarray(0, e));
    r.pc.set(r.fc.subarray(0, e)); r.ps.set(r.fs.subarray(0, e));
    x = r.px[from]; y = r.py[from]; ang = r.pa[from]; c = r.pc[from]; s = r.ps[from];
  }
  for (let j = from; j + 1 < n; j++) {
    const a = r.angle[j];
    let lx = w, ly = 0;
    if (a !== 0) {
      const hy = a >= 0 ? h : -h;
      const sa = Math.sin(a), ca = Math.cos(a);
      lx = hw + ca * hw + sa * hy;
      ly = hy + sa * hw - ca * hy;
    }
    x += c * lx - s * ly;
    y += s * lx + c * ly;
    if (a !== 0) {
      ang = wrap(ang + a);
      c = Math.cos(ang); s = Math.sin(ang);
    }
    r.px[j + 1] = x; r.py[j + 1] = y; r.pa[j + 1] = ang; r.pc[j + 1] = c; r.ps[j + 1] = s;
  }
  // what moves
  let moving = 0;
  const mm = r.magnetMoving, cls = r.cls;
  cls.fill(0);
  mm.fill(0);
  if (t < r.end) {
    const os = r.mOrderStart, oe = r.mOrderEnd;
    let lo = 0, hi = os.length;
    while (lo < hi) { const m = (lo + hi) >> 1; if (oe[m] <= t) lo = m + 1; else hi = m; }
    for (let q = lo; q < os.length && os[q] <= t; q++) {
      const k = r.mOrder[q];
      if (t < r.mEnd[k]) { mm[k] = 1; moving++; cls[k >> 1] = 1; }
    }
  }
  for (let q = 0; q < r.joint.length; q++) {
    const j = r.joint[q];
    if (r.turning[j]) { cls[j] = 2; cls[j + 1] = 2; }
  }
  r.hit = null;
  if (r.collision) {
    const ct = r.collision[0];
    if ((ct === null && t >= r.end) || (ct !== null && t >= ct)) {
      r.hit = r.collision[1];
      r.cls[r.hit[0]] = 3; r.cls[r.hit[1]] = 3;
    }
  }
  r.folded = folded;
  r.moving = moving;
}

// world positions of every magnet and of the hinge of every joint that folds, at time t
// (after update)
function placeDetail(r, t) {
  const pt = [0, 0];
  for (let m = 0; m < 2 * r.tiles; m++) {
    const i = m >> 1, sh = r.mShape[m];
    pathPoint(r.paths[r.mPath[m]], sh === 0 ? 0 : shapeAt(r, sh, t - r.mStart[m]), pt);
    r.mx[m] = r.px[i] + r.pc[i] * pt[0] - r.ps[i] * pt[1];
    r.my[m] = r.py[i] + r.ps[i] * pt[0] + r.pc[i] * pt[1];
  }
  const hx = 0.5 * r.w;
  for (let q = 0; q < r.joint.length; q++) {
    const j = r.joint[q], hy = r.jSign[q] * r.hingeY;
    r.hx[q] = r.px[j] + r.pc[j] * hx - r.ps[j] * hy;
    r.hy[q] = r.py[j] + r.ps[j] * hx + r.pc[j] * hy;
  }
}

// ---------- what the camera follows ----------
// The final poses' running box (tiles 0..i) and each joint's settling time (when it
// reaches its final angle) as a prefix maximum: tiles up to the first joint still to settle
// are in their final pose. Leaves the chain at its end.
function prepareCamera(r) {
  const n = r.tiles;
  update(r, r.end);
  r.bx0 = new Float64Array(n); r.by0 = new Float64Array(n);
  r.bx1 = new Float64Array(n); r.by1 = new Float64Array(n);
  r.fx = Float64Array.from(r.px); r.fy = Float64Array.from(r.py); r.fa = Float64Array.from(r.pa);
  r.fc = Float64Array.from(r.pc); r.fs = Float64Array.from(r.ps);
  let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
  for (let i = 0; i < n; i++) {
    x0 = Math.min(x0, r.px[i]); y0 = Math.min(y0, r.py[i]);
    x1 = Math.max(x1, r.px[i]); y1 = Math.max(y1, r.py[i]);
    r.bx0[i] = x0; r.by0[i] = y0; r.bx1[i] = x1; r.by1[i] = y1;
  }
  const settle = new Float64Array(Math.max(n - 1, 0)).fill(-Infinity);
  for (let q = 0; q < r.joint.length; q++) {
    const j = r.joint[q], s = r.jShape[q];
    if (shapeMoves(r, s)) settle[j] = Math.max(settle[j], r.jStart[q] + shapeLength(r, s));
  }
  for (let j = 1; j < n - 1; j++) settle[j] = Math.max(settle[j], settle[j - 1]);
  r.settle = settle;
  // the folded part's reach on a grid of REACH_STEPS over the run, made to grow at most
  // twice as fast as on average by growing earlier (a pass from the end): where the reach
  // leaps (a straight row settles at once) it grows steadily before the leap instead
  const reach = new Float64Array(REACH_STEPS + 1);
  for (let i = 0; i <= REACH_STEPS; i++) reach[i] = foldedTo(r, r.end * i / REACH_STEPS);
  const most = 2 * Math.max(reach[REACH_STEPS] - reach[0], 1) / REACH_STEPS;
  for (let i = REACH_STEPS - 1; i >= 0; i--) reach[i] = Math.max(reach[i], reach[i + 1] - most);
  r.reach = reach;
}

// grid steps of the folded part's smoothed reach
const REACH_STEPS = 1024;

// how far the folded part reaches at time t, smoothed (prepareCamera), in tiles
function reachAt(r, t) {
  if (!(r.end > 0) || t >= r.end) return r.tiles - 1;
  const u = Math.max(t, 0) / r.end * REACH_STEPS, i = Math.min(Math.floor(u), REACH_STEPS - 1);
  return r.reach[i] + (u - i) * (r.reach[i + 1] - r.reach[i]);
}

// the first tile that may be away from its final pose at time t (tiles before it are where
// they end)
function settledAt(r, t) {
  let lo = 0, hi = r.settle.length;
  while (lo < hi) { const m = (lo + hi) >> 1; if (r.settle[m] <= t) lo = m + 1; else hi = m; }
  return lo;
}

// how far the folded part reaches at time t, in tiles, continuous in t: from the first
// unsettled tile when the last joint before it settled to the next such tile when the
// joint holding it back settles
function foldedTo(r, t) {
  const j = settledAt(r, t);
  if (j >= r.settle.length) return r.tiles - 1;
  const from = j > 0 ? Math.max(r.settle[j - 1], 0) : 0, to = r.settle[j];
  if (!(to > from) || t <= from) return j;
  const next = settledAt(r, to);
  return j + (next - j) * Math.min((t - from) / (to - from), 1);
}
