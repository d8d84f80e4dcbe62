// foldchain viewer: plays one or more runs of a self-folding tile chain from their packed
// tracks (see src/viewer/mod.rs). Tile poses are composed from the joint angles as
// foldchain::kinematics::poses_at_angles does; magnets are placed on their paths in closed
// form (foldchain::viewer::PathForm).
(function () {
  'use strict';

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
        m = dt >= 0 && dt < shapeLength(r, sh) ? 1 : 0;
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

  // ---------- drawing ----------
  function octagonPath(ctx, r, i, v) {
    const c = r.pc[i], s = r.ps[i], x = r.px[i], y = r.py[i], o = r.oct;
    for (let q = 0; q < 16; q += 2) {
      const sx = v.ox + (x + c * o[q] - s * o[q + 1]) * v.k;
      const sy = v.oy - (y + s * o[q] + c * o[q + 1]) * v.k;
      if (q === 0) ctx.moveTo(sx, sy); else ctx.lineTo(sx, sy);
    }
    ctx.closePath();
  }

  function draw(p, t, opts) {
    const r = p.run, ctx = p.ctx, v = p.view;
    const W = p.cssW, H = p.cssH, dpr = p.dpr;
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.fillStyle = COL.bg;
    ctx.fillRect(0, 0, W, H);
    const k = v.k, tilePx = r.w * k, n = r.tiles;
    const full = opts.detailAll;
    // target outline
    if (r.target.length) {
      ctx.beginPath();
      for (const ring of r.target) {
        ring.forEach(function (q, i) {
          const sx = v.ox + q[0] * k, sy = v.oy - q[1] * k;
          if (i === 0) ctx.moveTo(sx, sy); else ctx.lineTo(sx, sy);
        });
        ctx.closePath();
      }
      ctx.fillStyle = COL.targetFill;
      ctx.fill('evenodd');
      ctx.lineWidth = 1.5;
      ctx.strokeStyle = COL.targetEdge;
      ctx.stroke();
    }
    const margin = r.w * 0.8 * k;
    const visible = function (i) {
      if (full) return true;
      const sx = v.ox + r.px[i] * k, sy = v.oy - r.py[i] * k;
      return sx > -margin && sx < W + margin && sy > -margin && sy < H + margin;
    };
    const outlines = full || tilePx >= OUTLINE_PX;
    const fills = [COL.tile, COL.moving, COL.folding, COL.hit];
    if (outlines) {
      for (let c = 0; c < 4; c++) {
        ctx.beginPath();
        let any = false;
        for (let i = 0; i < n; i++) {
          if (r.cls[i] === c && visible(i)) { octagonPath(ctx, r, i, v); any = true; }
        }
        if (!any) continue;
        ctx.fillStyle = fills[c];
        ctx.fill();
        ctx.lineWidth = c === 3 ? 2 : Math.min(Math.max(0.04 * tilePx, 0.3), 1.5);
        ctx.strokeStyle = c === 3 ? COL.hitEdge : COL.edge;
        ctx.stroke();
      }
    } else {
      // tiles too small to outline: the chain as a line through the centres
      ctx.beginPath();
      let last = -1;
      for (let i = 0; i < n; i++) {
        const sx = v.ox + r.px[i] * k, sy = v.oy - r.py[i] * k;
        if (last >= 0 && Math.abs(sx - last) < 0.25 && i + 1 < n && r.cls[i] === 0) continue;
        if (i === 0) ctx.moveTo(sx, sy); else ctx.lineTo(sx, sy);
        last = sx;
      }
      ctx.lineWidth = Math.max(tilePx, 1.2);
      ctx.lineJoin = 'round'; ctx.lineCap = 'round';
      ctx.strokeStyle = COL.line;
      ctx.stroke();
      for (let c = 1; c < 4; c++) {
        ctx.beginPath();
        let shown = 0;
        for (let i = 0; i < n && shown < MAX_HIGHLIGHTS; i++) {
          if (r.cls[i] === c && visible(i)) { octagonPath(ctx, r, i, v); shown++; }
        }
        if (!shown) continue;
        ctx.fillStyle = fills[c];
        ctx.fill();
        ctx.lineWidth = c === 3 ? 1.5 : 0.5;
        ctx.strokeStyle = c === 3 ? COL.hitEdge : COL.edge;
        ctx.stroke();
      }
    }
    if (n <= DETAIL_TILES && (full || tilePx >= DETAIL_PX)) drawDetail(p, t, visible);
    // the RI, at the outer edge of tile 0
    const rx = r.px[0] + r.pc[0] * r.ri[0] - r.ps[0] * r.ri[1];
    const ry = r.py[0] + r.ps[0] * r.ri[0] + r.pc[0] * r.ri[1];
    const rr = Math.max(r.magnetR * k, 3);
    ctx.beginPath();
    ctx.arc(v.ox + rx * k, v.oy - ry * k, rr, 0, 2 * Math.PI);
    ctx.fillStyle = COL.ri; ctx.fill();
    ctx.font = '11px sans-serif'; ctx.textAlign = 'right';
    ctx.fillText('RI', v.ox + rx * k - rr - 3, v.oy - ry * k + 4);
    // the collision: a ring around the two tiles
    if (r.hit) {
      const a = r.hit[0], b = r.hit[1];
      const cx = v.ox + 0.5 * (r.px[a] + r.px[b]) * k, cy = v.oy - 0.5 * (r.py[a] + r.py[b]) * k;
      const span = Math.hypot(r.px[a] - r.px[b], r.py[a] - r.py[b]) * k;
      ctx.beginPath();
      ctx.arc(cx, cy, Math.max(0.5 * span + tilePx, 14), 0, 2 * Math.PI);
      ctx.lineWidth = 2.5; ctx.strokeStyle = COL.hit; ctx.stroke();
    }
  }

  function drawDetail(p, t, visible) {
    const r = p.run, ctx = p.ctx, v = p.view, k = v.k, n = r.tiles;
    const pt = [0, 0];
    // channels
    ctx.beginPath();
    for (let i = 0; i < n; i++) {
      if (!visible(i)) continue;
      const c = r.pc[i], s = r.ps[i], x = r.px[i], y = r.py[i];
      for (let m = 2 * i; m <= 2 * i + 1; m++) {
        const L = r.pathLines[r.mPath[m]];
        for (let q = 0; q < L.length; q += 2) {
          const sx = v.ox + (x + c * L[q] - s * L[q + 1]) * k;
          const sy = v.oy - (y + s * L[q] + c * L[q + 1]) * k;
          if (q === 0) ctx.moveTo(sx, sy); else ctx.lineTo(sx, sy);
        }
      }
    }
    ctx.lineWidth = Math.max(2.2 * r.magnetR * k, 1);
    ctx.lineCap = 'round'; ctx.lineJoin = 'round';
    ctx.strokeStyle = COL.path;
    ctx.stroke();
    // hinges of the joints that fold
    const hr = Math.max(0.06 * r.w * k, 1.5);
    for (let pass = 0; pass < 2; pass++) {
      ctx.beginPath();
      for (let q = 0; q < r.joint.length; q++) {
        const j = r.joint[q];
        if (r.turning[j] !== pass || !visible(j)) continue;
        const hx = 0.5 * r.w, hy = r.jSign[q] * r.hingeY;
        const sx = v.ox + (r.px[j] + r.pc[j] * hx - r.ps[j] * hy) * k;
        const sy = v.oy - (r.py[j] + r.ps[j] * hx + r.pc[j] * hy) * k;
        ctx.moveTo(sx + hr, sy);
        ctx.arc(sx, sy, hr, 0, 2 * Math.PI);
      }
      ctx.fillStyle = pass ? COL.hingeTurning : COL.hinge;
      ctx.fill();
    }
    // magnets, by pole; moving ones ringed
    const mr = Math.max(r.magnetR * k, 1);
    const ringed = new Path2D();
    for (let pole = 0; pole < 2; pole++) {
      ctx.beginPath();
      for (let i = 0; i < n; i++) {
        if (!visible(i)) continue;
        const m = 2 * i + pole;
        const sh = r.mShape[m];
        const u = sh === 0 ? 0 : shapeAt(r, sh, t - r.mStart[m]);
        pathPoint(r.paths[r.mPath[m]], u, pt);
        const sx = v.ox + (r.px[i] + r.pc[i] * pt[0] - r.ps[i] * pt[1]) * k;
        const sy = v.oy - (r.py[i] + r.ps[i] * pt[0] + r.pc[i] * pt[1]) * k;
        ctx.moveTo(sx + mr, sy);
        ctx.arc(sx, sy, mr, 0, 2 * Math.PI);
        if (r.magnetMoving[m]) { ringed.moveTo(sx + mr + 1, sy); ringed.arc(sx, sy, mr + 1, 0, 2 * Math.PI); }
      }
      ctx.fillStyle = pole ? COL.poleB : COL.poleA;
      ctx.fill();
    }
    ctx.lineWidth = Math.max(0.5 * mr, 1.5);
    ctx.strokeStyle = COL.movingRing;
    ctx.stroke(ringed);
  }

  // ---------- the page ----------
  const runs = JSON.parse(document.getElementById('run-data').textContent).map(decode);
  const body = document.body;
  const end = runs.reduce(function (m, r) { return Math.max(m, r.end); }, 0);
  const panelsEl = document.getElementById('panels');
  const panels = runs.map(function (r) {
    const el = document.createElement('section');
    el.className = 'panel';
    el.dataset.run = r.label || 'run';
    const canvas = document.createElement('canvas');
    const cap = document.createElement('div');
    cap.className = 'caption';
    cap.innerHTML = '<div><span class="label"></span><span class="title"></span></div>' +
      '<div class="note"></div><div class="state"></div><div class="hit"></div>';
    cap.querySelector('.label').textContent = r.label;
    cap.querySelector('.title').textContent = runs.length > 1 ? '' : '';
    cap.querySelector('.note').textContent = r.note;
    el.appendChild(canvas); el.appendChild(cap);
    panelsEl.appendChild(el);
    return { run: r, el: el, canvas: canvas, ctx: canvas.getContext('2d', { alpha: false }),
      state: cap.querySelector('.state'), hitEl: cap.querySelector('.hit'),
      view: { ox: 0, oy: 0, k: 1 }, cssW: 1, cssH: 1, dpr: 1 };
  });

  // the shared view: world centre and pixels per mm
  const cam = { x: 0, y: 0, k: 1 };
  function fitAll() {
    let b = null;
    runs.forEach(function (r) {
      const q = r.box;
      b = b ? [Math.min(b[0], q[0]), Math.min(b[1], q[1]), Math.max(b[2], q[2]), Math.max(b[3], q[3])] : q.slice();
    });
    const p = panels[0];
    cam.x = 0.5 * (b[0] + b[2]); cam.y = 0.5 * (b[1] + b[3]);
    cam.k = Math.min((p.cssW - 20) / Math.max(b[2] - b[0], 1e-9), (p.cssH - 70) / Math.max(b[3] - b[1], 1e-9));
    // leave room for the caption
    cam.y += 25 / cam.k;
  }
  function layout() {
    panels.forEach(function (p) {
      const rect = p.el.getBoundingClientRect();
      p.dpr = window.devicePixelRatio || 1;
      p.cssW = Math.max(rect.width, 1); p.cssH = Math.max(rect.height, 1);
      p.canvas.width = Math.round(p.cssW * p.dpr);
      p.canvas.height = Math.round(p.cssH * p.dpr);
    });
  }
  function applyCam() {
    panels.forEach(function (p) {
      p.view.k = cam.k;
      p.view.ox = 0.5 * p.cssW - cam.x * cam.k;
      p.view.oy = 0.5 * p.cssH + cam.y * cam.k;
    });
  }

  // every moment something starts or stops, for the event jumps
  const events = (function () {
    const list = [0, end];
    runs.forEach(function (r) {
      for (let k = 0; k < r.mShape.length; k++) {
        const s = r.mShape[k];
        if (s !== 0 && shapeMoves(r, s)) list.push(r.mStart[k], r.mStart[k] + shapeLength(r, s));
      }
      for (let i = 0; i < r.joint.length; i++) {
        const s = r.jShape[i];
        if (shapeMoves(r, s)) list.push(r.jStart[i], r.jStart[i] + shapeLength(r, s));
      }
      if (r.collision && r.collision[0] !== null) list.push(r.collision[0]);
    });
    const a = Float64Array.from(list).sort();
    const out = [];
    for (let i = 0; i < a.length; i++) if (!out.length || a[i] > out[out.length - 1]) out.push(a[i]);
    return out;
  })();
  const eps = 1e-9 * Math.max(1, end);

  const state = { t: 0, playing: false, last: null, speed: end > 0 ? end / 20 : 1 };
  const opts = { detailAll: false, poses: false };
  const playBtn = document.getElementById('play');
  const scrub = document.getElementById('scrub');
  const clock = document.getElementById('clock');
  const speedSel = document.getElementById('speed');

  function fmt(x) { return x < 1e-3 && x > 0 ? x.toExponential(3) : x.toFixed(4); }

  function render() {
    const t0 = performance.now();
    const t = state.t;
    panels.forEach(function (p) {
      update(p.run, t);
      draw(p, t, opts);
    });
    if (opts.flush) panels.forEach(function (p) { p.ctx.getImageData(0, 0, 1, 1); });
    const ms = performance.now() - t0;
    panels.forEach(function (p) {
      const r = p.run;
      p.el.dataset.folded = r.folded;
      p.el.dataset.moving = r.moving;
      p.el.dataset.collision = r.hit ? r.hit[0] + ',' + r.hit[1] : '';
      p.state.textContent = r.folded + ' of ' + r.joint.length + ' folds made, ' + r.moving + ' magnets moving' +
        (runs.length > 1 ? ' (ends at ' + fmt(r.end) + ' s)' : '');
      p.hitEl.textContent = r.hit ? 'collision: tiles ' + r.hit[0] + ' and ' + r.hit[1] +
        (r.collision[0] === null ? ' in the final shape' : ' at t = ' + fmt(r.collision[0]) + ' s') : '';
      if (opts.poses) {
        const a = [];
        for (let i = 0; i < r.tiles; i++) a.push(r.px[i] + ',' + r.py[i] + ',' + r.pa[i]);
        p.el.dataset.poses = a.join(';');
      }
    });
    const first = panels[0];
    body.dataset.time = String(t);
    body.dataset.folded = first.run.folded;
    body.dataset.moving = first.run.moving;
    body.dataset.collision = first.el.dataset.collision;
    body.dataset.renderMs = ms.toFixed(2);
    const cr = first.canvas.getBoundingClientRect();
    body.dataset.view = [first.view.k, cr.left + first.view.ox, cr.top + first.view.oy].join(',');
    clock.textContent = 't = ' + fmt(t) + ' s of ' + fmt(end) + ' s';
    scrub.value = end > 0 ? Math.round(t / end * 1e6) : 0;
    playBtn.innerHTML = state.playing ? '&#10074;&#10074;' : '&#9654;';
    return ms;
  }

  function setTime(t, keep) {
    state.t = Math.min(Math.max(t, 0), end);
    render();
    if (!keep && !state.playing) {
      try { history.replaceState(null, '', '#t=' + (state.t >= end ? 'end' : state.t)); } catch (e) { /* file: may refuse */ }
    }
  }
  function frame(ts) {
    if (!state.playing) return;
    if (state.last !== null) {
      state.t += (ts - state.last) / 1000 * state.speed;
      if (state.t >= end) { state.t = end; state.playing = false; }
    }
    state.last = ts;
    render();
    if (state.playing) requestAnimationFrame(frame);
  }
  function play(on) {
    state.playing = on;
    state.last = null;
    if (on) {
      if (state.t >= end) state.t = 0;
      requestAnimationFrame(frame);
    } else {
      setTime(state.t);
    }
    render();
  }
  function jump(dir) {
    state.playing = false;
    let t = state.t;
    if (dir > 0) {
      let i = 0, j = events.length;
      while (i < j) { const m = (i + j) >> 1; if (events[m] <= t + eps) i = m + 1; else j = m; }
      t = i < events.length ? events[i] : end;
    } else {
      let i = 0, j = events.length;
      while (i < j) { const m = (i + j) >> 1; if (events[m] < t - eps) i = m + 1; else j = m; }
      t = i > 0 ? events[i - 1] : 0;
    }
    setTime(t);
  }
  function zoom(f, sx, sy) {
    const p = panels[0];
    if (sx === undefined) { sx = 0.5 * p.cssW; sy = 0.5 * p.cssH; }
    const wx = (sx - p.view.ox) / cam.k, wy = (p.view.oy - sy) / cam.k;
    cam.k *= f;
    cam.x = wx - (sx - 0.5 * p.cssW) / cam.k;
    cam.y = wy + (sy - 0.5 * p.cssH) / cam.k;
    applyCam(); render();
  }
  function pan(dx, dy) {
    cam.x -= dx / cam.k; cam.y += dy / cam.k;
    applyCam(); render();
  }

  // speed: how long the whole run takes to play
  [[320, 'run in 320 s'], [80, 'run in 80 s'], [20, 'run in 20 s'], [5, 'run in 5 s'], [1, 'run in 1 s']].forEach(function (o) {
    const e = document.createElement('option');
    e.value = String(end > 0 ? end / o[0] : 1); e.textContent = o[1];
    if (o[0] === 20) e.selected = true;
    speedSel.appendChild(e);
  });
  const rt = document.createElement('option');
  rt.value = '1'; rt.textContent = 'real time';
  speedSel.appendChild(rt);
  speedSel.addEventListener('change', function () { state.speed = parseFloat(speedSel.value); });

  playBtn.addEventListener('click', function () { play(!state.playing); });
  document.getElementById('prev').addEventListener('click', function () { jump(-1); });
  document.getElementById('next').addEventListener('click', function () { jump(1); });
  document.getElementById('fit').addEventListener('click', function () { fitAll(); applyCam(); render(); });
  scrub.addEventListener('input', function () { state.playing = false; setTime(scrub.value / 1e6 * end); });
  const hitRun = runs.find(function (r) { return r.collision; });
  const ticks = document.getElementById('ticks');
  runs.forEach(function (r) {
    if (r.collision && end > 0) {
      const b = document.createElement('b');
      b.style.left = (100 * (r.collision[0] === null ? r.end : r.collision[0]) / end) + '%';
      b.title = 'collision (' + r.label + ')';
      ticks.appendChild(b);
    }
  });
  if (hitRun) {
    const cb = document.getElementById('collision-jump');
    cb.hidden = false;
    cb.addEventListener('click', function () {
      state.playing = false;
      setTime(hitRun.collision[0] === null ? hitRun.end : hitRun.collision[0]);
    });
  }
  panels.forEach(function (p) {
    let drag = null;
    p.canvas.addEventListener('pointerdown', function (e) {
      drag = { x: e.clientX, y: e.clientY };
      p.canvas.classList.add('dragging');
      p.canvas.setPointerCapture(e.pointerId);
    });
    p.canvas.addEventListener('pointermove', function (e) {
      if (!drag) return;
      pan(e.clientX - drag.x, e.clientY - drag.y);
      drag = { x: e.clientX, y: e.clientY };
    });
    const stop = function () { drag = null; p.canvas.classList.remove('dragging'); };
    p.canvas.addEventListener('pointerup', stop);
    p.canvas.addEventListener('pointercancel', stop);
    p.canvas.addEventListener('wheel', function (e) {
      e.preventDefault();
      const rect = p.canvas.getBoundingClientRect();
      zoom(Math.exp(-e.deltaY * 0.0015), e.clientX - rect.left, e.clientY - rect.top);
    }, { passive: false });
  });
  document.addEventListener('keydown', function (e) {
    if (e.target && e.target.tagName === 'SELECT') return;
    const step = 0.1 * panels[0].cssW;
    switch (e.key) {
      case ' ': play(!state.playing); break;
      case '[': case ',': jump(-1); break;
      case ']': case '.': jump(1); break;
      case 'Home': state.playing = false; setTime(0); break;
      case 'End': state.playing = false; setTime(end); break;
      case '+': case '=': zoom(1.25); break;
      case '-': case '_': zoom(0.8); break;
      case '0': case 'f': fitAll(); applyCam(); render(); break;
      case 'ArrowLeft': pan(step, 0); break;
      case 'ArrowRight': pan(-step, 0); break;
      case 'ArrowUp': pan(0, step); break;
      case 'ArrowDown': pan(0, -step); break;
      default: return;
    }
    e.preventDefault();
  });
  window.addEventListener('resize', function () { layout(); applyCam(); render(); });

  // #t=SECONDS or #t=end, and test options (poses=1, detail=all, bench=N)
  function readHash() {
    const h = {};
    location.hash.replace(/^#/, '').split('&').forEach(function (kv) {
      const i = kv.indexOf('=');
      if (i > 0) h[decodeURIComponent(kv.slice(0, i))] = decodeURIComponent(kv.slice(i + 1));
    });
    return h;
  }
  function timeFrom(h) {
    if (h.t === undefined) return null;
    if (h.t === 'end') return end;
    const x = parseFloat(h.t);
    return isFinite(x) ? x : null;
  }
  window.addEventListener('hashchange', function () {
    const t = timeFrom(readHash());
    if (t !== null) { state.playing = false; setTime(t, true); }
  });

  layout();
  fitAll();
  applyCam();
  const hash = readHash();
  opts.detailAll = hash.detail === 'all';
  opts.poses = hash.poses === '1';
  const t0 = timeFrom(hash);
  state.t = Math.min(Math.max(t0 === null ? 0 : t0, 0), end);
  const bench = parseInt(hash.bench || '0', 10);
  if (bench > 0) {
    // frames at times spread over the run ending at the asked time, each flushed to pixels
    opts.flush = true;
    const target = state.t;
    let worst = 0, sum = 0;
    for (let i = 0; i < bench; i++) {
      state.t = target * (i + 1) / bench;
      const ms = render();
      worst = Math.max(worst, ms); sum += ms;
    }
    opts.flush = false;
    body.dataset.renderMsMax = worst.toFixed(2);
    body.dataset.renderMsMean = (sum / bench).toFixed(2);
    body.dataset.renderFrames = String(bench);
  } else {
    render();
  }
  if (t0 === null && end > 0) play(true);
})();
