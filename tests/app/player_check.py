#!/usr/bin/env python3
"""Opens an exported tour in headless Chromium and checks it as a viewer would.

usage: player_check.py PACKAGE_DIR SCREENSHOT_PREFIX [--xss-title TITLE] [--no-hotspots] [--swap-sequence]
                       [--transition A B C]

Talks to Chromium over --remote-debugging-pipe (DevTools protocol, NUL-separated JSON on fds 3 and 4), so it
needs nothing but Debian's chromium and python3. Checks: the panorama canvas renders non-blank; a walk key
moves to another keyframe and the picture changes; clicking a hotspot fires its action; a hotspot title that
holds markup is shown as text and never executed; with --swap-sequence, the clicked hotspot swaps its region
for an image sequence that plays, holds its last frame, and swaps back on a second click; with --transition A B
C (keyframe numbers, B between A and C), the view the walk from A to C draws at B's spot is closer to B's
own picture than a plain cross-fade of A and C would be. Then the same page in a Chromium WITHOUT
--allow-file-access-from-files (a browser as a viewer has it, where file:// images are tainted): it still renders
non-blank from the previews, and its status line says the full resolution needs http. Writes
SCREENSHOT_PREFIX-start.png, -walked.png and -file-only.png.
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
  const gl = c.getContext('webgl');
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

def check_hotspot_click(b, spot):
    fired_before = b.evaluate("window.plenopathPlayer.events.length")
    b.click(spot['x'], spot['y'])
    time.sleep(0.3)
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
    time.sleep(0.15)
    early = b.evaluate(PIXELS)
    b.wait_for("window.plenopathPlayer.hotspots.find(s => s.swapped).actionImage.ended", timeout=15,
               what='the image sequence to play to its end')
    time.sleep(0.5)
    late = b.evaluate(PIXELS)
    b.screenshot(prefix + '-swapped.png')
    time.sleep(0.5)
    held = b.evaluate(PIXELS)
    print('swap: before %d, early %d, end %d, held %d' % (before['hash'], early['hash'], late['hash'], held['hash']))
    if early['hash'] == before['hash']:
        fail('the region did not change when the sequence was swapped in')
    if late['hash'] == early['hash']:
        fail('the sequence did not play (the picture stayed the same)')
    if held['hash'] != late['hash']:
        fail('the sequence does not hold its last frame')
    # The second click, then the picture: waited for by state, not by time (a loaded machine renders late).
    fired = b.evaluate("window.plenopathPlayer.events.length")
    b.click(spot['x'], spot['y'])
    deadline = time.time() + 2.0
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
        time.sleep(0.8)  # the cross-fade
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
    b = Browser()
    try:
        open_page(b, package)
        b.wait_for("window.plenopathPlayer.state.level === 'full'", what='the full-resolution image')
        time.sleep(0.8)  # the cross-fade
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
            before = b.evaluate(PIXELS)
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
        b.wait_for("window.plenopathPlayer.state.level === 'full'", what='the full image after walking')
        time.sleep(0.8)
        walked = b.evaluate(PIXELS)
        b.screenshot(prefix + '-walked.png')
        print('walked view:', json.dumps(walked), 'keyframe', b.evaluate("window.plenopathPlayer.state.keyframe"))
        if walked['hash'] == start['hash']:
            fail('the picture did not change after walking')
        if walked['std'] < 8:
            fail('the view after walking looks blank')
    finally:
        b.close()
    check_without_file_access(package, prefix)
    print('ok')

if __name__ == '__main__':
    main()
