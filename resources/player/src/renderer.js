// ---------------------------------------------------------------- renderer: WebGL
// The panorama (two keyframe textures cross-faded on a full-screen triangle) and the hotspot quads. Walking
// from one keyframe to the next, the viewer is between them: each keyframe is drawn as seen from the
// viewer's own spot, projected onto a room around it (the floor at the camera height below, a round wall
// ROOM_RADIUS_M away, the ceiling ROOM_HEIGHT_M up), and the two blend by how far along the viewer is - so
// stills metres apart are walked through, not jump-cut. GL state
// is made once: programs, their attribute and uniform locations, the constant sampler units; a hotspot's
// vertices are uploaded when they change (another keyframe, another corner set), a video frame when the video
// has moved on, never every frame.
const TEXTURE_CACHE = 16;      // GPU textures kept (nearest keyframes)
const FADE_MS = 350;
const ROOM_RADIUS_M = 3.0;     // the room proxy of the walk between keyframes (at least 1 m beyond the viewer)
const ROOM_HEIGHT_M = 2.7;

const canvas = $('view');
// WebGL2 where there is one (mipmaps of any size), else WebGL1; the shaders are GLSL ES 1.00 for both.
const GL_OPTIONS = { antialias: true, xrCompatible: true, preserveDrawingBuffer: true };
const gl = canvas.getContext('webgl2', GL_OPTIONS) || canvas.getContext('webgl', GL_OPTIONS);
const BACKGROUND_VS = 'attribute vec2 a_pos; varying vec2 v_ndc;' +
  'void main(){ v_ndc = a_pos; gl_Position = vec4(a_pos, 0.0, 1.0); }';
const BACKGROUND_FS = 'precision highp float; varying vec2 v_ndc;' +
  'uniform mat3 u_ray; uniform sampler2D u_tex0; uniform sampler2D u_tex1;' +
  'uniform float u_heading0; uniform float u_heading1; uniform float u_mix;' +
  'uniform vec2 u_off0; uniform vec2 u_off1; uniform float u_radius0; uniform float u_radius1;' +
  'uniform float u_eye; uniform float u_room; uniform vec2 u_look;' +
  'const float PI = 3.141592653589793;' +
  // The point of the room proxy that the viewer, `off` from the keyframe, sees along d (unit), as seen
  // from the keyframe: the nearest of the round wall and the floor or ceiling.
  'vec3 proxy(vec2 off, float radius, vec3 d){' +
  '  if (dot(off, off) < 1e-8) return d;' +
  '  float a = dot(d.xy, d.xy); float b = dot(off, d.xy); float c = dot(off, off) - radius * radius;' +
  '  float t = a > 1e-8 ? (-b + sqrt(max(b * b - a * c, 0.0))) / a : 1e6;' +
  '  if (d.z < -1e-6) t = min(t, -u_eye / d.z);' +
  '  if (d.z > 1e-6) t = min(t, (u_room - u_eye) / d.z);' +
  '  return vec3(off, 0.0) + t * d; }' +
  // The azimuth is measured from the view direction (u_look), so that atan's jump of 2 pi lies behind the
  // viewer, and the texture wraps (REPEAT): no seam column where the mipmap level would jump.
  'vec4 equirect(sampler2D t, float shift, vec3 d){' +
  '  float phi = atan(dot(d.xy, vec2(-u_look.y, u_look.x)), dot(d.xy, u_look)); float el = atan(d.z, length(d.xy));' +
  '  float u = (shift - phi + PI) / (2.0 * PI); float v = (0.5 * PI - el) / PI;' +
  '  return texture2D(t, vec2(u, v)); }' +
  'void main(){ vec3 d = normalize(u_ray * vec3(v_ndc, 1.0));' +
  '  gl_FragColor = mix(equirect(u_tex1, u_heading1, proxy(u_off1, u_radius1, d)),' +
  '                     equirect(u_tex0, u_heading0, proxy(u_off0, u_radius0, d)), u_mix); }';
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

// A program with its attribute and uniform locations, looked up once.
function makeProgram(vs, fs, attributes, uniforms) {
  const program = compile(vs, fs);
  const out = { program, attribute: {}, uniform: {} };
  for (const a of attributes) out.attribute[a] = gl.getAttribLocation(program, a);
  for (const u of uniforms) out.uniform[u] = gl.getUniformLocation(program, u);
  return out;
}

let background, quadProgram, triangleBuffer, whiteTexture;
function initGl() {
  if (!gl) throw new Error('This browser has no WebGL: the tour cannot be shown.');
  background = makeProgram(BACKGROUND_VS, BACKGROUND_FS, ['a_pos'],
    ['u_ray', 'u_tex0', 'u_tex1', 'u_heading0', 'u_heading1', 'u_mix', 'u_off0', 'u_off1', 'u_radius0',
      'u_radius1', 'u_eye', 'u_room', 'u_look']);
  quadProgram = makeProgram(QUAD_VS, QUAD_FS, ['a_world', 'a_uv'], ['u_view_proj', 'u_media', 'u_tint']);
  // Sampler units never change.
  gl.useProgram(background.program);
  gl.uniform1i(background.uniform.u_tex0, 0);
  gl.uniform1i(background.uniform.u_tex1, 1);
  gl.useProgram(quadProgram.program);
  gl.uniform1i(quadProgram.uniform.u_media, 0);
  triangleBuffer = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, triangleBuffer);
  gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([-1, -1, 3, -1, -1, 3]), gl.STATIC_DRAW);
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

// Keyframe textures: an LRU of GPU textures, so long tours stay within GPU memory. A keyframe's image (the
// preview, then the full one) is decoded and uploaded off the frame loop; until it is, the keyframe keeps the
// texture it had (or none: then it is not drawn). k.textureLevel is the level the texture shows.
const textureOrder = [];
function keyframeTexture(k) {
  if (k.image && k.textureImage !== k.image && k.decodingImage !== k.image) {
    const image = k.image, level = k.level;
    k.decodingImage = image;
    decodeForTexture(image).then((source) => {
      if (k.decodingImage !== image) { if (source.close) source.close(); return; }
      k.decodingImage = null;
      const made = makeMipmappedTexture(source, true);
      if (k.texture) gl.deleteTexture(k.texture);
      k.texture = made.texture;
      k.textureInfo = { width: made.width, height: made.height, mipmaps: made.mipmaps, repeat: made.repeat };
      k.textureImage = image;
      k.textureLevel = level;
      touchTexture(k);
      requestDraw();
    }).catch((e) => { if (k.decodingImage === image) k.decodingImage = null; console.warn('keyframe ' + k.frame + ': ' + e.message); });
  }
  if (k.texture) touchTexture(k);
  return k.texture || null;
}

function touchTexture(k) {
  const at = textureOrder.indexOf(k);
  if (at >= 0) textureOrder.splice(at, 1);
  textureOrder.push(k);
  while (textureOrder.length > TEXTURE_CACHE) {
    const old = textureOrder.shift();
    gl.deleteTexture(old.texture);
    old.texture = null;
    old.textureImage = null;
    old.textureInfo = null;
    old.textureLevel = 'none';
  }
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

// The keyframes either side of arc length s that have an image, and how far along from the first to the
// second the viewer is; null when s is at a keyframe or outside them.
function walkBracket(s) {
  let before = null, after = null;
  for (const k of keyframes) {
    if (!k.image) continue;
    if (k.s <= s && (!before || k.s > before.s)) before = k;
    if (k.s >= s && (!after || k.s < after.s)) after = k;
  }
  if (!before || !after || before === after || after.s - before.s < 1e-6) return null;
  return { before, after, along: (s - before.s) / (after.s - before.s) };
}

// The background: keyframe k0 blended over k1 by `mix`, each seen from the viewer at plan point `at`
// (null: from the keyframe itself).
function drawBackground(ray, k0, k1, mix, at) {
  // A keyframe whose texture is not uploaded yet gives way to the other one.
  const t0 = keyframeTexture(k0), t1 = k1 === k0 ? t0 : keyframeTexture(k1);
  if (!t0 && !t1) return false;
  if (!t0) { k0 = k1; mix = 1; } else if (!t1) { k1 = k0; }
  const off = (k) => at ? [at.x - k.x, at.y - k.y] : [0, 0];
  const radius = (o) => Math.max(ROOM_RADIUS_M, Math.hypot(o[0], o[1]) + 1.0);
  const off0 = off(k0), off1 = off(k1);
  const pos = background.attribute.a_pos;
  gl.useProgram(background.program);
  gl.bindBuffer(gl.ARRAY_BUFFER, triangleBuffer);
  gl.enableVertexAttribArray(pos);
  gl.vertexAttribPointer(pos, 2, gl.FLOAT, false, 0, 0);
  gl.uniformMatrix3fv(background.uniform.u_ray, false, ray);
  gl.activeTexture(gl.TEXTURE0);
  gl.bindTexture(gl.TEXTURE_2D, k0.texture);
  gl.activeTexture(gl.TEXTURE1);
  gl.bindTexture(gl.TEXTURE_2D, k1.texture);
  // Forward of the view in the plan, and each keyframe's heading relative to it, within (-pi, pi].
  // Looking up or down the forward's level part vanishes: the screen's up (down when looking up) stands in.
  const upNorm = Math.hypot(ray[3], ray[4], ray[5]) || 1, fz = ray[8] / (Math.hypot(ray[6], ray[7], ray[8]) || 1);
  const look = [ray[6] - fz * ray[3] / upNorm, ray[7] - fz * ray[4] / upNorm];
  const lookAngle = Math.atan2(look[1], look[0]), norm = Math.hypot(look[0], look[1]);
  const relative = (heading) => Math.atan2(Math.sin(heading - lookAngle), Math.cos(heading - lookAngle));
  gl.uniform2f(background.uniform.u_look, norm > 1e-9 ? look[0] / norm : 1, norm > 1e-9 ? look[1] / norm : 0);
  gl.uniform1f(background.uniform.u_heading0, relative(k0.heading));
  gl.uniform1f(background.uniform.u_heading1, relative(k1.heading));
  gl.uniform1f(background.uniform.u_mix, mix);
  gl.uniform2fv(background.uniform.u_off0, off0);
  gl.uniform2fv(background.uniform.u_off1, off1);
  gl.uniform1f(background.uniform.u_radius0, radius(off0));
  gl.uniform1f(background.uniform.u_radius1, radius(off1));
  gl.uniform1f(background.uniform.u_eye, tour.camera_height_m || 1.6);
  gl.uniform1f(background.uniform.u_room, Math.max(ROOM_HEIGHT_M, (tour.camera_height_m || 1.6) + 0.3));
  gl.disable(gl.DEPTH_TEST);
  gl.drawArrays(gl.TRIANGLES, 0, 3);
  gl.disableVertexAttribArray(pos);
  return true;
}

let fade = { from: -1, start: 0 };
function drawScene(width, height, ray, viewProj) {
  const current = keyframes[player.state.keyframe];
  if (!current) return;
  // Walking: between the keyframes either side, from where the viewer is.
  const bracket = player.state.moving ? walkBracket(player.state.s) : null;
  if (bracket) {
    drawBackground(ray, bracket.after, bracket.before, bracket.along, frameAtS(player.state.s));
    return;
  }
  const previous = keyframes[fade.from] || current;
  const t = Math.min(1, (performance.now() - fade.start) / FADE_MS);
  drawBackground(ray, current, previous, t, null);
  player.state.textureLevel = current.texture ? current.textureLevel : 'none';
  if (t >= 1) {
    drawTiles(current, ray, viewProj, height);
    drawHotspots(current, viewProj);
  }
}

// The texture a hotspot shows: its media, or what its swap action put in its place. A video's current frame
// is uploaded when the video has moved on to another frame (or another video is shown), not every draw.
function hotspotTexture(h) {
  const source = h.swapped && h.actionImage ? h.actionImage : h.mediaElement;
  if (!source) return null;
  if (source instanceof HTMLVideoElement) {
    if (source.readyState < 2) return null;
    if (!h.videoTexture) h.videoTexture = makeTexture(null);
    if (h.videoSource !== source || h.videoTime !== source.currentTime || !source.paused) {
      gl.bindTexture(gl.TEXTURE_2D, h.videoTexture);
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, gl.RGBA, gl.UNSIGNED_BYTE, source);
      h.videoSource = source;
      h.videoTime = source.currentTime;
    }
    return h.videoTexture;
  }
  if (!source.texture) source.texture = makeTexture(source);
  return source.texture;
}

// A hotspot's triangles (eye-relative corners and texture coordinates) as seen from keyframe k, in a vertex
// buffer of its own that is filled again only when k changes.
function hotspotVertices(h, k) {
  if (h.vertexKeyframe === k) return h.vertexCount;
  h.vertexKeyframe = k;
  h.vertexCount = 0;
  const corners = hotspotCorners(h, k);
  if (!corners || corners.length < 3) return 0;
  const uv = [[0, 0], [1, 0], [1, 1], [0, 1]];
  const triangles = [];
  for (const i of [0, 1, 2, 0, 2, 3]) {
    if (i >= corners.length) continue;
    triangles.push(...corners[i], ...(uv[i] || [0, 0]));
  }
  if (!h.vertexBuffer) h.vertexBuffer = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, h.vertexBuffer);
  gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(triangles), gl.STATIC_DRAW);
  h.vertexCount = triangles.length / 5;
  return h.vertexCount;
}

function drawHotspots(k, viewProj) {
  const aWorld = quadProgram.attribute.a_world, aUv = quadProgram.attribute.a_uv;
  gl.useProgram(quadProgram.program);
  gl.enable(gl.BLEND);
  gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
  gl.uniformMatrix4fv(quadProgram.uniform.u_view_proj, false, viewProj);
  for (const h of hotspots) {
    const count = hotspotVertices(h, k);
    if (count === 0) continue;
    const texture = hotspotTexture(h);
    gl.bindBuffer(gl.ARRAY_BUFFER, h.vertexBuffer);
    gl.enableVertexAttribArray(aWorld);
    gl.enableVertexAttribArray(aUv);
    gl.vertexAttribPointer(aWorld, 3, gl.FLOAT, false, 20, 0);
    gl.vertexAttribPointer(aUv, 2, gl.FLOAT, false, 20, 12);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, texture || whiteTexture);
    const tint = texture ? [1, 1, 1, 1] : [0.2, 0.5, 1.0, 0.25];  // an event region without media: a glow
    gl.uniform4fv(quadProgram.uniform.u_tint, tint);
    gl.drawArrays(gl.TRIANGLES, 0, count);
    gl.disableVertexAttribArray(aWorld);
    gl.disableVertexAttribArray(aUv);
  }
  gl.disable(gl.BLEND);
}
