// Plenopath web player: walks a plenoptic path exported by Plenopath Studio.
// Plain WebGL, no build step; works from file:// (images then come from small data-URI scripts) and from
// any static server. Conventions (tour.json, schema in tour.schema.json): plan frame X right, Y up, Z up;
// heading = direction of a panorama's centre column, counter-clockwise from +X; equirectangular column 0 is
// azimuth -180 deg and azimuth grows to the right, so the ray at world angle phi is at azimuth heading - phi.
// Every text from the tour is inserted with textContent, never as HTML.
'use strict';
(function () {
  const PI = Math.PI;
  const DEG = PI / 180;
  const TEXTURE_CACHE = 16;      // GPU textures kept (nearest keyframes)
  const WALK_SPEED = 1.6;        // metres per second when animating between keyframes
  const FADE_MS = 350;

  const $ = (id) => document.getElementById(id);
  const player = {
    state: { yaw: 0, pitch: 0, fov: 75, s: 0, keyframe: -1, level: 'none', moving: false },
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

  // ---------------------------------------------------------------- tour and images
  const assetWaiters = new Map();
  // Called by images/*.js and media/*.js: the asset as a data URI (file:// pages cannot texture from files).
  window.plenopathAsset = function (name, dataUri) {
    const waiter = assetWaiters.get(name);
    if (waiter) { assetWaiters.delete(name); waiter(dataUri); }
  };
  const fromFile = location.protocol === 'file:';

  function assetUrl(path, script) {
    if (!fromFile || !script) return Promise.resolve(path);
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

  // ---------------------------------------------------------------- WebGL
  const canvas = $('view');
  const gl = canvas.getContext('webgl', { antialias: true, xrCompatible: true, preserveDrawingBuffer: true });
  const BACKGROUND_VS = 'attribute vec2 a_pos; varying vec2 v_ndc;' +
    'void main(){ v_ndc = a_pos; gl_Position = vec4(a_pos, 0.0, 1.0); }';
  const BACKGROUND_FS = 'precision highp float; varying vec2 v_ndc;' +
    'uniform mat3 u_ray; uniform sampler2D u_tex0; uniform sampler2D u_tex1;' +
    'uniform float u_heading0; uniform float u_heading1; uniform float u_mix;' +
    'const float PI = 3.141592653589793;' +
    'vec4 equirect(sampler2D t, float heading, vec3 d){' +
    '  float phi = atan(d.y, d.x); float el = atan(d.z, length(d.xy));' +
    '  float u = fract((heading - phi + PI) / (2.0 * PI)); float v = (0.5 * PI - el) / PI;' +
    '  return texture2D(t, vec2(u, v)); }' +
    'void main(){ vec3 d = u_ray * vec3(v_ndc, 1.0);' +
    '  gl_FragColor = mix(equirect(u_tex1, u_heading1, d), equirect(u_tex0, u_heading0, d), u_mix); }';
  const QUAD_VS = 'attribute vec3 a_world; attribute vec2 a_uv; uniform mat4 u_view_proj; varying vec2 v_uv;' +
    'void main(){ v_uv = a_uv; gl_Position = u_view_proj * vec4(a_world, 1.0); }';
  const QUAD_FS = 'precision mediump float; varying vec2 v_uv; uniform sampler2D u_media; uniform vec4 u_tint;' +
    'void main(){ gl_FragColor = texture2D(u_media, v_uv) * u_tint; }';

  function compile(vs, fs) {
    const program = gl.createProgram();
    for (const [type, src] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
      const shader = gl.createShader(type);
      gl.shaderSource(shader, src);
      gl.compileShader(shader);
      if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(shader));
      gl.attachShader(program, shader);
    }
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
    return program;
  }

  let background, quadProgram, triangleBuffer, quadBuffer, whiteTexture;
  function initGl() {
    if (!gl) throw new Error('This browser has no WebGL: the tour cannot be shown.');
    background = compile(BACKGROUND_VS, BACKGROUND_FS);
    quadProgram = compile(QUAD_VS, QUAD_FS);
    triangleBuffer = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, triangleBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([-1, -1, 3, -1, -1, 3]), gl.STATIC_DRAW);
    quadBuffer = gl.createBuffer();
    whiteTexture = makeTexture(null);
  }

  function makeTexture(source) {
    const t = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, t);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    if (source) gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, gl.RGBA, gl.UNSIGNED_BYTE, source);
    else gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, 1, 1, 0, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array([255, 255, 255, 255]));
    return t;
  }

  // Keyframe textures: an LRU of GPU textures, so long tours stay within GPU memory.
  const textureOrder = [];
  function keyframeTexture(k) {
    if (!k.image) return null;
    if (!k.texture || k.textureLevel !== k.level) {
      if (k.texture) gl.deleteTexture(k.texture);
      k.texture = makeTexture(k.image);
      k.textureLevel = k.level;
    }
    const at = textureOrder.indexOf(k);
    if (at >= 0) textureOrder.splice(at, 1);
    textureOrder.push(k);
    while (textureOrder.length > TEXTURE_CACHE) {
      const old = textureOrder.shift();
      gl.deleteTexture(old.texture);
      old.texture = null;
    }
    return k.texture;
  }

  // Camera basis in the plan frame for a world yaw (CCW from +X) and pitch.
  function basis(yaw, pitch) {
    const cp = Math.cos(pitch), sp = Math.sin(pitch);
    const f = [cp * Math.cos(yaw), cp * Math.sin(yaw), sp];
    const r = [Math.sin(yaw), -Math.cos(yaw), 0];
    const u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]];
    return { f, r, u };
  }

  // u_ray maps (ndc.x, ndc.y, 1) to a world direction; u_view_proj maps eye-relative world points to clip space.
  function viewMatrices(width, height) {
    const b = basis(player.state.yaw, player.state.pitch);
    const ty = Math.tan(player.state.fov * DEG / 2), tx = ty * width / height;
    const ray = [b.r[0] * tx, b.r[1] * tx, b.r[2] * tx, b.u[0] * ty, b.u[1] * ty, b.u[2] * ty, b.f[0], b.f[1], b.f[2]];
    const near = 0.05, far = 500, fy = 1 / ty, fx = 1 / tx;
    // view: rows r, u, -f; projection: standard perspective. Column-major 4x4.
    const v = [b.r, b.u, [-b.f[0], -b.f[1], -b.f[2]]];
    const a = (far + near) / (near - far), c = 2 * far * near / (near - far);
    const viewProj = new Float32Array(16);
    for (let col = 0; col < 3; ++col) {
      viewProj[col * 4 + 0] = fx * v[0][col];
      viewProj[col * 4 + 1] = fy * v[1][col];
      viewProj[col * 4 + 2] = a * v[2][col];
      viewProj[col * 4 + 3] = -v[2][col];
    }
    viewProj[12] = 0; viewProj[13] = 0; viewProj[14] = c; viewProj[15] = 0;
    return { ray, viewProj };
  }

  let fade = { from: -1, start: 0 };
  function drawScene(width, height, ray, viewProj) {
    const current = keyframes[player.state.keyframe];
    if (!current) return;
    const previous = keyframes[fade.from] || current;
    const t = Math.min(1, (performance.now() - fade.start) / FADE_MS);
    gl.useProgram(background);
    const pos = gl.getAttribLocation(background, 'a_pos');
    gl.bindBuffer(gl.ARRAY_BUFFER, triangleBuffer);
    gl.enableVertexAttribArray(pos);
    gl.vertexAttribPointer(pos, 2, gl.FLOAT, false, 0, 0);
    gl.uniformMatrix3fv(gl.getUniformLocation(background, 'u_ray'), false, ray);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, keyframeTexture(current));
    gl.activeTexture(gl.TEXTURE1);
    gl.bindTexture(gl.TEXTURE_2D, keyframeTexture(previous) || keyframeTexture(current));
    gl.uniform1i(gl.getUniformLocation(background, 'u_tex0'), 0);
    gl.uniform1i(gl.getUniformLocation(background, 'u_tex1'), 1);
    gl.uniform1f(gl.getUniformLocation(background, 'u_heading0'), current.heading);
    gl.uniform1f(gl.getUniformLocation(background, 'u_heading1'), previous.heading);
    gl.uniform1f(gl.getUniformLocation(background, 'u_mix'), t);
    gl.disable(gl.DEPTH_TEST);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.disableVertexAttribArray(pos);
    if (t >= 1) drawHotspots(current, viewProj);
  }

  // ---------------------------------------------------------------- hotspots
  // Corners of a hotspot relative to the eye at keyframe k, or null when it cannot be placed from there.
  function hotspotCorners(h, k) {
    const eyeZ = tour.camera_height_m || 1.6;
    if (h.world_corners.length >= 3) return h.world_corners.map((c) => [c[0] - k.x, c[1] - k.y, c[2] - eyeZ]);
    // Directions only: valid from the frame it was authored in (or a keyframe within 0.3 m of it).
    const f = frames.find((fr) => fr.index === h.frame);
    if (!f || Math.hypot(f.x - k.x, f.y - k.y) > 0.3) return null;
    return h.image_corners_deg.map(([az, el]) => {
      const phi = f.heading - az * DEG, e = el * DEG;
      return [5 * Math.cos(e) * Math.cos(phi), 5 * Math.cos(e) * Math.sin(phi), 5 * Math.sin(e)];
    });
  }

  function hotspotTexture(h) {
    const source = h.swapped && h.actionImage ? h.actionImage : h.mediaElement;
    if (!source) return null;
    if (source instanceof HTMLVideoElement) {
      if (source.readyState < 2) return null;
      if (!h.videoTexture) h.videoTexture = makeTexture(null);
      gl.bindTexture(gl.TEXTURE_2D, h.videoTexture);
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, gl.RGBA, gl.UNSIGNED_BYTE, source);
      return h.videoTexture;
    }
    if (!source.texture) source.texture = makeTexture(source);
    return source.texture;
  }

  function drawHotspots(k, viewProj) {
    gl.useProgram(quadProgram);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    const aWorld = gl.getAttribLocation(quadProgram, 'a_world'), aUv = gl.getAttribLocation(quadProgram, 'a_uv');
    gl.uniformMatrix4fv(gl.getUniformLocation(quadProgram, 'u_view_proj'), false, viewProj);
    for (const h of hotspots) {
      const corners = hotspotCorners(h, k);
      if (!corners || corners.length < 3) continue;
      const texture = hotspotTexture(h);
      const uv = [[0, 0], [1, 0], [1, 1], [0, 1]];
      const triangles = [];
      for (const i of [0, 1, 2, 0, 2, 3]) {
        if (i >= corners.length) continue;
        triangles.push(...corners[i], ...(uv[i] || [0, 0]));
      }
      gl.bindBuffer(gl.ARRAY_BUFFER, quadBuffer);
      gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(triangles), gl.DYNAMIC_DRAW);
      gl.enableVertexAttribArray(aWorld);
      gl.enableVertexAttribArray(aUv);
      gl.vertexAttribPointer(aWorld, 3, gl.FLOAT, false, 20, 0);
      gl.vertexAttribPointer(aUv, 2, gl.FLOAT, false, 20, 12);
      gl.activeTexture(gl.TEXTURE0);
      gl.bindTexture(gl.TEXTURE_2D, texture || whiteTexture);
      gl.uniform1i(gl.getUniformLocation(quadProgram, 'u_media'), 0);
      const tint = texture ? [1, 1, 1, 1] : [0.2, 0.5, 1.0, 0.25];  // an event region without media: a glow
      gl.uniform4fv(gl.getUniformLocation(quadProgram, 'u_tint'), tint);
      gl.drawArrays(gl.TRIANGLES, 0, triangles.length / 5);
      gl.disableVertexAttribArray(aWorld);
      gl.disableVertexAttribArray(aUv);
    }
    gl.disable(gl.BLEND);
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
      case 'swap_image':
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
      case 'play_video':
        if (h.mediaElement instanceof HTMLVideoElement) {
          if (h.mediaElement.paused) h.mediaElement.play().catch(() => {}); else h.mediaElement.pause();
        } else if (target) {
          assetUrl(target, h.actionScript).then((url) => { const v = document.createElement('video');
            v.src = url; v.controls = true; v.autoplay = true; v.style.maxWidth = '100%';
            showPanel(h.title, ''); $('panel-text').appendChild(v); });
        }
        break;
      case 'play_sound':
        if (target) assetUrl(target, h.actionScript).then((url) => new Audio(url).play().catch(() => {}));
        break;
      case 'jump': {
        const frame = parseInt(target, 10);
        const f = frames.find((fr) => fr.index === frame);
        if (f) walkTo(f.s);
        break;
      }
      case 'open_url':
        if (/^https?:\/\//i.test(target)) window.open(target, '_blank', 'noopener,noreferrer');
        else showPanel(h.title, 'This link was not opened (only http and https links are allowed): ' + target);
        break;
      case 'show_text':
      default:
        showPanel(h.title, target);
    }
  }

  function checkProximity() {
    const here = frameAtS(player.state.s);
    for (const h of hotspots) {
      if (h.trigger !== 'proximity' || !(h.trigger_distance_m > 0)) continue;
      let cx, cy;
      if (h.world_corners.length) {
        cx = h.world_corners.reduce((a, c) => a + c[0], 0) / h.world_corners.length;
        cy = h.world_corners.reduce((a, c) => a + c[1], 0) / h.world_corners.length;
      } else {
        const f = frames.find((fr) => fr.index === h.frame);
        if (!f) continue;
        cx = f.x; cy = f.y;
      }
      const inside = Math.hypot(here.x - cx, here.y - cy) <= h.trigger_distance_m;
      if (inside && !h.inside) fire(h);
      h.inside = inside;
    }
  }

  // ---------------------------------------------------------------- walking
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
      if (!k || k.level === 'full' || k.fullRequested) continue;
      k.fullRequested = true;
      loadImage(k.full, k.full_script).then((img) => {
        k.image = img; k.level = 'full';
        if (i === player.state.keyframe) player.state.level = 'full';
        requestDraw();
      }).catch((e) => { k.fullRequested = false; console.warn(e.message); });
    }
  }

  function loadPreviews() {
    const byRank = keyframes.slice().sort((a, b) => a.rank - b.rank);
    let next = 0;
    const worker = () => {
      if (next >= byRank.length) return Promise.resolve();
      const k = byRank[next++];
      return loadImage(k.preview, k.preview_script).then((img) => {
        if (k.level !== 'full') { k.image = img; k.level = 'preview'; }
        if (player.state.keyframe < 0 || !keyframes[player.state.keyframe].image) {
          const i = nearestKeyframe(player.state.s, true);
          if (i >= 0) { player.state.keyframe = -1; setKeyframe(i); }
        }
        requestDraw();
      }).catch((e) => console.warn(e.message)).then(worker);
    };
    return Promise.all([worker(), worker(), worker(), worker()]);
  }

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
      if (h.trigger !== 'click') continue;
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
    const onOrientation = (e) => {
      if (e.alpha === null) return;
      if (yawOffset === null) yawOffset = player.state.yaw - e.alpha * DEG;
      player.state.yaw = yawOffset + e.alpha * DEG;
      player.state.pitch = Math.max(-85 * DEG, Math.min(85 * DEG, (e.beta - 90) * DEG));
      const now = performance.now();
      if (Math.abs(e.gamma) > 20 && now - lastWalk > 700) { lastWalk = now; walk(e.gamma > 0 ? 1 : -1); }
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

  function stepAnimation() {
    if (!animation) return false;
    const t = Math.min(1, (performance.now() - animation.start) / animation.duration);
    const ease = t < 0.5 ? 2 * t * t : 1 - 2 * (1 - t) * (1 - t);
    player.state.s = animation.from + (animation.to - animation.from) * ease;
    if (t >= 1) { animation = null; player.state.moving = false; }
    const i = nearestKeyframe(player.state.s, true);
    if (i >= 0) setKeyframe(i);
    checkProximity();
    return true;
  }

  function frame() {
    drawRequested = false;
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
        `${player.state.s.toFixed(1)} m of ${(frames.length ? frames[frames.length - 1].s : 0).toFixed(1)} m · ${k.level}`;
    }
    const fading = performance.now() - fade.start < FADE_MS;
    const playing = (m) => m instanceof HTMLVideoElement && !m.paused && !m.ended;
    const video = hotspots.some((s) => playing(s.mediaElement) || (s.swapped && playing(s.actionImage)));
    if (animating || fading || video) requestDraw();
  }

  // ---------------------------------------------------------------- start
  function start(data) {
    if (!data || data.format !== 'plenopath-tour') throw new Error('tour.json is not a Plenopath tour.');
    if (data.version > 1) throw new Error('This tour was made by a newer Plenopath Studio (format ' + data.version + ').');
    tour = data;
    document.title = tour.title || 'Plenopath tour';
    $('title').textContent = tour.title || '';
    frames = tour.path.frames.map((f) => ({ index: f[0], x: f[1], y: f[2], heading: f[3] * DEG, s: f[4] }));
    keyframes = tour.keyframes.map((k) => Object.assign({}, k, { heading: k.heading_deg * DEG, image: null, level: 'none' }));
    keyframes.sort((a, b) => a.s - b.s);
    if (keyframes.length === 0) throw new Error('This tour has no keyframes.');
    const start = frames.find((f) => f.index === tour.start_frame) || keyframes[0];
    player.state.s = start.s;
    player.state.yaw = start.heading;
    hotspots = (tour.hotspots || []).map((h) => {
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
    initGl();
    bindInput();
    fitMap();
    requestDraw();
    return loadPreviews();
  }

  player.walk = walk;
  player.walkToFrame = (frame) => { const f = frames.find((fr) => fr.index === frame); if (f) walkTo(f.s); };
  player.ready = loadTour().then(start).then(() => true).catch((e) => { showError(e.message); return false; });
})();
