#!/usr/bin/env python3
"""Opens an exported tour in headless Chromium and checks it as a viewer would.

usage: player_check.py PACKAGE_DIR SCREENSHOT_PREFIX [--xss-title TITLE] [--no-hotspots] [--swap-sequence]
                       [--transition A B C] [--max-texture N] [--webgl1] [--multires] [--gyro] [--frame-times]

Talks to Chromium over --remote-debugging-pipe (DevTools protocol, NUL-separated JSON on fds 3 and 4), so it
needs nothing but Debian's chromium and python3. Checks: the panorama canvas renders non-blank; a walk key
moves to another keyframe and the picture changes; clicking a hotspot fires its action; a hotspot title that
holds markup is shown as text and never executed; with --swap-sequence, the clicked hotspot swaps its region
for an image sequence that plays, holds its last frame, and swaps back on a second click; with --transition A B
C (keyframe numbers, B between A and C), the view the walk from A to C draws at B's spot is closer to B's
own picture than a plain cross-fade of A and C would be. Always: the start label names the keyframe at the
start frame (from tour.json); any page exception or console error fails the check.
--max-texture N: the GPU's MAX_TEXTURE_SIZE is cut to N: the keyframe textures fit, with mipmaps.
--webgl1: a browser without WebGL2.
--multires (a tour with cube tiles): a wide and a zoomed-in view choose different tile levels, each non-blank
and in line with the panorama.
--gyro: deviceorientation events with the screen upright and turned to landscape give the expected view.
--frame-times: walks the path back and forth and prints the p50/p95 frame time.
Then the same page in a Chromium WITHOUT --allow-file-access-from-files (a browser as a viewer has it,
where file:// images are tainted): it still renders non-blank from the previews, and its status line says
the full resolution needs http.
Writes SCREENSHOT_PREFIX-start.png, -walked.png and -file-only.png (and -tiles-fov*.png).
"""
import base64, json, os, subprocess, sys, tempfile, time

def fail(msg):
    print('FAIL: ' + msg)
    sys.exit(1)

class Browser:
    def __init__(self, file_access=True):
        self.profile = tempfile.mkdtemp(prefix='plenopath-chromium-')
        r_ours, w_chrome = os.pipe()   # chromium writes to its fd 4
        r_chrome, w_ours = os.pipe()   # chromium reads from its fd 3
        def setup():
            # Via fresh copies: dup2 onto the same number would keep close-on-exec set.
            a, b = os.dup(r_chrome), os.dup(w_chrome)
            os.dup2(a, 3)
            os.dup2(b, 4)
            os.set_inheritable(3, True)
            os.set_inheritable(4, True)
        args = ['chromium', '--headless=new', '--remote-debugging-pipe', '--no-sandbox', '--no-first-run',
                '--disable-background-networking', '--disable-component-update', '--disable-sync',
                '--disable-quic', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
                '--ignore-gpu-blocklist', '--window-size=1280,800', '--user-data-dir=' + self.profile]
        args += ['--allow-file-access-from-files'] if file_access else []
        args += ['about:blank']
        # close_fds=False: the fds 3 and 4 made in setup() must survive into chromium (our own pipe ends are
        # not inheritable, so nothing else leaks).
        self.proc = subprocess.Popen(args, preexec_fn=setup, close_fds=False,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(r_chrome); os.close(w_chrome)
        self.rd = os.fdopen(r_ours, 'rb', buffering=0)
        self.wr = os.fdopen(w_ours, 'wb', buffering=0)
        self.next_id = 0
        self.buffer = b''
        self.session = None
        self.page_errors = []   # exceptions and console errors of the page, as they arrive

    def note_event(self, event):
        """Keeps the page's exceptions and console errors: a player test fails on any of them."""
        method, params = event.get('method'), event.get('params', {})
        text = None
        if method == 'Runtime.exceptionThrown':
            d = params.get('exceptionDetails', {})
            text = 'exception: ' + (d.get('exception', {}).get('description') or d.get('text', '')) + \
                ' at %s:%s' % (d.get('url', ''), d.get('lineNumber', ''))
        elif method == 'Runtime.consoleAPICalled' and params.get('type') in ('error', 'assert'):
            text = 'console.' + params.get('type') + ': ' + ' '.join(str(a.get('value', a.get('description', ''))) for a in params.get('args', []))
        elif method == 'Log.entryAdded' and params.get('entry', {}).get('level') == 'error':
            e = params['entry']
            text = 'log error (%s): %s %s' % (e.get('source', ''), e.get('text', ''), e.get('url', ''))
        if text is not None:
            print('PAGE ERROR: ' + text)
            self.page_errors.append(text)

    def check_page_errors(self, when):
        if self.page_errors:
            fail('%d page error(s) %s, the first: %s' % (len(self.page_errors), when, self.page_errors[0]))

    def send(self, method, params=None, session=True, timeout=30):
        self.next_id += 1
        msg = {'id': self.next_id, 'method': method, 'params': params or {}}
        if session and self.session:
            msg['sessionId'] = self.session
        self.wr.write(json.dumps(msg).encode() + b'\0')
        deadline = time.time() + timeout
        while time.time() < deadline:
            while b'\0' not in self.buffer:
                chunk = self.rd.read(1 << 16)
                if not chunk:
                    fail('chromium closed the pipe during ' + method)
                self.buffer += chunk
            raw, self.buffer = self.buffer.split(b'\0', 1)
            reply = json.loads(raw)
            if 'method' in reply:
                self.note_event(reply)
            if reply.get('id') == self.next_id:
                if 'error' in reply:
                    fail(method + ': ' + json.dumps(reply['error']))
                return reply.get('result', {})
        fail('timeout waiting for ' + method)

    def evaluate(self, expression, await_promise=False):
        r = self.send('Runtime.evaluate', {'expression': expression, 'returnByValue': True,
                                           'awaitPromise': await_promise})
        if 'exceptionDetails' in r:
            fail('JavaScript error: ' + json.dumps(r['exceptionDetails'])[:500])
        return r['result'].get('value')

    def wait_for(self, expression, timeout=30, what=''):
        deadline = time.time() + timeout
        while time.time() < deadline:
            if self.evaluate(expression):
                return
            time.sleep(0.2)
        fail('timed out waiting for ' + (what or expression))

    def screenshot(self, file):
        data = self.send('Page.captureScreenshot', {'format': 'png'})['data']
        with open(file, 'wb') as f:
            f.write(base64.b64decode(data))

    def click(self, x, y):
        for kind in ('mouseMoved', 'mousePressed', 'mouseReleased'):
            self.send('Input.dispatchMouseEvent', {'type': kind, 'x': x, 'y': y, 'button': 'left', 'clickCount': 1})

    def key(self, key, code, keycode):
        for kind in ('keyDown', 'keyUp'):
            self.send('Input.dispatchKeyEvent', {'type': kind, 'key': key, 'code': code,
                                                 'windowsVirtualKeyCode': keycode, 'nativeVirtualKeyCode': keycode})

    def close(self):
        try:
            self.send('Browser.close', session=False, timeout=5)
        except (SystemExit, OSError):
            pass
        self.proc.kill()
        self.proc.wait()

PIXELS = """(() => {
  const c = document.getElementById('view');
  const gl = c.getContext('webgl2') || c.getContext('webgl');
  const w = c.width, h = c.height, px = new Uint8Array(w * h * 4);
  gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
  let sum = 0, sum2 = 0, hash = 0, n = 0;
  for (let i = 0; i < px.length; i += 4 * 7) {
    const v = (px[i] + px[i + 1] + px[i + 2]) / 3;
    sum += v; sum2 += v * v; n++;
    hash = (hash * 31 + px[i] + 7 * px[i + 1] + 13 * px[i + 2]) >>> 0;
  }
  const mean = sum / n;
  return {mean, std: Math.sqrt(Math.max(0, sum2 / n - mean * mean)), hash, w, h};
})()"""

def settled_pixels(b, timeout=10):
    """The picture once it stays the same for 0.4 s (a hotspot's poster or an image may still be arriving)."""
    deadline, last = time.time() + timeout, b.evaluate(PIXELS)
    while time.time() < deadline:
        time.sleep(0.4)
        now = b.evaluate(PIXELS)
        if now['hash'] == last['hash']:
            return now
        last = now
    return last


def check_hotspot_click(b, spot):
    fired_before = b.evaluate("window.plenopathPlayer.events.length")
    b.click(spot['x'], spot['y'])
    # Waited for by state: on a loaded machine the click lands late, and a label click then would undo it.
    deadline = time.time() + 5.0
    while time.time() < deadline and b.evaluate("window.plenopathPlayer.events.length") == fired_before:
        time.sleep(0.1)
    via = 'canvas'
    if b.evaluate("window.plenopathPlayer.events.length") == fired_before:
        b.click(spot['lx'], spot['ly'])
        time.sleep(0.3)
        via = 'label'
    events = b.evaluate("window.plenopathPlayer.events")
    if len(events) <= fired_before:
        fail('clicking the hotspot fired nothing')
    print('hotspot fired via %s: %s' % (via, json.dumps(events[-1])))
    if events[-1]['action'] == 'show_text' and b.evaluate("document.getElementById('panel').hidden"):
        fail('show_text did not open the panel')
    b.key('Escape', 'Escape', 27)
    return via


def check_swap_sequence(b, spot, before, prefix):
    """After the first click on a swap_image hotspot whose target is a video: the region shows the sequence."""
    if b.evaluate("window.plenopathPlayer.events.slice(-1)[0].action") != 'swap_image':
        fail('the hotspot is not a swap_image event')
    b.wait_for("(() => { const h = window.plenopathPlayer.hotspots.find(s => s.swapped);"
               " return !!(h && h.actionImage && h.actionImage.readyState >= 2); })()", timeout=15,
               what='the image sequence to load')
    # The first frame of the sequence on screen: waited for by state (a loaded machine draws late).
    early = b.evaluate(PIXELS)
    deadline = time.time() + 5.0
    while early['hash'] == before['hash'] and time.time() < deadline:
        time.sleep(0.05)
        early = b.evaluate(PIXELS)
    # The pictures while it plays, until it ends: on a loaded machine the first one may be drawn late, so
    # "it played" is any two different pictures of the sequence, not the first against the last.
    seen = {early['hash']}
    deadline = time.time() + 20.0
    while time.time() < deadline and not b.evaluate(
            "window.plenopathPlayer.hotspots.find(s => s.swapped).actionImage.ended"):
        seen.add(b.evaluate(PIXELS)['hash'])
        time.sleep(0.05)
    b.wait_for("window.plenopathPlayer.hotspots.find(s => s.swapped).actionImage.ended", timeout=5,
               what='the image sequence to play to its end')
    time.sleep(0.5)
    late = b.evaluate(PIXELS)
    seen.add(late['hash'])
    seen.discard(before['hash'])
    b.screenshot(prefix + '-swapped.png')
    time.sleep(0.5)
    held = b.evaluate(PIXELS)
    print('swap: before %d, early %d, end %d, held %d; %d pictures of the sequence seen'
          % (before['hash'], early['hash'], late['hash'], held['hash'], len(seen)))
    if early['hash'] == before['hash']:
        fail('the region did not change when the sequence was swapped in')
    if len(seen) < 2:
        fail('the sequence did not play (the picture stayed the same)')
    if held['hash'] != late['hash']:
        fail('the sequence does not hold its last frame')
    # The second click, then the picture: waited for by state, not by time (a loaded machine renders late).
    fired = b.evaluate("window.plenopathPlayer.events.length")
    b.click(spot['x'], spot['y'])
    deadline = time.time() + 5.0
    while time.time() < deadline and b.evaluate("window.plenopathPlayer.events.length") == fired:
        time.sleep(0.1)
    if b.evaluate("window.plenopathPlayer.events.length") == fired:
        b.click(spot['lx'], spot['ly'])  # the label, as the first click may have needed
    deadline = time.time() + 15.0
    back = b.evaluate(PIXELS)
    while back['hash'] != before['hash'] and time.time() < deadline:
        time.sleep(0.2)
        back = b.evaluate(PIXELS)
    if back['hash'] != before['hash']:
        fail('a second click did not bring the original region back')
    print('sequence swapped in, played, held its last frame, swapped back')


LIMIT_TEXTURE_SIZE = """(() => {
  for (const C of [window.WebGLRenderingContext, window.WebGL2RenderingContext]) {
    if (!C) continue;
    const get = C.prototype.getParameter;
    C.prototype.getParameter = function (p) {
      const v = get.call(this, p);
      return p === this.MAX_TEXTURE_SIZE ? Math.min(v, %d) : v;
    };
  }
})();"""


NO_WEBGL2 = """(() => {
  const get = HTMLCanvasElement.prototype.getContext;
  HTMLCanvasElement.prototype.getContext = function (kind, options) {
    return kind === 'webgl2' ? null : get.call(this, kind, options);
  };
})();"""


GRAB = """((name) => {
  const c = document.getElementById('view'), gl = c.getContext('webgl2') || c.getContext('webgl');
  const px = new Uint8Array(c.width * c.height * 4);
  gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
  (window.__grabs = window.__grabs || {})[name] = px;
  return true;
})('%s')"""
MAD = """((a, b) => {
  const p = window.__grabs[a], q = window.__grabs[b];
  let sum = 0;
  for (let i = 0; i < p.length; i += 4) sum += Math.abs(p[i] - q[i]) + Math.abs(p[i + 1] - q[i + 1]) + Math.abs(p[i + 2] - q[i + 2]);
  return sum / (p.length / 4 * 3);
})('%s', '%s')"""


def set_view(b, width, height, mobile=False, orientation=None):
    params = {'width': width, 'height': height, 'deviceScaleFactor': 1, 'mobile': mobile}
    if orientation is not None:
        params['screenOrientation'] = {'angle': orientation, 'type': {0: 'portraitPrimary', 90: 'landscapePrimary',
                                                                      180: 'portraitSecondary', 270: 'landscapeSecondary'}[orientation]}
    b.send('Emulation.setDeviceMetricsOverride', params)
    time.sleep(0.3)


def check_multires(b, prefix):
    """Cube tiles: a wide view and a zoomed-in one choose different levels, each drawn non-blank from its
    tiles, which agree with the equirectangular preview under them far better than a view turned 10 degrees."""
    set_view(b, 640, 400)
    levels = []
    for fov in (110, 40):
        b.evaluate("window.plenopathPlayer.zoomTo(%d)" % fov)
        b.wait_for("(() => { const t = window.plenopathPlayer.tiles; return t.level >= 0 && t.visible > 0 && "
                   "t.loaded === t.visible; })()", timeout=60, what='the tiles in view at fov %d' % fov)
        time.sleep(0.3)
        tiles = b.evaluate("Object.assign({}, window.plenopathPlayer.tiles)")
        size = b.evaluate("window.PLENOPATH_TOUR.tiles.levels[%d].size" % tiles['level'])
        view = b.evaluate(PIXELS)
        b.evaluate(GRAB % 'tiles')
        b.screenshot('%s-tiles-fov%d.png' % (prefix, fov))
        b.evaluate("window.plenopathPlayer.tiles.enabled = false; window.plenopathPlayer.zoomTo(%d)" % fov)
        time.sleep(0.4)
        b.evaluate(GRAB % 'preview')
        b.evaluate("window.plenopathPlayer.state.yaw += 10 * Math.PI / 180; window.plenopathPlayer.zoomTo(%d)" % fov)
        time.sleep(0.4)
        b.evaluate(GRAB % 'turned')
        b.evaluate("window.plenopathPlayer.state.yaw -= 10 * Math.PI / 180; window.plenopathPlayer.tiles.enabled = true;"
                   " window.plenopathPlayer.zoomTo(%d)" % fov)
        agree, turned = b.evaluate(MAD % ('tiles', 'preview')), b.evaluate(MAD % ('preview', 'turned'))
        print('fov %d: tile level %d (faces of %d px), %d tiles in view drawn %d; view %s; tiles vs preview %.2f, '
              'preview vs turned 10 deg %.2f (mean abs difference, 0-255)' %
              (fov, tiles['level'], size, tiles['visible'], tiles['drawn'], json.dumps(view), agree, turned))
        if view['std'] < 8:
            fail('the view drawn from tiles looks blank')
        if tiles['drawn'] < tiles['visible'] or agree == 0:
            fail('the tiles were not drawn')
        if not agree < 0.5 * turned:
            fail('the tiles do not line up with the panorama')
        levels.append(tiles['level'])
    if not levels[1] > levels[0]:
        fail('zooming in did not choose a finer tile level: %s' % levels)
    set_view(b, 1280, 800)


def check_gyro(b):
    """The gyroscope with the page upright, then turned to landscape either way: deviceorientation events of
    a device held as described give the view's yaw (relative to the first reading) and pitch."""
    set_view(b, 400, 800, mobile=True, orientation=0)
    if b.evaluate("document.getElementById('gyro').hidden"):
        fail('no gyroscope button on a touch device')
    b.evaluate("document.getElementById('gyro').click()")
    keyframe = b.evaluate("window.plenopathPlayer.state.keyframe")
    # (screen angle, alpha, beta, gamma) -> (yaw, pitch) in degrees, worked out from the device's axes
    # (W3C: x to the screen's right, y to its top, z out of it; R = Rz(alpha) Rx(beta) Ry(gamma) into east,
    # north, up; the camera looks out of the back).
    cases = [
        (0, 0, 90, 0, 0, 0),      # upright, portrait: looks north, level (the reference)
        (0, 0, 60, 0, 0, -30),    # top tilted away 30 deg: looks 30 deg down
        (0, 30, 90, 0, 30, 0),    # turned 30 deg counter-clockwise about the vertical: 30 deg to the left
        (90, 90, 0, -90, 0, 0),   # landscape, turned a quarter counter-clockwise (top to the west): north, level
        (90, 90, 0, -60, 0, -30), # ... the page's top tilted away 30 deg: 30 deg down
        (270, -90, 0, 90, 0, 0),  # landscape the other way (top to the east): north, level
    ]
    yaw0 = None
    for angle, alpha, beta, gamma, yaw, pitch in cases:
        if b.evaluate("screen.orientation.angle") != angle:
            set_view(b, 400 if angle in (0, 180) else 800, 800 if angle in (0, 180) else 400, mobile=True,
                     orientation=angle)
            if b.evaluate("screen.orientation.angle") != angle:
                fail('the emulated screen angle did not take')
        b.evaluate("window.dispatchEvent(new DeviceOrientationEvent('deviceorientation', "
                   "{alpha: %g, beta: %g, gamma: %g, absolute: false}))" % (alpha, beta, gamma))
        state = b.evaluate("window.plenopathPlayer.state")
        got_yaw, got_pitch = state['yaw'] * 180 / 3.141592653589793, state['pitch'] * 180 / 3.141592653589793
        if yaw0 is None:
            yaw0 = got_yaw
        rel = (got_yaw - yaw0 + 180) % 360 - 180
        print('gyro: screen %3d deg, alpha %4g beta %4g gamma %4g -> yaw %+7.2f (want %+g), pitch %+7.2f (want %+g)' %
              (angle, alpha, beta, gamma, rel, yaw, got_pitch, pitch))
        if abs(rel - yaw) > 0.5 or abs(got_pitch - pitch) > 0.5:
            fail('the gyroscope view does not follow the device and the screen orientation')
    if b.evaluate("window.plenopathPlayer.state.keyframe") != keyframe:
        fail('holding the device level walked')
    b.evaluate("document.getElementById('gyro').click()")
    set_view(b, 1280, 800)


def check_frame_times(b):
    """Walks the path end to end and back twice (the images load and reach the GPU), then again until 30
    frames were drawn back to back (or 90 s); prints their frame-time percentiles."""
    ends = b.evaluate("(() => { const k = window.PLENOPATH_TOUR.keyframes.slice().sort((a, b) => a.s - b.s);"
                      " return [k[0].frame, k[k.length - 1].frame]; })()")
    def walk_to(frame):
        b.evaluate("window.plenopathPlayer.walkToFrame(%d)" % frame)
        b.wait_for("!window.plenopathPlayer.state.moving", timeout=60, what='the walk to frame %d' % frame)
    for _ in range(2):  # the first pass loads the full images, the second uploads them on the way
        walk_to(ends[1])
        walk_to(ends[0])
    b.wait_for("window.plenopathPlayer.state.textureLevel === 'full'", timeout=60, what='the full image')
    print('keyframe textures before measuring: %s' % json.dumps(b.evaluate(
        "window.plenopathPlayer.textures().map(t => t.level + ' ' + t.width + 'x' + t.height)")))
    b.evaluate("window.plenopathFrameTimes.reset()")
    deadline = time.time() + 90
    while b.evaluate("window.plenopathFrameTimes().frames") < 30 and time.time() < deadline:
        walk_to(ends[1])
        walk_to(ends[0])
    t = b.evaluate("window.plenopathFrameTimes()")
    size = b.evaluate("[document.getElementById('view').width, document.getElementById('view').height]")
    print('frame time walking at %dx%d over %d frames: p50 %.1f ms, p95 %.1f ms (in the callback: p50 %.1f ms, '
          'p95 %.1f ms)' % (size[0], size[1], t['frames'], t['p50'], t['p95'], t['work_p50'], t['work_p95']))
    if t['frames'] < 10:
        fail('too few frames drawn back to back while walking: %s' % json.dumps(t))


def check_start_label(b, package):
    """At the start the label names the keyframe at the start frame, counted along the path (tour.json)."""
    with open(os.path.join(package, 'tour.json')) as f:
        tour = json.load(f)
    s_of = {fr[0]: fr[4] for fr in tour['path']['frames']}
    start_s = s_of.get(tour['start_frame'], 0.0)
    along = sorted(tour['keyframes'], key=lambda k: k['s'])
    i = min(range(len(along)), key=lambda j: abs(along[j]['s'] - start_s))
    total = tour['path']['frames'][-1][4]
    expected = 'Keyframe %d of %d · frame %d · %.1f m of %.1f m' % (i + 1, len(along), along[i]['frame'], start_s, total)
    label = b.evaluate("document.getElementById('status').textContent")
    print('start label: ' + label)
    if not label.startswith(expected):
        fail('the start label should begin %r' % expected)


def check_texture_limit(b, limit):
    """With MAX_TEXTURE_SIZE cut to `limit`, every keyframe texture fits it and the picture is there."""
    gpu = b.evaluate("window.plenopathPlayer.gpu()")
    textures = b.evaluate("window.plenopathPlayer.textures()")
    print('GPU: WebGL%d, MAX_TEXTURE_SIZE %d; textures: %s' % (gpu['version'], gpu['maxTextureSize'], json.dumps(textures)))
    if gpu['maxTextureSize'] != limit:
        fail('the player did not see the cut MAX_TEXTURE_SIZE')
    if not textures:
        fail('no keyframe texture on the GPU')
    for t in textures:
        if t['width'] > limit or t['height'] > limit:
            fail('a texture is larger than MAX_TEXTURE_SIZE: ' + json.dumps(t))
        if not t['mipmaps']:
            fail('a keyframe texture has no mipmaps: ' + json.dumps(t))


def open_page(b, package):
    target = next(t for t in b.send('Target.getTargets', session=False)['targetInfos'] if t['type'] == 'page')
    b.session = b.send('Target.attachToTarget', {'targetId': target['targetId'], 'flatten': True},
                       session=False)['sessionId']
    b.send('Page.enable')
    b.send('Runtime.enable')
    b.send('Emulation.setDeviceMetricsOverride', {'width': 1280, 'height': 800, 'deviceScaleFactor': 1,
                                                  'mobile': False})
    b.send('Page.navigate', {'url': 'file://' + package + '/index.html'})
    b.wait_for("window.plenopathPlayer !== undefined", what='the player script')
    if not b.evaluate("window.plenopathPlayer.ready", await_promise=True):
        fail('player reported an error: ' + str(b.evaluate("document.getElementById('error').textContent")))
    b.wait_for("window.plenopathPlayer.state.keyframe >= 0", what='the first keyframe')


def check_without_file_access(package, prefix):
    """A browser that taints file:// images: the previews (scripts) show, the full images are refused once."""
    b = Browser(file_access=False)
    try:
        open_page(b, package)
        b.wait_for("window.plenopathPlayer.state.note !== ''", timeout=30,
                   what='the player to find the full image unusable from file://')
        # The preview decoded, uploaded and faded in: on a loaded machine that takes a while.
        b.wait_for("window.plenopathPlayer.state.textureLevel === 'preview'", timeout=60,
                   what='the preview on screen')
        b.wait_for("(%s).std >= 8" % PIXELS.strip(), timeout=30, what='the preview drawn (non-blank)')
        time.sleep(0.8)  # the rest of the cross-fade
        view = b.evaluate(PIXELS)
        b.screenshot(prefix + '-file-only.png')
        status = b.evaluate("document.getElementById('status').textContent")
        level = b.evaluate("window.plenopathPlayer.state.level")
        print('without file access: level %s, view %s, status: %s' % (level, json.dumps(view), status))
        if level != 'preview':
            fail('without file access the view is at level ' + str(level) + ', not preview')
        if view['std'] < 8:
            fail('without file access the panorama canvas looks blank: ' + json.dumps(view))
        if 'serve the folder over http' not in status:
            fail('the status line does not say why the resolution is low: ' + status)
    finally:
        b.close()


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        sys.exit(2)
    package, prefix = os.path.abspath(sys.argv[1]), sys.argv[2]
    xss_title = sys.argv[sys.argv.index('--xss-title') + 1] if '--xss-title' in sys.argv else None
    max_texture = int(sys.argv[sys.argv.index('--max-texture') + 1]) if '--max-texture' in sys.argv else None
    b = Browser()
    try:
        target = next(t for t in b.send('Target.getTargets', session=False)['targetInfos'] if t['type'] == 'page')
        b.session = b.send('Target.attachToTarget', {'targetId': target['targetId'], 'flatten': True},
                           session=False)['sessionId']
        b.send('Page.enable')
        b.send('Runtime.enable')
        b.send('Log.enable')
        b.send('Emulation.setDeviceMetricsOverride', {'width': 1280, 'height': 800, 'deviceScaleFactor': 1,
                                                      'mobile': False})
        if max_texture:
            # A GPU that holds textures of max_texture pixels at most (a phone's), whatever this one holds.
            b.send('Page.addScriptToEvaluateOnNewDocument', {'source': LIMIT_TEXTURE_SIZE % max_texture})
        if '--webgl1' in sys.argv:
            # A browser without WebGL2: mipmaps only of power-of-two textures.
            b.send('Page.addScriptToEvaluateOnNewDocument', {'source': NO_WEBGL2})
        if '--gyro' in sys.argv:
            b.send('Emulation.setTouchEmulationEnabled', {'enabled': True, 'maxTouchPoints': 5})
        b.send('Page.navigate', {'url': 'file://' + package + '/index.html'})
        b.wait_for("window.plenopathPlayer !== undefined", what='the player script')
        if not b.evaluate("window.plenopathPlayer.ready", await_promise=True):
            fail('player reported an error: ' + str(b.evaluate("document.getElementById('error').textContent")))
        b.wait_for("window.plenopathPlayer.state.keyframe >= 0", what='the first keyframe')
        tiled = b.evaluate("!!(window.PLENOPATH_TOUR && window.PLENOPATH_TOUR.tiles)")
        # A tiled tour keeps the preview under its tiles; any other shows its full image.
        b.wait_for("window.plenopathPlayer.state.textureLevel === '%s'" % ('preview' if tiled else 'full'),
                   timeout=60, what='the keyframe image on screen')
        time.sleep(0.8)  # the cross-fade
        check_start_label(b, package)
        if max_texture:
            check_texture_limit(b, max_texture)
        start = b.evaluate(PIXELS)
        b.screenshot(prefix + '-start.png')
        print('start view:', json.dumps(start))
        if start['std'] < 8:
            fail('the panorama canvas looks blank: ' + json.dumps(start))
        keyframe0 = b.evaluate("window.plenopathPlayer.state.keyframe")

        # A markup title is text: no <img> created, nothing executed, the label shows the raw string.
        if xss_title is not None:
            labels = b.evaluate("Array.from(document.querySelectorAll('.hotspot-label')).map(l => l.textContent)")
            if xss_title not in labels:
                fail('hotspot title not shown as text; labels are ' + json.dumps(labels))
            if b.evaluate("document.querySelectorAll('#labels img, #labels script').length") != 0:
                fail('markup in a hotspot title became elements')
            if b.evaluate("window.__pwned !== undefined"):
                fail('markup in a hotspot title was executed')

        # Click on a visible hotspot: the quad itself on the canvas (ray test), else its label.
        spot = None if '--no-hotspots' in sys.argv else b.evaluate("""(() => {
          const l = Array.from(document.querySelectorAll('.hotspot-label')).find(e => !e.hidden);
          if (!l) return null; const r = l.getBoundingClientRect();
          return {x: r.left + r.width / 2, y: r.top + r.height / 2 + 40, lx: r.left + r.width / 2, ly: r.top + r.height / 2};
        })()""")
        if spot is None and '--no-hotspots' not in sys.argv:
            fail('no hotspot is visible from the start view')
        if spot is not None:
            before = settled_pixels(b)
            via = check_hotspot_click(b, spot)
            if '--swap-sequence' in sys.argv:
                if via != 'canvas':
                    fail('the swap hotspot was not hit on the canvas')
                check_swap_sequence(b, spot, before, prefix)

        if '--transition' in sys.argv:
            a, m, c = (int(v) for v in sys.argv[sys.argv.index('--transition') + 1:][:3])
            b.wait_for("window.plenopathPlayer.transitionError(%d, %d, %d) !== null" % (a, m, c), timeout=20,
                       what='the three keyframes of the transition')
            err = b.evaluate("window.plenopathPlayer.transitionError(%d, %d, %d)" % (a, m, c))
            print('transition at keyframe %d: walked %.2f, cross-fade %.2f (mean abs difference, 0-255)' %
                  (m, err['walked'], err['crossfade']))
            b.evaluate("window.plenopathPlayer.transitionError(%d, %d, %d, true)" % (a, m, c))
            b.screenshot(prefix + '-transition.png')
            if not err['walked'] < 0.85 * err['crossfade']:
                fail('the walk between stills is no closer to the picture in between than a cross-fade: ' +
                     json.dumps(err))

        # Walk forward: another keyframe, another picture.
        b.evaluate("document.getElementById('view').focus()")
        b.key('w', 'KeyW', 87)
        b.wait_for("window.plenopathPlayer.state.keyframe !== %d && !window.plenopathPlayer.state.moving" % keyframe0,
                   timeout=10, what='a walk to another keyframe')
        b.wait_for("window.plenopathPlayer.state.textureLevel === '%s'" % ('preview' if tiled else 'full'),
                   timeout=60, what='the keyframe image after walking')
        time.sleep(0.8)
        walked = b.evaluate(PIXELS)
        b.screenshot(prefix + '-walked.png')
        print('walked view:', json.dumps(walked), 'keyframe', b.evaluate("window.plenopathPlayer.state.keyframe"))
        if walked['hash'] == start['hash']:
            fail('the picture did not change after walking')
        if walked['std'] < 8:
            fail('the view after walking looks blank')
        if '--multires' in sys.argv:
            check_multires(b, prefix)
        if '--gyro' in sys.argv:
            check_gyro(b)
        if '--frame-times' in sys.argv:
            check_frame_times(b)
        time.sleep(0.3)
        b.evaluate('0')  # reads the events that arrived meanwhile
        b.check_page_errors('during the check')
    finally:
        b.close()
    check_without_file_access(package, prefix)
    print('ok')

if __name__ == '__main__':
    main()
