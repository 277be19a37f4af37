// ---------------------------------------------------------------- tour data: the document, its assets, the path
// The tour (tour.json, or tour.js from file://), the asset loaders, and the path geometry every other module
// reads: frames along the path, keyframes sorted by arc length, the hotspots' live state.
const PI = Math.PI;
const DEG = PI / 180;

const $ = (id) => document.getElementById(id);
const player = {
  // level: the best image loaded for the keyframe shown; textureLevel: the one on screen (decoded, uploaded).
  state: { yaw: 0, pitch: 0, fov: 75, s: 0, keyframe: -1, level: 'none', textureLevel: 'none', moving: false, note: '' },
  events: [],                  // fired hotspot actions, newest last (for embedding pages and tests)
  get hotspots() { return hotspots; },  // their live state: swapped, loaded media (for tests)
  ready: null,
};
window.plenopathPlayer = player;

function showError(message) {
  const box = $('error');
  box.textContent = message;
  box.hidden = false;
}

const assetWaiters = new Map();
// Called by images/*.js and media/*.js: the asset as a data URI (file:// pages cannot texture from files).
window.plenopathAsset = function (name, dataUri) {
  const waiter = assetWaiters.get(name);
  if (waiter) { assetWaiters.delete(name); waiter(dataUri); }
};
const fromFile = location.protocol === 'file:';

// The asset's URL: its path, or from file:// (or `always`) the data URI its script hands over.
function assetUrl(path, script, always) {
  if ((!fromFile && !always) || !script) return Promise.resolve(path);
  return new Promise((resolve, reject) => {
    assetWaiters.set(path, resolve);
    const tag = document.createElement('script');
    tag.src = script;
    tag.onerror = () => { assetWaiters.delete(path); reject(new Error('cannot load ' + script)); };
    document.head.appendChild(tag);
  });
}

function loadImage(path, script) {
  return assetUrl(path, script).then((url) => new Promise((resolve, reject) => {
    const img = new Image();
    img.onload = () => resolve(img);
    img.onerror = () => reject(new Error('cannot load ' + path));
    img.src = url;
  }));
}

// A keyframe's preview: a script holding the small JPEG (from file:// and http alike); older packages had a
// .jpg with a preview_script.
function loadPreview(k) {
  if (/\.js$/i.test(k.preview)) return loadImage(k.preview, k.preview, true);
  return loadImage(k.preview, k.preview_script);
}

// A keyframe's full image, once the renderer may use it: a browser that isolates file:// pages taints file
// images, and texImage2D would throw a SecurityError on each. The player then stays on the previews and
// says so once in its status line.
let fullBlocked = false;
function loadFull(k) {
  if (fullBlocked) return Promise.reject(new Error('full images cannot be textures here'));
  return loadImage(k.full, k.full_script).then((img) => {
    if (fromFile && !k.full_script && isTainted(img)) {
      fullBlocked = true;
      player.state.note = 'Opened from a file: preview resolution — serve the folder over http for full resolution';
      requestDraw();
      throw new Error(player.state.note);
    }
    return img;
  });
}

// The same rule as texImage2D's: reading a tainted image's pixels throws a SecurityError.
function isTainted(img) {
  const g = document.createElement('canvas').getContext('2d');
  g.canvas.width = g.canvas.height = 1;
  g.drawImage(img, 0, 0, 1, 1);
  try { g.getImageData(0, 0, 1, 1); return false; } catch (e) {
    if (e.name === 'SecurityError') return true;
    throw e;
  }
}

// An image sequence (the lift doors opening) travels as a video: played once on the region, it then holds
// its last frame. Resolves when the first frame can be drawn.
function loadSequence(path, script) {
  return assetUrl(path, script).then((url) => new Promise((resolve, reject) => {
    const v = document.createElement('video');
    v.muted = true; v.loop = false; v.playsInline = true; v.preload = 'auto';
    v.addEventListener('loadeddata', () => { resolve(v); requestDraw(); }, { once: true });
    v.addEventListener('error', () => reject(new Error('cannot load ' + path)), { once: true });
    v.src = url;
    v.play().catch(() => {});
  }));
}

function isVideoFile(path) { return /\.(mp4|webm|ogv|mov|m4v)$/i.test(path); }

function loadTour() {
  if (window.PLENOPATH_TOUR) return Promise.resolve(window.PLENOPATH_TOUR);
  return fetch('tour.json').then((r) => {
    if (!r.ok) throw new Error('tour.json: HTTP ' + r.status);
    return r.json();
  });
}

// ---------------------------------------------------------------- path geometry
let tour = null;
let frames = [];        // {index, x, y, heading, s}
let keyframes = [];     // sorted by s: {frame, x, y, heading, s, rank, preview, full, ..., image, level, texture}
let hotspots = [];

function frameAtS(s) {
  if (frames.length === 0) return { x: 0, y: 0, heading: 0 };
  if (s <= frames[0].s) return frames[0];
  if (s >= frames[frames.length - 1].s) return frames[frames.length - 1];
  let lo = 0, hi = frames.length - 1;
  while (hi - lo > 1) { const mid = (lo + hi) >> 1; if (frames[mid].s <= s) lo = mid; else hi = mid; }
  const a = frames[lo], b = frames[hi];
  const t = b.s > a.s ? (s - a.s) / (b.s - a.s) : 0;
  return { x: a.x + t * (b.x - a.x), y: a.y + t * (b.y - a.y), heading: a.heading, tx: b.x - a.x, ty: b.y - a.y };
}

function nearestKeyframe(s, requireImage) {
  let best = -1, bestD = Infinity;
  keyframes.forEach((k, i) => {
    if (requireImage && !k.image) return;
    const d = Math.abs(k.s - s);
    if (d < bestD) { bestD = d; best = i; }
  });
  return best;
}

function nearestSOnPath(x, y) {
  let best = 0, bestD = Infinity;
  for (let i = 0; i + 1 < frames.length; ++i) {
    const a = frames[i], b = frames[i + 1];
    const dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
    const t = len2 > 0 ? Math.max(0, Math.min(1, ((x - a.x) * dx + (y - a.y) * dy) / len2)) : 0;
    const px = a.x + t * dx, py = a.y + t * dy, d = (px - x) ** 2 + (py - y) ** 2;
    if (d < bestD) { bestD = d; best = a.s + t * (b.s - a.s); }
  }
  if (frames.length === 1) best = frames[0].s;
  return best;
}

// The tour's frames and keyframes in the units the player works in (radians), keyframes sorted by arc length.
function readTour(data) {
  if (!data || data.format !== 'plenopath-tour') throw new Error('tour.json is not a Plenopath tour.');
  if (data.version > 1) throw new Error('This tour was made by a newer Plenopath Studio (format ' + data.version + ').');
  tour = data;
  frames = tour.path.frames.map((f) => ({ index: f[0], x: f[1], y: f[2], heading: f[3] * DEG, s: f[4] }));
  keyframes = tour.keyframes.map((k) => Object.assign({}, k, { heading: k.heading_deg * DEG, image: null, level: 'none' }));
  keyframes.sort((a, b) => a.s - b.s);
}

function frameWithIndex(index) { return frames.find((fr) => fr.index === index); }
