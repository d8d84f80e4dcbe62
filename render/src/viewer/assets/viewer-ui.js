// foldchain viewer, the page: panels, the shared clock and view, controls, the URL hash,
// the state on <body>, and the test options.

// options from the hash: view=X0,Y0,X1,Y1, follow=0|1, and for tests poses=1, detail=all,
// renderer=2d|raster, bench=N, probe=T1,T2,...
const hash = readHash();
const opts = { detailAll: hash.detail === 'all', poses: hash.poses === '1', renderer: hash.renderer || 'auto', flush: false };
const runs = JSON.parse(document.getElementById('run-data').textContent).map(decode);
runs.forEach(prepareCamera);
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
  const riLabel = document.createElement('span');
  riLabel.className = 'ri';
  riLabel.textContent = 'RI';
  const cap = document.createElement('div');
  cap.className = 'caption';
  cap.innerHTML = '<div><span class="label"></span><span class="title"></span></div>' +
    '<div class="state"></div><div class="hit"></div>';
  cap.querySelector('.label').textContent = r.label;
  el.appendChild(under); el.appendChild(mid); el.appendChild(canvas); el.appendChild(riLabel); el.appendChild(cap);
  panelsEl.appendChild(el);
  return { run: r, el: el, canvas: canvas, under: under, mid: mid, raster: makeRaster(mid), rastered: false,
    ctx: under.getContext('2d', { alpha: false }), overCtx: canvas.getContext('2d'),
    riLabel: riLabel, state: cap.querySelector('.state'), hitEl: cap.querySelector('.hit'),
    view: { ox: 0, oy: 0, k: 1 }, cssW: 1, cssH: 1, dpr: 1 };
});

panels.forEach(function (p) { p.midCtx = p.mid.getContext('2d'); });

// every tile's pose, 'x,y,angle;...' (mm, radians)
function posesText(r) {
  const a = [];
  for (let i = 0; i < r.tiles; i++) a.push(r.px[i] + ',' + r.py[i] + ',' + r.pa[i]);
  return a.join(';');
}

// whether more than RASTER_ABOVE tiles may be in view: the chain has that many and the
// panel holds that many tiles side by side (tiles do not overlap unless they collide)
function manyInView(p) {
  const side = p.run.w * p.view.k;
  return p.run.tiles > RASTER_ABOVE && p.cssW * p.cssH > RASTER_ABOVE * side * side;
}

// the shared view: the world point at the panels' top left corner (mm) and pixels per mm;
// a resized window fits the box the view was fitted to again (`box`, until a pan or zoom),
// or keeps that corner where it is
const cam = { x: 0, y: 0, k: 1, box: null };
const CAPTION_PX = 70;
// the view holding the box b (world mm), or the whole run, into `c` (default the camera)
function fitAll(b, c) {
  c = c || cam;
  if (!b) {
    runs.forEach(function (r) {
      const q = r.box;
      b = b ? [Math.min(b[0], q[0]), Math.min(b[1], q[1]), Math.max(b[2], q[2]), Math.max(b[3], q[3])] : q.slice();
    });
  }
  const p = panels[0];
  // leave room for the caption (CAPTION_PX at the top)
  if (c === cam) cam.box = b;
  c.k = Math.min((p.cssW - 20) / Math.max(b[2] - b[0], 1e-9), (p.cssH - CAPTION_PX - 10) / Math.max(b[3] - b[1], 1e-9));
  c.x = 0.5 * (b[0] + b[2]) - 0.5 * p.cssW / c.k;
  c.y = 0.5 * (b[1] + b[3]) + (0.5 * (p.cssH - CAPTION_PX) + CAPTION_PX) / c.k;
  return c;
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
// the camera follows the folding part unless told otherwise (follow=0, view=...)
followBox.checked = hash.follow !== '0' && !hash.view;

function fmt(x) { return x < 1e-3 && x > 0 ? x.toExponential(3) : x.toFixed(4); }

// The camera that follows the fold: it frames the part of the chain that has folded (the
// tiles before the first joint still to settle) with the next FOLLOW_CONTEXT tiles, all
// where they will end, at least FOLLOW_MIN_TILES tiles across, with room around for the
// tiles turning at the fold (they are within a tile or two of where the first of them
// ends); once the run has ended, the final shape. The box is a function of the time alone
// (a paused page at #t=... shows the same view every time), only grows, and grows
// continuously and at a bounded pace (the folded part's reach advances steadily between
// settling joints, no faster than twice its average, the last tile counted in part): the
// tail whipping round beyond the fold never shakes it.
// While playing the camera glides to it (FOLLOW_EASE_S seconds of real time to cover 63%
// of the way).
const FOLLOW_CONTEXT = 8;
const FOLLOW_MIN_TILES = 10;
const FOLLOW_EASE_S = 0.25;
function followBoxAt(t) {
  let b = null;
  runs.forEach(function (r) {
    const n = r.tiles;
    const e = Math.min(reachAt(r, t) + FOLLOW_CONTEXT, n - 1);
    const last = Math.floor(e), part = e - last, next = Math.min(last + 1, n - 1);
    // final poses of tiles 0..e, the last in part
    let x0 = r.bx0[last], y0 = r.by0[last], x1 = r.bx1[last], y1 = r.by1[last];
    const x = r.fx[last] + part * (r.fx[next] - r.fx[last]), y = r.fy[last] + part * (r.fy[next] - r.fy[last]);
    x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
    // a tile reaches 0.54 w from its centre (half its diagonal across the corners), the
    // RI's label a little further; while tiles remain to fold, room for those turning
    const pad = r.w * (1 + 1.5 * Math.min((n - 1 - e) / FOLLOW_CONTEXT, 1));
    const least = 0.5 * FOLLOW_MIN_TILES * r.w;
    const cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
    const hx = Math.max(0.5 * (x1 - x0) + pad, least), hy = Math.max(0.5 * (y1 - y0) + pad, least);
    const q = [cx - hx, cy - hy, cx + hx, cy + hy];
    b = b ? [Math.min(b[0], q[0]), Math.min(b[1], q[1]), Math.max(b[2], q[2]), Math.max(b[3], q[3])] : q;
  });
  return b;
}
// follow: the camera on followBoxAt(t) (after update), gliding there over `dt` seconds of
// real time while playing, at once otherwise
function follow(t, dt) {
  const b = followBoxAt(t);
  if (!b) return;
  const to = fitAll(b, {});
  cam.box = null;
  if (dt > 0) {
    const p = panels[0], f = 1 - Math.exp(-dt / FOLLOW_EASE_S);
    // centres and the log of the scale
    const cx = cam.x + 0.5 * p.cssW / cam.k, cy = cam.y - 0.5 * p.cssH / cam.k;
    const tx = to.x + 0.5 * p.cssW / to.k, ty = to.y - 0.5 * p.cssH / to.k;
    const k = Math.exp(Math.log(cam.k) + f * (Math.log(to.k) - Math.log(cam.k)));
    const nx = cx + f * (tx - cx), ny = cy + f * (ty - cy);
    cam.k = k;
    cam.x = nx - 0.5 * p.cssW / k;
    cam.y = ny + 0.5 * p.cssH / k;
  } else {
    cam.x = to.x; cam.y = to.y; cam.k = to.k;
  }
  applyCam();
}

// what has happened up to the shown time, in words: the joints folded so far while the run
// goes on, the outcome once it has ended
function statusText(r, t) {
  const joints = r.folded + ' of ' + r.joint.length + (r.joint.length === 1 ? ' fold' : ' folds') + ' done';
  if (t < r.end) return 'folding: ' + joints + ', ' + r.moving + (r.moving === 1 ? ' magnet' : ' magnets') + ' moving';
  return (r.note || 'ended') + ' (' + joints + ' at t = ' + fmt(r.end) + ' s)';
}

// draws every panel at state.t; `dt`: seconds of real time since the last frame while
// playing (the camera glides), else the camera jumps
function render(dt) {
  const t0 = performance.now();
  const t = state.t;
  panels.forEach(function (p) { update(p.run, t); });
  if (followBox.checked) follow(t, dt || 0);
  panels.forEach(function (p) {
    p.rastered = opts.renderer === 'raster' || (opts.renderer !== '2d' && manyInView(p));
    // without a target outline the rasterised chain carries the background too
    p.opaque = p.rastered && !p.run.target.length;
    if (!p.opaque) drawUnder(p);
    p.mid.hidden = !p.rastered;
    if (p.rastered) {
      p.raster.draw(p, t, opts);
      if (p.overDrawn) { p.overCtx.setTransform(1, 0, 0, 1, 0, 0); p.overCtx.clearRect(0, 0, p.canvas.width, p.canvas.height); p.overDrawn = false; }
    } else {
      drawChain2d(p, t, opts);
      drawOver(p);
    }
  });
  if (opts.flush) {
    panels.forEach(function (p) {
      if (!p.opaque) p.ctx.getImageData(0, 0, 1, 1);
      (p.rastered ? p.midCtx : p.overCtx).getImageData(0, 0, 1, 1);
    });
  }
  const ms = performance.now() - t0;
  panels.forEach(function (p) {
    const r = p.run;
    p.el.dataset.folded = r.folded;
    p.el.dataset.moving = r.moving;
    p.el.dataset.collision = r.hit ? r.hit[0] + ',' + r.hit[1] : '';
    p.state.textContent = statusText(r, t);
    p.el.dataset.status = p.state.textContent;
    p.hitEl.textContent = r.hit ? 'collision: tiles ' + r.hit[0] + ' and ' + r.hit[1] +
      (r.collision[0] === null ? ' in the final shape' : ' at t = ' + fmt(r.collision[0]) + ' s') : '';
    if (opts.poses) p.el.dataset.poses = posesText(r);
  });
  const first = panels[0];
  body.dataset.time = String(t);
  body.dataset.folded = first.run.folded;
  body.dataset.moving = first.run.moving;
  body.dataset.collision = first.el.dataset.collision;
  body.dataset.status = first.el.dataset.status;
  body.dataset.follow = followBox.checked ? '1' : '0';
  body.dataset.renderMs = ms.toFixed(2);
  body.dataset.renderer = first.rastered ? 'raster' : 'canvas';
  const cr = first.canvas.getBoundingClientRect();
  body.dataset.view = [first.view.k, cr.left + first.view.ox, cr.top + first.view.oy].join(',');
  body.dataset.panel = [cr.left, cr.top, cr.width, cr.height].join(',');
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
  let dt = 0;
  if (state.last !== null) {
    dt = (ts - state.last) / 1000;
    state.t += dt * state.speed;
    if (state.t >= end) { state.t = end; state.playing = false; }
  }
  state.last = ts;
  render(dt);
  if (state.playing) requestAnimationFrame(frame);
  else if (followBox.checked) requestAnimationFrame(glide);
}
// after playing to the end, the camera glides on to the final shape
function glide(ts) {
  if (state.playing || !followBox.checked) return;
  const dt = state.last === null ? 0 : (ts - state.last) / 1000;
  state.last = ts;
  const was = { x: cam.x, y: cam.y, k: cam.k };
  render(dt);
  const moved = Math.abs(cam.k / was.k - 1) > 1e-3 || Math.hypot(cam.x - was.x, cam.y - was.y) * cam.k > 0.5;
  if (moved) requestAnimationFrame(glide); else render();
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
  cam.box = null;
  cam.k *= f;
  cam.x = wx - sx / cam.k;
  cam.y = wy + sy / cam.k;
  applyCam(); render();
}
function pan(dx, dy) {
  followBox.checked = false;
  cam.box = null;
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
window.addEventListener('resize', function () {
  layout();
  if (cam.box && !followBox.checked) fitAll(cam.box);
  applyCam(); render();
});

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
if (hash.view) followBox.checked = false;
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
  // the opening frame, flushed to pixels, then once the page is idle the same frame redrawn
  // in full: the first pays for compiling the page's script (data-first-render-ms), the
  // second is what every later full redraw costs (data-render-ms)
  opts.flush = true;
  body.dataset.firstRenderMs = render().toFixed(2);
  opts.flush = false;
  setTimeout(function () {
    if (state.playing) return;
    opts.flush = true;
    render();
    opts.flush = false;
  }, 0);
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
// views=T1,T2,...: the following camera's view at those times (as a paused page shows it)
// on <body>'s data-view-1, data-view-2, ... (as data-view)
if (hash.views) {
  const cr = panels[0].canvas.getBoundingClientRect();
  hash.views.split(',').map(parseFloat).forEach(function (t, i) {
    panels.forEach(function (p) { update(p.run, t); });
    const c = fitAll(followBoxAt(t), {});
    body.setAttribute('data-view-' + (i + 1), [c.k, cr.left - c.x * c.k, cr.top + c.y * c.k].join(','));
  });
  render();
}
// opened without a time: play from the start
if (t0 === null && !hash.probe && !hash.views && !(bench > 0) && end > 0) play(true);
