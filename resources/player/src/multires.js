// ---------------------------------------------------------------- multires: cube tiles of a keyframe
// When tour.json describes cube tiles (tour.tiles: levels coarsest first, the six faces' axes in the camera
// frame; keyframe.tiles: the folder), a keyframe at rest is drawn from them over its equirectangular preview:
// the level is the coarsest whose face has at least the screen's pixels per radian at the view centre (a face
// of s pixels spans 90 degrees: s / 2 pixels per radian there), never one above MAX_TEXTURE_SIZE; only the
// tiles in view load, nearest the view centre first, coarse levels first; a level is drawn under the next
// finer one, so what is loaded stays on screen until the finer tile arrives. Levels no sharper than the
// equirectangular texture shown are not drawn (nor loaded). Walking between keyframes uses the equirectangular
// images alone.
const TILE_CACHE = 384;        // GPU tile textures kept
const TILE_LOADS = 6;          // tiles loading at once

const tileTextures = [];       // tiles holding a texture, least recently drawn first
let tileLoads = 0;
let tilesBlocked = false;      // the browser will not let tiles be read back (a file:// page): preview only
const multires = { enabled: true, level: -1, visible: 0, loaded: 0, drawn: 0 };

function hasTiles(k) { return !!(tour && tour.tiles && tour.tiles.projection === 'cube' && k && k.tiles); }

// The level for a view `fov` degrees high on a canvas `height` pixels high, as an index into tour.tiles.levels.
function chooseTileLevel(fov, height) {
  const levels = tour.tiles.levels, limit = gpuLimits().maxTextureSize;
  const needed = height / 2 / Math.tan(fov * DEG / 2);  // screen pixels per radian at the view centre
  let chosen = -1;
  for (let i = 0; i < levels.length; ++i) {
    if (levels[i].fallback_only) continue;
    if (levels[i].size > limit) break;
    chosen = i;
    if (levels[i].size / 2 >= needed) break;
  }
  return chosen;
}

// The tiles of keyframe k at `level`, made on first use: world-frame corners (eye-relative, on the unit
// cube), the centre direction and the angular radius of the tile (for the view test).
function levelTiles(k, level) {
  if (!k.tileLevels) k.tileLevels = [];
  if (k.tileLevels[level]) return k.tileLevels[level];
  const { size, tile_size: ts } = tour.tiles.levels[level];
  const n = Math.ceil(size / ts), ch = Math.cos(k.heading), sh = Math.sin(k.heading);
  // Camera frame (+x forward, +y left, +z up) to the plan frame: a turn by the keyframe's heading.
  const world = (c) => [c[0] * ch - c[1] * sh, c[0] * sh + c[1] * ch, c[2]];
  const unit = (v) => { const l = Math.hypot(v[0], v[1], v[2]); return [v[0] / l, v[1] / l, v[2] / l]; };
  const tiles = [];
  for (const face of tour.tiles.faces) {
    const at = (px, py) => {
      const a = 2 * px / size - 1, b = 2 * py / size - 1;
      return world([0, 1, 2].map((i) => face.forward[i] + a * face.right[i] + b * face.down[i]));
    };
    for (let y = 0; y < n; ++y) {
      for (let x = 0; x < n; ++x) {
        const x0 = x * ts, y0 = y * ts, x1 = Math.min(size, x0 + ts), y1 = Math.min(size, y0 + ts);
        const corners = [at(x0, y0), at(x1, y0), at(x1, y1), at(x0, y1)];
        const centre = unit(at((x0 + x1) / 2, (y0 + y1) / 2));
        const radius = Math.max(...corners.map((c) => {
          const u = unit(c);
          return Math.acos(Math.max(-1, Math.min(1, u[0] * centre[0] + u[1] * centre[1] + u[2] * centre[2])));
        }));
        const path = tour.tiles.path.replace('{level}', level).replace('{face}', face.name)
          .replace('{y}', y).replace('{x}', x);
        tiles.push({ level, corners, centre, radius, url: k.tiles + '/' + path, texture: null, loading: false,
          failed: false, buffer: null });
      }
    }
  }
  k.tileLevels[level] = tiles;
  return tiles;
}

function tileVertexBuffer(tile) {
  if (tile.buffer) return tile.buffer;
  const uv = [[0, 0], [1, 0], [1, 1], [0, 1]], data = [];
  for (const i of [0, 1, 2, 0, 2, 3]) data.push(...tile.corners[i], ...uv[i]);
  tile.buffer = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, tile.buffer);
  gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(data), gl.STATIC_DRAW);
  return tile.buffer;
}

function loadTile(tile) {
  tile.loading = true;
  ++tileLoads;
  const img = new Image();
  const done = () => { --tileLoads; tile.loading = false; requestDraw(); };
  img.onload = () => decodeForTexture(img).then((source) => {
    tile.texture = makeMipmappedTexture(source, false).texture;
    tileTextures.push(tile);
    while (tileTextures.length > TILE_CACHE) {
      const old = tileTextures.shift();
      gl.deleteTexture(old.texture);
      old.texture = null;
    }
  }).catch((e) => {
    tile.failed = true;
    // Every tile would fail alike (a file:// page): the full equirectangular images take over.
    if (e && e.name === 'SecurityError' && !tilesBlocked) { tilesBlocked = true; requestFull(player.state.keyframe); }
    console.warn('tile ' + tile.url + ': ' + (e && e.message));
  }).then(done);
  img.onerror = () => { tile.failed = true; console.warn('cannot load tile ' + tile.url); done(); };
  img.src = tile.url;
}

// Draws keyframe k's tiles for the view (ray: u_ray of viewMatrices; height: canvas pixels) and starts the
// loads the view wants. Returns the number of tiles drawn.
function drawTiles(k, ray, viewProj, height) {
  multires.level = -1; multires.visible = 0; multires.loaded = 0; multires.drawn = 0;
  if (!hasTiles(k)) return 0;
  const chosen = chooseTileLevel(player.state.fov, height);
  multires.level = chosen;
  if (!multires.enabled || tilesBlocked || chosen < 0) return 0;
  // The view cone: around the forward ray, out to the corner of the screen.
  const f = [ray[6], ray[7], ray[8]], fl = Math.hypot(...f);
  const corner = Math.atan(Math.hypot(ray[0], ray[1], ray[2], ray[3], ray[4], ray[5]) / fl);
  const angle = (c) => Math.acos(Math.max(-1, Math.min(1, (c[0] * f[0] + c[1] * f[1] + c[2] * f[2]) / fl)));
  const baseFace = k.textureInfo ? k.textureInfo.width / 4 : 0;  // the equirectangular texture's detail
  const wanted = [];
  const aWorld = quadProgram.attribute.a_world, aUv = quadProgram.attribute.a_uv;
  gl.useProgram(quadProgram.program);
  gl.uniformMatrix4fv(quadProgram.uniform.u_view_proj, false, viewProj);
  gl.uniform4fv(quadProgram.uniform.u_tint, [1, 1, 1, 1]);
  gl.activeTexture(gl.TEXTURE0);
  gl.enableVertexAttribArray(aWorld);
  gl.enableVertexAttribArray(aUv);
  for (let level = 0; level <= chosen; ++level) {
    const info = tour.tiles.levels[level];
    if (info.fallback_only || info.size <= baseFace) continue;
    const visible = levelTiles(k, level).map((t) => ({ t, a: angle(t.centre) }))
      .filter((v) => v.a < corner + v.t.radius).sort((p, q) => p.a - q.a);
    for (const { t } of visible) {
      if (level === chosen) { ++multires.visible; if (t.texture) ++multires.loaded; }
      if (!t.texture) { if (!t.loading && !t.failed) wanted.push(t); continue; }
      gl.bindBuffer(gl.ARRAY_BUFFER, tileVertexBuffer(t));
      gl.vertexAttribPointer(aWorld, 3, gl.FLOAT, false, 20, 0);
      gl.vertexAttribPointer(aUv, 2, gl.FLOAT, false, 20, 12);
      gl.bindTexture(gl.TEXTURE_2D, t.texture);
      gl.drawArrays(gl.TRIANGLES, 0, 6);
      const at = tileTextures.indexOf(t);
      if (at >= 0) { tileTextures.splice(at, 1); tileTextures.push(t); }
      ++multires.drawn;
    }
  }
  gl.disableVertexAttribArray(aWorld);
  gl.disableVertexAttribArray(aUv);
  for (const t of wanted) { if (tileLoads >= TILE_LOADS) break; loadTile(t); }
  return multires.drawn;
}
