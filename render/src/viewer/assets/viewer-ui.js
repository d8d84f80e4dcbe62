// foldchain viewer, the page: panels, the shared clock and view, controls, the URL hash,
// the state on <body>, and the test options.

// options from the hash: view=X0,Y0,X1,Y1, follow=1, and for tests poses=1, detail=all,
// renderer=2d|raster, bench=N, probe=T1,T2,...
const hash = readHash();
const opts = { detailAll: hash.detail === 'all', poses: hash.poses === '1', renderer: hash.renderer || 'auto', flush: false };
const runs = JSON.parse(document.getElementById('run-data').textContent).map(decode);
const body = document.body;
const end = runs.reduce(function (m, r) { return Math.max(m, r.end); }, 0);
const panelsEl = document.getElementById('panels');
const panels = runs.map(function (r) {
  const el = document.createElement('section');
  el.className = 'panel';
  el.dataset.run = r.label || 'run';
  // three layers: background, target and (few tiles in view) the chain drawn by the
  // canvas; the chain rasterised by the page (many tiles in view); RI and collision
  const under = document.createElement('canvas');
  const mid = document.createElement('canvas');
  const canvas = document.createElement('canvas');
  const cap = document.createElement('div');
  cap.className = 'caption';
  cap.innerHTML = '<div><span class="label"></span><span class="title"></span></div>' +
    '<div class="note"></div><div class="state"></div><div class="hit"></div>';
  cap.querySelector('.label').textContent = r.label;
  cap.querySelector('.note').textContent = r.note;
  el.appendChild(under); el.appendChild(mid); el.appendChild(canvas); el.appendChild(cap);
  panelsEl.appendChild(el);
  return { run: r, el: el, canvas: canvas, under: under, mid: mid, raster: makeRaster(mid), rastered: false,
    ctx: under.getContext('2d', { alpha: false }), overCtx: canvas.getContext('2d'),
    state: cap.querySelector('.state'), hitEl: cap.querySelector('.hit'),
    view: { ox: 0, oy: 0, k: 1 }, cssW: 1, cssH: 1, dpr: 1 };
});

panels.forEach(function (p) { p.midCtx = p.mid.getContext('2d'); });

// every tile's pose, 'x,y,angle;...' (mm, radians)
function posesText(r) {
  const a = [];
  for (let i = 0; i < r.tiles; i++) a.push(r.px[i] + ',' + r.py[i] + ',' + r.pa[i]);
  return a.join(';');
}

// how many tile centres lie in the panel
function inView(p) {
  const r = p.run, v = p.view, m = r.w * v.k;
  let count = 0;
  for (let i = 0; i < r.tiles; i++) {
    const X = v.ox + r.px[i] * v.k, Y = v.oy - r.py[i] * v.k;
    if (X > -m && X < p.cssW + m && Y > -m && Y < p.cssH + m) count++;
  }
  return count;
}

// the shared view: the world point at the panels' top left corner (mm) and pixels per mm;
// a resized window keeps that corner where it is
const cam = { x: 0, y: 0, k: 1 };
// the view holding the box b (world mm), or the whole run
function fitAll(b) {
  if (!b) {
    runs.forEach(function (r) {
      const q = r.box;
      b = b ? [Math.min(b[0], q[0]), Math.min(b[1], q[1]), Math.max(b[2], q[2]), Math.max(b[3], q[3])] : q.slice();
    });
  }
  const p = panels[0];
  // leave room for the caption (70 px at the top)
  cam.k = Math.min((p.cssW - 20) / Math.max(b[2] - b[0], 1e-9), (p.cssH - 80) / Math.max(b[3] - b[1], 1e-9));
  cam.x = 0.5 * (b[0] + b[2]) - 0.5 * p.cssW / cam.k;
  cam.y = 0.5 * (b[1] + b[3]) + (0.5 * (p.cssH - 70) + 70) / cam.k;
}
function layout() {
  panels.forEach(function (p) {
    const rect = p.el.getBoundingClientRect();
    p.dpr = window.devicePixelRatio || 1;
    p.cssW = Math.max(rect.width, 1); p.cssH = Math.max(rect.height, 1);
    [p.canvas, p.under, p.mid].forEach(function (c) {
      c.width = Math.round(p.cssW * p.dpr);
      c.height = Math.round(p.cssH * p.dpr);
    });
  });
}
function applyCam() {
  panels.forEach(function (p) {
    p.view.k = cam.k;
    p.view.ox = -cam.x * cam.k;
    p.view.oy = cam.y * cam.k;
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
const playBtn = document.getElementById('play');
const scrub = document.getElementById('scrub');
const clock = document.getElementById('clock');
const speedSel = document.getElementById('speed');
const followBox = document.getElementById('follow');
followBox.checked = hash.follow === '1';

function fmt(x) { return x < 1e-3 && x > 0 ? x.toExponential(3) : x.toFixed(4); }

// the tiles from FOLLOW_CONTEXT before the first to as many after the last one that moves
// in any run, as a box (world mm), or null when nothing moves
const FOLLOW_CONTEXT = 24;
function movingBox() {
  let b = null;
  runs.forEach(function (r) {
    let first = -1, last = -1;
    for (let i = 0; i < r.tiles; i++) if (r.cls[i]) { if (first < 0) first = i; last = i; }
    if (first < 0) return;
    const a = Math.max(first - FOLLOW_CONTEXT, 0), z = Math.min(last + FOLLOW_CONTEXT, r.tiles - 1);
    for (let i = a; i <= z; i++) {
      const x = r.px[i], y = r.py[i];
      b = b ? [Math.min(b[0], x), Math.min(b[1], y), Math.max(b[2], x), Math.max(b[3], y)] : [x, y, x, y];
    }
    const pad = 1.5 * r.w;
    b = [b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad];
  });
  return b;
}
// follow: the view moves to the part that moves, gliding while playing
function follow() {
  const b = movingBox();
  if (!b) return;
  const was = { x: cam.x, y: cam.y, k: cam.k };
  fitAll(b);
  if (state.playing) {
    const f = 0.15;
    cam.k = Math.exp(Math.log(was.k) + f * (Math.log(cam.k) - Math.log(was.k)));
    cam.x = was.x + f * (cam.x - was.x);
    cam.y = was.y + f * (cam.y - was.y);
  }
  applyCam();
}

function render() {
  const t0 = performance.now();
  const t = state.t;
  panels.forEach(function (p) { update(p.run, t); });
  if (followBox.checked) follow();
  panels.forEach(function (p) {
    drawUnder(p);
    p.rastered = opts.renderer === 'raster' || (opts.renderer !== '2d' && inView(p) > RASTER_ABOVE);
    p.mid.hidden = !p.rastered;
    if (p.rastered) p.raster.draw(p, t, opts); else drawChain2d(p, t, opts);
    drawOver(p, p.overCtx, true);
  });
  if (opts.flush) {
    panels.forEach(function (p) {
      [p.ctx, p.overCtx, p.midCtx].forEach(function (c) { c.getImageData(0, 0, 1, 1); });
    });
  }
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
    if (opts.poses) p.el.dataset.poses = posesText(r);
  });
  const first = panels[0];
  body.dataset.time = String(t);
  body.dataset.folded = first.run.folded;
  body.dataset.moving = first.run.moving;
  body.dataset.collision = first.el.dataset.collision;
  body.dataset.renderMs = ms.toFixed(2);
  body.dataset.renderer = first.rastered ? 'raster' : 'canvas';
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
  followBox.checked = false;
  cam.k *= f;
  cam.x = wx - sx / cam.k;
  cam.y = wy + sy / cam.k;
  applyCam(); render();
}
function pan(dx, dy) {
  followBox.checked = false;
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
document.getElementById('fit').addEventListener('click', function () { followBox.checked = false; fitAll(); applyCam(); render(); });
followBox.addEventListener('change', function () { render(); });
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
    case '0': case 'f': followBox.checked = false; fitAll(); applyCam(); render(); break;
    case 'v': followBox.checked = !followBox.checked; render(); break;
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
// view=X0,Y0,X1,Y1 (world mm) opens on that box
const asked = (hash.view || '').split(',').map(parseFloat);
fitAll(asked.length === 4 && asked.every(isFinite) && asked[2] > asked[0] && asked[3] > asked[1] ? asked : null);
applyCam();
const t0 = timeFrom(hash);
state.t = Math.min(Math.max(t0 === null ? 0 : t0, 0), end);
const bench = parseInt(hash.bench || '0', 10);
if (bench > 0) {
  // frames at times spread over the run ending at the asked time, each flushed to pixels
  opts.flush = true;
  const target = state.t;
  const times = [];
  for (let i = 0; i < bench; i++) {
    state.t = target * (i + 1) / bench;
    times.push(render());
  }
  opts.flush = false;
  times.sort(function (x, y) { return x - y; });
  body.dataset.renderMsMax = times[bench - 1].toFixed(2);
  body.dataset.renderMsMedian = times[bench >> 1].toFixed(2);
  body.dataset.renderFrames = String(bench);
} else {
  render();
}
// probe=T1,T2,...: the poses at those times on each panel's data-poses-1, data-poses-2, ...
if (hash.probe) {
  hash.probe.split(',').map(parseFloat).forEach(function (t, i) {
    panels.forEach(function (p) {
      update(p.run, t);
      p.el.setAttribute('data-poses-' + (i + 1), posesText(p.run));
    });
  });
  render();
}
// opened without a time: play from the start
if (t0 === null && !hash.probe && !(bench > 0) && end > 0) play(true);
