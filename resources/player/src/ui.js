// ---------------------------------------------------------------- UI: map, input, frame loop, start
// The map window, mouse/touch/keyboard/gyroscope/VR input, the frame loop that draws on request, and the
// start-up that ties the modules together.

// ---------------------------------------------------------------- map window
const mapCanvas = $('map-canvas');
let mapTransform = null;
function fitMap() {
  const rect = mapCanvas.getBoundingClientRect(), dpr = window.devicePixelRatio || 1;
  mapCanvas.width = Math.max(1, Math.round(rect.width * dpr));
  mapCanvas.height = Math.max(1, Math.round(rect.height * dpr));
  let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
  const add = (x, y) => { minX = Math.min(minX, x); minY = Math.min(minY, y); maxX = Math.max(maxX, x); maxY = Math.max(maxY, y); };
  for (const l of tour.plan.lines) { add(l[0], l[1]); add(l[2], l[3]); }
  for (const f of frames) add(f.x, f.y);
  if (!isFinite(minX)) { minX = minY = 0; maxX = maxY = 1; }
  const margin = 0.5, w = maxX - minX + 2 * margin, h = maxY - minY + 2 * margin;
  const scale = Math.min(mapCanvas.width / w, mapCanvas.height / h);
  const ox = (mapCanvas.width - scale * w) / 2 - scale * (minX - margin);
  const oy = (mapCanvas.height - scale * h) / 2 + scale * (maxY + margin);
  mapTransform = { scale, ox, oy, dpr };
}
const toMap = (x, y) => [mapTransform.ox + mapTransform.scale * x, mapTransform.oy - mapTransform.scale * y];
const fromMap = (px, py) => [(px - mapTransform.ox) / mapTransform.scale, (mapTransform.oy - py) / mapTransform.scale];

function drawMap() {
  if (!mapTransform) fitMap();
  const ctx = mapCanvas.getContext('2d'), dpr = mapTransform.dpr;
  ctx.clearRect(0, 0, mapCanvas.width, mapCanvas.height);
  ctx.lineCap = 'round';
  for (const l of tour.plan.lines) {
    const layer = tour.plan.layers[l[4]] || {};
    if (layer.visible === false) continue;
    ctx.strokeStyle = layer.occluder ? '#222' : '#999';
    ctx.lineWidth = (layer.occluder ? 2 : 1) * dpr;
    ctx.beginPath(); ctx.moveTo(...toMap(l[0], l[1])); ctx.lineTo(...toMap(l[2], l[3])); ctx.stroke();
  }
  ctx.fillStyle = '#666';
  ctx.font = `${11 * dpr}px sans-serif`;
  ctx.textAlign = 'center';
  for (const label of tour.plan.labels || []) ctx.fillText(label.text, ...toMap(label.x, label.y));
  ctx.strokeStyle = '#2a6fdb'; ctx.lineWidth = 2 * dpr;
  ctx.beginPath();
  frames.forEach((f, i) => (i ? ctx.lineTo(...toMap(f.x, f.y)) : ctx.moveTo(...toMap(f.x, f.y))));
  ctx.stroke();
  for (const k of keyframes) {
    ctx.fillStyle = k.image ? '#f08c00' : '#c9c9c9';
    ctx.beginPath(); ctx.arc(...toMap(k.x, k.y), 3 * dpr, 0, 2 * PI); ctx.fill();
  }
  // The viewer: position along the path and a view cone of the horizontal field of view.
  const here = frameAtS(player.state.s), [px, py] = toMap(here.x, here.y);
  const hfov = 2 * Math.atan(Math.tan(player.state.fov * DEG / 2) * canvas.clientWidth / Math.max(1, canvas.clientHeight));
  const radius = 40 * dpr;
  ctx.fillStyle = 'rgba(220,40,40,.25)';
  ctx.beginPath(); ctx.moveTo(px, py);
  ctx.arc(px, py, radius, -(player.state.yaw + hfov / 2), -(player.state.yaw - hfov / 2));
  ctx.closePath(); ctx.fill();
  ctx.fillStyle = '#d22'; ctx.beginPath(); ctx.arc(px, py, 5 * dpr, 0, 2 * PI); ctx.fill();
}

function mapEvent(e) {
  const rect = mapCanvas.getBoundingClientRect(), dpr = mapTransform.dpr;
  const [x, y] = fromMap((e.clientX - rect.left) * dpr, (e.clientY - rect.top) * dpr);
  walkTo(nearestSOnPath(x, y));
}

// ---------------------------------------------------------------- input
let drag = null;
function lookBy(dx, dy) {
  const perPixel = player.state.fov * DEG / Math.max(1, canvas.clientHeight);
  player.state.yaw += dx * perPixel;
  player.state.pitch = Math.max(-85 * DEG, Math.min(85 * DEG, player.state.pitch + dy * perPixel));
  requestDraw();
}
function zoomBy(factor) {
  player.state.fov = Math.max(20, Math.min(110, player.state.fov * factor));
  requestDraw();
}
function clickAt(clientX, clientY) {
  const k = keyframes[player.state.keyframe];
  if (!k) return;
  const rect = canvas.getBoundingClientRect();
  const { ray } = viewMatrices(rect.width, rect.height);
  const nx = (clientX - rect.left) / rect.width * 2 - 1, ny = 1 - (clientY - rect.top) / rect.height * 2;
  const dir = [0, 1, 2].map((i) => ray[i] * nx + ray[3 + i] * ny + ray[6 + i]);
  for (const h of hotspots) {
    if (h.trigger !== HotspotTrigger.CLICK) continue;
    const corners = hotspotCorners(h, k);
    if (corners && corners.length >= 3 && rayHitsHotspot(dir, corners)) { fire(h); return; }
  }
}

function bindInput() {
  canvas.addEventListener('pointerdown', (e) => {
    drag = { x: e.clientX, y: e.clientY, startX: e.clientX, startY: e.clientY, pointers: (drag ? drag.pointers : 0) + 1 };
    canvas.setPointerCapture(e.pointerId);
    canvas.classList.add('dragging');
    canvas.focus();
  });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag) return;
    lookBy(e.clientX - drag.x, e.clientY - drag.y);  // grab the picture: drag right to look left
    drag.x = e.clientX; drag.y = e.clientY;
  });
  canvas.addEventListener('pointerup', (e) => {
    if (drag && Math.hypot(e.clientX - drag.startX, e.clientY - drag.startY) < 5) clickAt(e.clientX, e.clientY);
    drag = null;
    canvas.classList.remove('dragging');
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    if (e.ctrlKey) zoomBy(e.deltaY > 0 ? 1.08 : 1 / 1.08);
    else walk(e.deltaY < 0 ? 1 : -1);
  }, { passive: false });
  let pinch = null;
  canvas.addEventListener('touchmove', (e) => {
    if (e.touches.length !== 2) { pinch = null; return; }
    const d = Math.hypot(e.touches[0].clientX - e.touches[1].clientX, e.touches[0].clientY - e.touches[1].clientY);
    if (pinch) zoomBy(pinch / d);
    pinch = d;
    drag = null;
  });
  window.addEventListener('keydown', (e) => {
    const step = 5 * DEG;
    switch (e.key) {
      case 'ArrowUp': case 'w': case 'W': walk(1); break;
      case 'ArrowDown': case 's': case 'S': walk(-1); break;
      case 'ArrowLeft': case 'a': case 'A': player.state.yaw += step; break;
      case 'ArrowRight': case 'd': case 'D': player.state.yaw -= step; break;
      case 'PageUp': player.state.pitch = Math.min(85 * DEG, player.state.pitch + step); break;
      case 'PageDown': player.state.pitch = Math.max(-85 * DEG, player.state.pitch - step); break;
      case '+': case '=': zoomBy(1 / 1.1); break;
      case '-': zoomBy(1.1); break;
      case 'Escape': $('panel').hidden = true; break;
      default: return;
    }
    e.preventDefault();
    requestDraw();
  });
  $('forward').addEventListener('click', () => walk(1));
  $('back').addEventListener('click', () => walk(-1));
  $('panel-close').addEventListener('click', () => { $('panel').hidden = true; });
  let mapDragging = false;
  mapCanvas.addEventListener('pointerdown', (e) => { mapDragging = true; mapCanvas.setPointerCapture(e.pointerId); mapEvent(e); });
  mapCanvas.addEventListener('pointermove', (e) => { if (mapDragging) mapEvent(e); });
  mapCanvas.addEventListener('pointerup', () => { mapDragging = false; });
  window.addEventListener('resize', () => { fitMap(); requestDraw(); });
  bindDeviceOrientation();
  bindXr();
}

// Gyroscope: look around by turning the device; rolling it right or left walks forward or back.
function bindDeviceOrientation() {
  if (!('DeviceOrientationEvent' in window) || !('ontouchstart' in window)) return;
  const button = $('gyro');
  button.hidden = false;
  let enabled = false, yawOffset = null, lastWalk = 0;
  // The device's compass is not the plan's north: the first reading keeps the view's yaw, later ones turn it.
  // The screen's angle is read at each event, so turning to landscape keeps the view where it looks.
  const onOrientation = (e) => {
    if (e.alpha === null || e.beta === null || e.gamma === null) return;
    const view = viewFromDeviceOrientation(e.alpha, e.beta, e.gamma, screenAngle());
    if (yawOffset === null) yawOffset = player.state.yaw - view.yaw;
    player.state.yaw = yawOffset + view.yaw;
    player.state.pitch = Math.max(-85 * DEG, Math.min(85 * DEG, view.pitch));
    const now = performance.now();
    if (Math.abs(view.roll) > 20 * DEG && now - lastWalk > 700) { lastWalk = now; walk(view.roll > 0 ? 1 : -1); }
    requestDraw();
  };
  button.addEventListener('click', () => {
    const start = () => { enabled = !enabled; yawOffset = null;
      if (enabled) window.addEventListener('deviceorientation', onOrientation);
      else window.removeEventListener('deviceorientation', onOrientation); };
    if (typeof DeviceOrientationEvent.requestPermission === 'function')
      DeviceOrientationEvent.requestPermission().then((r) => { if (r === 'granted') start(); });
    else start();
  });
}

// WebXR: the same panorama around the viewer's head; the controller's select walks forward.
function bindXr() {
  if (!navigator.xr || !navigator.xr.isSessionSupported) return;
  navigator.xr.isSessionSupported('immersive-vr').then((ok) => {
    if (!ok) return;
    const button = $('vr');
    button.hidden = false;
    button.addEventListener('click', startXr);
  }).catch(() => {});
}

function startXr() {
  navigator.xr.requestSession('immersive-vr').then(async (session) => {
    await gl.makeXRCompatible();
    session.updateRenderState({ baseLayer: new XRWebGLLayer(session, gl) });
    const space = await session.requestReferenceSpace('local');
    const yaw0 = player.state.yaw;
    session.addEventListener('select', () => walk(1));
    const onFrame = (time, frame) => {
      session.requestAnimationFrame(onFrame);
      const pose = frame.getViewerPose(space);
      if (!pose) return;
      const layer = session.renderState.baseLayer;
      gl.bindFramebuffer(gl.FRAMEBUFFER, layer.framebuffer);
      stepAnimation();
      for (const view of pose.views) {
        const vp = layer.getViewport(view);
        gl.viewport(vp.x, vp.y, vp.width, vp.height);
        const { ray, viewProj } = xrMatrices(view, yaw0);
        drawScene(vp.width, vp.height, ray, viewProj);
      }
    };
    session.requestAnimationFrame(onFrame);
  }).catch((e) => showError('VR could not start: ' + e.message));
}

// XR space (x right, y up, -z forward at start) to the plan frame, keeping the yaw the viewer had.
function xrMatrices(view, yaw0) {
  const b = basis(yaw0, 0);
  const planFromXr = (v) => [0, 1, 2].map((i) => b.r[i] * v[0] + b.u[i] * v[1] - b.f[i] * v[2]);
  const m = view.transform.matrix, p = view.projectionMatrix;
  const rotate = (v) => [0, 1, 2].map((i) => m[i] * v[0] + m[4 + i] * v[1] + m[8 + i] * v[2]);
  // Eye-space direction of an NDC point for a (possibly asymmetric) perspective projection.
  const eyeDir = (x, y) => [(x + p[8]) / p[0], (y + p[9]) / p[5], -1];
  const d00 = planFromXr(rotate(eyeDir(0, 0))), d10 = planFromXr(rotate(eyeDir(1, 0))), d01 = planFromXr(rotate(eyeDir(0, 1)));
  const ray = [d10[0] - d00[0], d10[1] - d00[1], d10[2] - d00[2], d01[0] - d00[0], d01[1] - d00[1], d01[2] - d00[2], ...d00];
  // viewProj = P * inverse(R) * xrFromPlan (rotation only: the panorama is at infinity for the head).
  const xrFromPlan = (v) => [b.r[0] * v[0] + b.r[1] * v[1] + b.r[2] * v[2], b.u[0] * v[0] + b.u[1] * v[1] + b.u[2] * v[2],
    -(b.f[0] * v[0] + b.f[1] * v[1] + b.f[2] * v[2])];
  const inverseRotate = (v) => [0, 1, 2].map((i) => m[i * 4] * v[0] + m[i * 4 + 1] * v[1] + m[i * 4 + 2] * v[2]);
  const viewProj = new Float32Array(16);
  for (let col = 0; col < 3; ++col) {
    const axis = [0, 0, 0]; axis[col] = 1;
    const e = inverseRotate(xrFromPlan(axis));
    for (let row = 0; row < 4; ++row) viewProj[col * 4 + row] = p[row] * e[0] + p[4 + row] * e[1] + p[8 + row] * e[2];
  }
  for (let row = 0; row < 4; ++row) viewProj[12 + row] = p[12 + row];
  return { ray, viewProj };
}

// ---------------------------------------------------------------- frame loop
let drawRequested = false;
function requestDraw() {
  if (drawRequested) return;
  drawRequested = true;
  requestAnimationFrame(frame);
}

function frame() {
  drawRequested = false;
  probeFrameStart();
  const dpr = window.devicePixelRatio || 1;
  const w = Math.round(canvas.clientWidth * dpr), h = Math.round(canvas.clientHeight * dpr);
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  const animating = stepAnimation();
  gl.viewport(0, 0, w, h);
  gl.clearColor(0.07, 0.07, 0.07, 1);
  gl.clear(gl.COLOR_BUFFER_BIT);
  const { ray, viewProj } = viewMatrices(w, h);
  drawScene(w, h, ray, viewProj);
  updateLabels(viewProj);
  drawMap();
  const k = keyframes[player.state.keyframe];
  if (k) {
    $('status').textContent = `Keyframe ${keyframes.indexOf(k) + 1} of ${keyframes.length} · frame ${k.frame} · ` +
      `${player.state.s.toFixed(1)} m of ${(frames.length ? frames[frames.length - 1].s : 0).toFixed(1)} m · ${k.level}` +
      (player.state.note ? ' · ' + player.state.note : '');
  }
  const fading = performance.now() - fade.start < FADE_MS;
  const playing = (m) => m instanceof HTMLVideoElement && !m.paused && !m.ended;
  const video = hotspots.some((s) => playing(s.mediaElement) || (s.swapped && playing(s.actionImage)));
  if (animating || fading || video) requestDraw();
  probeFrameEnd(drawRequested);
}

// ---------------------------------------------------------------- start
function start(data) {
  readTour(data);
  document.title = tour.title || 'Plenopath tour';
  $('title').textContent = tour.title || '';
  if (keyframes.length === 0) throw new Error('This tour has no keyframes.');
  const start = frameWithIndex(tour.start_frame) || keyframes[0];
  player.state.s = start.s;
  player.state.yaw = start.heading;
  setupHotspots(tour.hotspots || []);
  initGl();
  bindInput();
  fitMap();
  requestDraw();
  return loadPreviews();
}

player.walk = walk;
// Tests and embedding pages: the GPU's limits, the keyframe textures on the GPU, the cube tiles' state.
player.gpu = () => Object.assign({ version: gpuLimits().webgl2 ? 2 : 1 }, gpuLimits(), { anisotropy: !!gpuLimits().anisotropy });
player.textures = () => keyframes.filter((k) => k.texture).map((k) => Object.assign({ frame: k.frame, level: k.textureLevel }, k.textureInfo));
player.tiles = multires;
player.zoomTo = (fov) => { player.state.fov = Math.max(20, Math.min(110, fov)); requestDraw(); };
player.walkToFrame = (frame) => { const f = frameWithIndex(frame); if (f) walkTo(f.s); };
// Tests: looking from keyframe a toward keyframe c, the view at keyframe b's spot as the walk from a to c
// draws it (the room proxy) and as a plain cross-fade would, each against b's own picture there: mean
// absolute difference per channel (0-255). null until the three images are loaded. With `show`, the walked
// view stays on the canvas (for a screenshot) until the next draw.
player.transitionError = (a, b, c, show) => {
  const ka = keyframes[a], kb = keyframes[b], kc = keyframes[c];
  if (!ka || !kb || !kc || !keyframeTexture(ka) || !keyframeTexture(kb) || !keyframeTexture(kc)) return null;
  player.state.yaw = Math.atan2(kc.y - ka.y, kc.x - ka.x);
  player.state.pitch = 0;
  const w = canvas.width, h = canvas.height;
  const { ray } = viewMatrices(w, h);
  const along = (kb.s - ka.s) / (kc.s - ka.s);
  const grab = () => { const px = new Uint8Array(w * h * 4); gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px); return px; };
  gl.viewport(0, 0, w, h);
  drawBackground(ray, kb, kb, 1, null);
  const truth = grab();
  drawBackground(ray, kc, ka, along, { x: kb.x, y: kb.y });
  const walked = grab();
  drawBackground(ray, kc, ka, along, null);
  const faded = grab();
  const mad = (p) => {
    let sum = 0;
    for (let i = 0; i < p.length; i += 4)
      sum += Math.abs(p[i] - truth[i]) + Math.abs(p[i + 1] - truth[i + 1]) + Math.abs(p[i + 2] - truth[i + 2]);
    return sum / (p.length / 4 * 3);
  };
  const out = { walked: mad(walked), crossfade: mad(faded), along };
  if (show) drawBackground(ray, kc, ka, along, { x: kb.x, y: kb.y });
  else requestDraw();
  return out;
};
player.ready = loadTour().then(start).then(() => true).catch((e) => { showError(e.message); return false; });
