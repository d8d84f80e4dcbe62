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
  // poses: kinematics::poses_at_angles
  const w = r.w, hw = 0.5 * w, h = r.hingeY;
  let x = 0, y = 0, ang = 0, c = 1, s = 0;
  r.px[0] = 0; r.py[0] = 0; r.pa[0] = 0; r.pc[0] = 1; r.ps[0] = 0;
  for (let j = 0; j + 1 < n; j++) {
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
  r.cls.fill(0);
  for (let k = 0; k < 2 * n; k++) {
    const sh = r.mShape[k];
    let m = 0;
    if (sh !== 0 && shapeMoves(r, sh)) {
      const dt = t - r.mStart[k];
      m = dt >= 0 && dt < shapeLength(r, sh) && t < r.end ? 1 : 0;
    }
    r.magnetMoving[k] = m;
    if (m) { moving++; r.cls[k >> 1] = 1; }
  }
  for (let j = 0; j + 1 < n; j++) {
    if (r.turning[j]) { r.cls[j] = 2; r.cls[j + 1] = 2; }
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
