// ---------------------------------------------------------------- walk: moving along the path
// Walking between keyframes (an eased animation of the arc length s), the keyframe shown at s, and the order
// in which images load: every preview by progressive rank, then the full images around the viewer.
const WALK_SPEED = 1.6;        // metres per second when animating between keyframes

let animation = null;
function walkTo(s) {
  const total = frames.length ? frames[frames.length - 1].s : 0;
  s = Math.max(0, Math.min(total, s));
  const from = player.state.s;
  const duration = Math.min(900, Math.max(200, Math.abs(s - from) / WALK_SPEED * 1000));
  animation = { from, to: s, start: performance.now(), duration };
  player.state.moving = true;
  requestDraw();
}

// One keyframe forward (+1) or back (-1) along the path, "forward" meaning the way the viewer looks.
function walk(direction) {
  if (keyframes.length === 0) return;
  const here = frameAtS(player.state.s);
  const b = basis(player.state.yaw, 0);
  const tx = here.tx !== undefined ? here.tx : Math.cos(here.heading);
  const ty = here.ty !== undefined ? here.ty : Math.sin(here.heading);
  const along = b.f[0] * tx + b.f[1] * ty >= 0 ? 1 : -1;
  const sign = direction * along;
  const current = animation ? animation.to : player.state.s;
  let target = null;
  for (const k of keyframes) {
    if (sign > 0 && k.s > current + 1e-6 && (target === null || k.s < target)) target = k.s;
    if (sign < 0 && k.s < current - 1e-6 && (target === null || k.s > target)) target = k.s;
  }
  if (target !== null) walkTo(target);
}

function setKeyframe(index) {
  if (index < 0 || index === player.state.keyframe) return;
  fade = { from: player.state.keyframe, start: performance.now() };
  player.state.keyframe = index;
  const k = keyframes[index];
  player.state.level = k.level;
  requestFull(index);
}

// ---------------------------------------------------------------- loading order: previews, then full
function requestFull(index) {
  for (const i of [index, index + 1, index - 1, index + 2, index - 2]) {
    const k = keyframes[i];
    // A keyframe with cube tiles shows them at rest: its full equirectangular image is not needed then.
    if (!k || k.level === 'full' || k.fullRequested || (hasTiles(k) && !tilesBlocked)) continue;
    k.fullRequested = true;
    loadFull(k).then((img) => {
      k.image = img; k.level = 'full';
      if (i === player.state.keyframe) player.state.level = 'full';
      requestDraw();
    }).catch((e) => { k.fullRequested = fullBlocked; if (!fullBlocked) console.warn(e.message); });
  }
}

function loadPreviews() {
  const byRank = keyframes.slice().sort((a, b) => a.rank - b.rank);
  let next = 0;
  const worker = () => {
    if (next >= byRank.length) return Promise.resolve();
    const k = byRank[next++];
    return loadPreview(k).then((img) => {
      if (k.level !== 'full') { k.image = img; k.level = 'preview'; }
      // Previews arrive in progressive order (coarse to fine), not along the path: the first one may be the
      // path's far end. Until the viewer moves, the keyframe shown is the nearest one loaded so far.
      const i = nearestKeyframe(player.state.s, true);
      if (i >= 0 && i !== player.state.keyframe && !animation) { player.state.keyframe = -1; setKeyframe(i); }
      requestDraw();
    }).catch((e) => console.warn(e.message)).then(worker);
  };
  return Promise.all([worker(), worker(), worker(), worker()]);
}

function stepAnimation() {
  if (!animation) return false;
  const t = Math.min(1, (performance.now() - animation.start) / animation.duration);
  const ease = t < 0.5 ? 2 * t * t : 1 - 2 * (1 - t) * (1 - t);
  player.state.s = animation.from + (animation.to - animation.from) * ease;
  // Arrived: the walk's own blend ends on this keyframe, so no cross-fade follows it.
  if (t >= 1) { animation = null; player.state.moving = false; fade.start = 0; }
  const i = nearestKeyframe(player.state.s, true);
  if (i >= 0) setKeyframe(i);
  checkProximity();
  return true;
}
