// ---------------------------------------------------------------- hotspots: where they are, what they do
// Movie textures and event regions: their corners seen from a keyframe, their labels, the click ray test,
// the proximity trigger and the actions. Trigger and action names are the generated constants of
// enums.js (from resources/schema/enums.json, shared with the studio and tour.schema.json).

// Corners of a hotspot relative to the eye at keyframe k, or null when it cannot be placed from there.
function hotspotCorners(h, k) {
  const eyeZ = tour.camera_height_m || 1.6;
  if (h.world_corners.length >= 3) return h.world_corners.map((c) => [c[0] - k.x, c[1] - k.y, c[2] - eyeZ]);
  // Directions only: valid from the frame it was authored in (or a keyframe within 0.3 m of it).
  const f = frameWithIndex(h.frame);
  if (!f || Math.hypot(f.x - k.x, f.y - k.y) > 0.3) return null;
  return h.image_corners_deg.map(([az, el]) => {
    const phi = f.heading - az * DEG, e = el * DEG;
    return [5 * Math.cos(e) * Math.cos(phi), 5 * Math.cos(e) * Math.sin(phi), 5 * Math.sin(e)];
  });
}

// The tour's hotspots with their live state (swapped, inside, loaded media) and a label each.
function setupHotspots(list) {
  hotspots = list.map((h) => {
    const spot = Object.assign({ swapped: false, inside: false }, h);
    spot.label = document.createElement('div');
    spot.label.className = 'hotspot-label';
    spot.label.textContent = h.title || '';
    spot.label.hidden = true;
    spot.label.addEventListener('click', () => fire(spot));
    $('labels').appendChild(spot.label);
    spot.actionScript = spot.action_target && /^media\//.test(spot.action_target) ? spot.action_target.replace(/\.[^.]+$/, '.js') : '';
    if (h.media) {
      const script = h.media.replace(/\.[^.]+$/, '.js');
      if (isVideoFile(h.media)) {
        assetUrl(h.media, script).then((url) => {
          const v = document.createElement('video');
          v.muted = true; v.loop = true; v.playsInline = true; v.src = url;
          v.addEventListener('loadeddata', requestDraw);
          v.play().catch(() => {});
          spot.mediaElement = v;
        }).catch((e) => console.warn(e.message));
      } else {
        loadImage(h.media, script).then((img) => { spot.mediaElement = img; requestDraw(); })
          .catch((e) => console.warn(e.message));
      }
    }
    return spot;
  });
}

function project(point, viewProj, width, height) {
  const m = viewProj, p = [point[0], point[1], point[2], 1], out = [0, 0, 0, 0];
  for (let row = 0; row < 4; ++row) for (let col = 0; col < 4; ++col) out[row] += m[col * 4 + row] * p[col];
  if (out[3] <= 0.01) return null;
  return [(out[0] / out[3] * 0.5 + 0.5) * width, (1 - (out[1] / out[3] * 0.5 + 0.5)) * height];
}

function updateLabels(viewProj) {
  const k = keyframes[player.state.keyframe];
  const w = canvas.clientWidth, h = canvas.clientHeight;
  for (const spot of hotspots) {
    const corners = k && hotspotCorners(spot, k);
    let at = null;
    if (corners) {
      const top = corners.reduce((acc, c) => [acc[0] + c[0] / corners.length, acc[1] + c[1] / corners.length,
        Math.max(acc[2], c[2])], [0, 0, -Infinity]);
      at = project(top, viewProj, w, h);
    }
    spot.label.hidden = !at || !spot.title;
    if (at) { spot.label.style.left = at[0] + 'px'; spot.label.style.top = at[1] + 'px'; }
  }
}

// Ray (eye-relative, world frame) against the hotspot's triangles.
function rayHitsHotspot(dir, corners) {
  const tri = (a, b, c) => {
    const e1 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]], e2 = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    const p = [dir[1] * e2[2] - dir[2] * e2[1], dir[2] * e2[0] - dir[0] * e2[2], dir[0] * e2[1] - dir[1] * e2[0]];
    const det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (Math.abs(det) < 1e-12) return false;
    const tv = [-a[0], -a[1], -a[2]];
    const u = (tv[0] * p[0] + tv[1] * p[1] + tv[2] * p[2]) / det;
    const q = [tv[1] * e1[2] - tv[2] * e1[1], tv[2] * e1[0] - tv[0] * e1[2], tv[0] * e1[1] - tv[1] * e1[0]];
    const v = (dir[0] * q[0] + dir[1] * q[1] + dir[2] * q[2]) / det;
    const t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
    return u >= 0 && v >= 0 && u + v <= 1 && t > 0;
  };
  return tri(corners[0], corners[1], corners[2]) || (corners.length > 3 && tri(corners[0], corners[2], corners[3]));
}

function showPanel(title, text) {
  $('panel-title').textContent = title || '';
  $('panel-text').textContent = text || '';
  $('panel').hidden = false;
}

function fire(h) {
  player.events.push({ id: h.id, action: h.action, time: Date.now() });
  requestDraw();  // a swap (either way) must show at once, even when nothing else is moving
  const target = h.action_target || '';
  switch (h.action) {
    case HotspotAction.SWAP_IMAGE:
      h.swapped = !h.swapped;
      if (h.swapped && h.actionImage instanceof HTMLVideoElement) {
        h.actionImage.currentTime = 0;  // the sequence plays again from its start
        h.actionImage.play().catch(() => {});
      }
      if (h.swapped && !h.actionImage && target) {
        const load = isVideoFile(target) ? loadSequence(target, h.actionScript) : loadImage(target, h.actionScript);
        load.then((media) => { h.actionImage = media; requestDraw(); }).catch(() => {
          h.swapped = false;
          showPanel(h.title, 'The alternative image could not be loaded.');
        });
      }
      break;
    case HotspotAction.PLAY_VIDEO:
      if (h.mediaElement instanceof HTMLVideoElement) {
        if (h.mediaElement.paused) h.mediaElement.play().catch(() => {}); else h.mediaElement.pause();
      } else if (target) {
        assetUrl(target, h.actionScript).then((url) => { const v = document.createElement('video');
          v.src = url; v.controls = true; v.autoplay = true; v.style.maxWidth = '100%';
          showPanel(h.title, ''); $('panel-text').appendChild(v); });
      }
      break;
    case HotspotAction.PLAY_SOUND:
      if (target) assetUrl(target, h.actionScript).then((url) => new Audio(url).play().catch(() => {}));
      break;
    case HotspotAction.JUMP: {
      const frame = parseInt(target, 10);
      const f = frameWithIndex(frame);
      if (f) walkTo(f.s);
      break;
    }
    case HotspotAction.OPEN_URL:
      if (/^https?:\/\//i.test(target)) window.open(target, '_blank', 'noopener,noreferrer');
      else showPanel(h.title, 'This link was not opened (only http and https links are allowed): ' + target);
      break;
    case HotspotAction.SHOW_TEXT:
    default:
      showPanel(h.title, target);
  }
}

function checkProximity() {
  const here = frameAtS(player.state.s);
  for (const h of hotspots) {
    if (h.trigger !== HotspotTrigger.PROXIMITY || !(h.trigger_distance_m > 0)) continue;
    let cx, cy;
    if (h.world_corners.length) {
      cx = h.world_corners.reduce((a, c) => a + c[0], 0) / h.world_corners.length;
      cy = h.world_corners.reduce((a, c) => a + c[1], 0) / h.world_corners.length;
    } else {
      const f = frameWithIndex(h.frame);
      if (!f) continue;
      cx = f.x; cy = f.y;
    }
    const inside = Math.hypot(here.x - cx, here.y - cy) <= h.trigger_distance_m;
    if (inside && !h.inside) fire(h);
    h.inside = inside;
  }
}
