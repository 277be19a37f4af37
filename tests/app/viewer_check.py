#!/usr/bin/env python3
"""Opens an exported tour in the real third-party viewers, in headless Chromium, and checks what they draw.

usage: viewer_check.py PACKAGE_DIR NODE_MODULES SHOTS_DIR

PACKAGE_DIR: an export of tests/app/viewer_test.sh's capture (viewer_marks.py: world-fixed compass marks in
every keyframe, image-fixed marks in keyframe 0) with --multires --pannellum --marzipano --psv.
NODE_MODULES: where npm installed pannellum, marzipano, @photo-sphere-viewer/* and three.

A local http server (python3 -m http.server on a free port) serves the package at /pkg/ and the npm packages
at /npm/. For each viewer (Pannellum on pannellum.json's multiRes tiles, Marzipano on the package's own
marzipano.html, Photo Sphere Viewer's virtual-tour + map + markers plugins on psv.json):
- the view is not blank;
- orientation: pointed at each mark's (azimuth, elevation), the viewer shows that mark's colour at the
  centre of the screen (cube faces, their order and their orientation, up and down faces included);
- one link walked, as a click on it does: the scene changes, and the view looks the same way in the world
  (a world-fixed mark stays at the centre; for PSV, which turns towards the link, the mark in that direction);
- no console error, no page exception, no failed load (Runtime.exceptionThrown, console errors, Log errors).
Screenshots go to SHOTS_DIR/<viewer>-*.png.
"""
import base64, json, os, shutil, socket, subprocess, sys, tempfile, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import player_check  # noqa: E402  (the DevTools-pipe browser)
import viewer_marks as vm  # noqa: E402

WIDTH, HEIGHT = 1000, 700
# Keyframe 0 faces east (heading 0): its marks, as (azimuth, elevation, colour).
K0_MARKS = vm.marks_of_frame(0.0, True)


def fail(msg):
    print('FAIL: ' + msg)
    sys.exit(1)


class Browser(player_check.Browser):
    """player_check's browser (it notes the page's exceptions and console and log errors as they arrive),
    with what the viewers' checks read from the screen."""

    def errors(self):
        """The page's errors so far."""
        self.evaluate('0')  # drain the pipe
        return list(self.page_errors)

    def centre_colour(self):
        """The colour class of the 5x5 pixels at the centre of the screen (majority)."""
        png = base64.b64decode(self.send('Page.captureScreenshot', {
            'format': 'png', 'clip': {'x': WIDTH / 2 - 2.5, 'y': HEIGHT / 2 - 2.5, 'width': 5, 'height': 5,
                                      'scale': 1}})['data'])
        _, _, rows = vm.read_png_rgb(png)
        names = [vm.classify(p) for r in rows for p in r]
        return max(set(names), key=names.count), rows[len(rows) // 2][len(rows[0]) // 2]

    def shot(self, file):
        png = base64.b64decode(self.send('Page.captureScreenshot', {'format': 'png'})['data'])
        with open(file, 'wb') as f:
            f.write(png)
        w, h, rows = vm.read_png_rgb(png)
        values = [sum(p) / 3 for r in rows[::7] for p in r[::7]]
        mean = sum(values) / len(values)
        black = sum(1 for v in values if v < 8) / len(values)  # where a viewer drew no tile
        return (sum((v - mean) ** 2 for v in values) / len(values)) ** 0.5, black


def free_port():
    s = socket.socket()
    s.bind(('127.0.0.1', 0))
    port = s.getsockname()[1]
    s.close()
    return port


PANNELLUM_PAGE = """<!DOCTYPE html><html><head><meta charset="utf-8"><link rel="icon" href="data:,">
<link rel="stylesheet" href="/npm/pannellum/build/pannellum.css">
<style>html,body{margin:0;height:100%;overflow:hidden}#pano{width:100vw;height:100vh}</style>
<script src="/npm/pannellum/build/pannellum.js"></script></head><body><div id="pano"></div><script>
fetch('/pkg/pannellum.json').then(r => r.json()).then(config => {
  config.default.basePath = '/pkg/';   // the package's paths are relative to it
  config.default.sceneFadeDuration = 0;
  window.viewer = pannellum.viewer('pano', config);
});
</script></body></html>"""

PSV_PAGE = """<!DOCTYPE html><html><head><meta charset="utf-8"><link rel="icon" href="data:,">
<link rel="stylesheet" href="/npm/@photo-sphere-viewer/core/index.css">
<link rel="stylesheet" href="/npm/@photo-sphere-viewer/virtual-tour-plugin/index.css">
<link rel="stylesheet" href="/npm/@photo-sphere-viewer/map-plugin/index.css">
<link rel="stylesheet" href="/npm/@photo-sphere-viewer/markers-plugin/index.css">
<style>html,body{margin:0;height:100%;overflow:hidden}#viewer{width:100vw;height:100vh}</style>
<script type="importmap">{"imports": {
  "three": "/npm/three/build/three.module.js",
  "@photo-sphere-viewer/core": "/npm/@photo-sphere-viewer/core/index.module.js",
  "@photo-sphere-viewer/markers-plugin": "/npm/@photo-sphere-viewer/markers-plugin/index.module.js",
  "@photo-sphere-viewer/map-plugin": "/npm/@photo-sphere-viewer/map-plugin/index.module.js",
  "@photo-sphere-viewer/virtual-tour-plugin": "/npm/@photo-sphere-viewer/virtual-tour-plugin/index.module.js"}}
</script></head><body><div id="viewer"></div><script type="module">
import { Viewer } from '@photo-sphere-viewer/core';
import { MarkersPlugin } from '@photo-sphere-viewer/markers-plugin';
import { MapPlugin } from '@photo-sphere-viewer/map-plugin';
import { VirtualTourPlugin } from '@photo-sphere-viewer/virtual-tour-plugin';
const base = '/pkg/';
const tour = await (await fetch(base + 'psv.json')).json();
for (const n of tour.nodes) {
  n.panorama = base + n.panorama;
  if (n.thumbnail) n.thumbnail = base + n.thumbnail;
}
const viewer = new Viewer({
  container: 'viewer',
  navbar: false,
  plugins: [
    MarkersPlugin,
    [MapPlugin, {imageUrl: base + tour.map.imageUrl, center: tour.map.center, rotation: tour.map.rotation}],
    [VirtualTourPlugin, {positionMode: tour.positionMode, renderMode: '3d', nodes: tour.nodes,
                         startNodeId: tour.startNodeId, transitionOptions: {showLoader: false, effect: 'none', rotation: false},
                         map: {imageUrl: base + tour.map.imageUrl, size: tour.map.size}}],
  ],
});
const vt = viewer.getPlugin(VirtualTourPlugin);
window.psv = {viewer, vt, map: viewer.getPlugin(MapPlugin), node: null};
vt.addEventListener('node-changed', e => { window.psv.node = e.node.id; });
</script></body></html>"""


def settle(b, seconds=1.0):
    time.sleep(seconds)


def check_marks(b, name, point, wait):
    """Points the viewer at each mark of keyframe 0 and reads the centre."""
    wrong = []
    for az, el, colour in K0_MARKS:
        b.evaluate(point(az, el))
        wait()
        seen, rgb = b.centre_colour()
        print('%s: azimuth %6.1f elevation %5.1f: expected %-7s saw %-10s %s' % (name, az, el, colour, seen, rgb))
        if seen != colour:
            wrong.append((az, el, colour, seen))
    return wrong


def open_page(b, url, ready, what):
    b.page_errors.clear()
    b.send('Page.navigate', {'url': url})
    b.wait_for(ready, timeout=60, what=what)


def check_pannellum(b, root, shots):
    open_page(b, root + '/pannellum.html', "window.viewer && window.viewer.isLoaded() === true", 'Pannellum')
    b.wait_for("!window.viewer.getRenderer().isLoading()", timeout=60, what='Pannellum tiles')
    b.evaluate("viewer.setHfov(60, false)")
    settle(b)
    std, black = b.shot(shots + '/pannellum-start.png')
    print('pannellum: start view std %.1f, %.2f%% black, scene %s' % (std, 100 * black, b.evaluate("viewer.getScene()")))
    if std < 8 or black > 0.005:
        fail('pannellum: the view looks blank or has holes')
    if b.evaluate("viewer.getConfig().type") != 'multires':
        fail('pannellum: the scene is not multires')

    def wait():
        time.sleep(0.3)
        b.wait_for("!window.viewer.getRenderer().isLoading()", timeout=30, what='Pannellum tiles')
        time.sleep(0.3)
    wrong = check_marks(b, 'pannellum', lambda az, el: "viewer.setPitch(%f, false); viewer.setYaw(%f, false)" % (el, az),
                        wait)
    # The link forward, clicked: it lies at yaw 0 (keyframe 1 stands 1 m east). The view looks at it.
    b.evaluate("viewer.setPitch(-35, false); viewer.setYaw(0, false)")
    wait()
    spot = b.evaluate("""(() => { const h = viewer.getConfig().hotSpots.find(h => h.sceneId === 'k1');
      const r = h.div.getBoundingClientRect(); return {x: r.left + r.width / 2, y: r.top + r.height / 2}; })()""")
    b.shot(shots + '/pannellum-link.png')
    b.click(spot['x'], spot['y'])
    b.wait_for("viewer.getScene() === 'k1' && viewer.isLoaded() && !viewer.getRenderer().isLoading()", timeout=30,
               what='Pannellum scene k1 after the click')
    # sameAzimuth with northOffset: yaw 0 east in k0 (heading east) is yaw 90 in k1 (heading north).
    yaw = b.evaluate("viewer.getYaw()")
    b.evaluate("viewer.setPitch(0, false)")
    wait()
    seen, rgb = b.centre_colour()
    _, black = b.shot(shots + '/pannellum-walked.png')
    if black > 0.005:
        fail('pannellum: %.2f%% of the view after the walk is black' % (100 * black))
    print('pannellum: walked to k1, yaw %.1f, centre %s %s (expected red: east)' % (yaw, seen, rgb))
    if abs(yaw - 90) > 1 or seen != 'red':
        fail('pannellum: the view turned at the scene change (yaw %.1f, saw %s)' % (yaw, seen))
    return wrong


def check_marzipano(b, root, shots):
    open_page(b, root + '/pkg/marzipano.html', "window.marzipanoTour && window.marzipanoTour.current === 'k0'",
              'Marzipano')
    view = "marzipanoTour.scenes[marzipanoTour.current].view"
    b.evaluate(view + ".setFov(Math.PI / 3)")
    settle(b, 2)
    std, black = b.shot(shots + '/marzipano-start.png')
    print('marzipano: start view std %.1f, %.2f%% black' % (std, 100 * black))
    if std < 8 or black > 0.005:
        fail('marzipano: the view looks blank or has holes')
    # Marzipano's pitch grows downwards: pitch = -elevation.
    wrong = check_marks(b, 'marzipano', lambda az, el: view + ".setParameters({yaw: %f, pitch: %f})" % (
        az * 3.141592653589793 / 180, -el * 3.141592653589793 / 180), lambda: settle(b, 1.0))
    # The link forward, clicked: it lies at yaw 0, 35 degrees down (keyframe 1 stands 1 m east).
    b.evaluate(view + ".setParameters({yaw: 0, pitch: 35 * Math.PI / 180})")
    settle(b, 1.0)
    spot = b.evaluate("""(() => { const e = Array.from(document.querySelectorAll('.link')).find(e =>
      e.textContent === 'Forward' && e.getBoundingClientRect().width > 0);
      const r = e.getBoundingClientRect(); return {x: r.left + r.width / 2, y: r.top + r.height / 2}; })()""")
    b.shot(shots + '/marzipano-link.png')
    b.click(spot['x'], spot['y'])
    b.wait_for("marzipanoTour.current === 'k1'", timeout=10, what='Marzipano scene k1 after the click')
    yaw = b.evaluate(view + ".yaw() * 180 / Math.PI")
    b.evaluate(view + ".setPitch(0)")
    settle(b, 2)
    seen, rgb = b.centre_colour()
    _, black = b.shot(shots + '/marzipano-walked.png')
    if black > 0.005:
        fail('marzipano: %.2f%% of the view after the walk is black' % (100 * black))
    print('marzipano: walked to k1, yaw %.1f, centre %s %s (expected red: east)' % (yaw, seen, rgb))
    if abs(yaw - 90) > 1 or seen != 'red':
        fail('marzipano: the view turned at the scene change (yaw %.1f, saw %s)' % (yaw, seen))
    return wrong


def check_psv(b, root, shots):
    open_page(b, root + '/psv.html', "window.psv && window.psv.node === 'k0'", 'Photo Sphere Viewer')
    settle(b, 1.5)
    std, black = b.shot(shots + '/psv-start.png')
    print('psv: start view std %.1f, %.2f%% black' % (std, 100 * black))
    if std < 8 or black > 0.005:
        fail('psv: the view looks blank or has holes')
    if not b.evaluate("!!document.querySelector('.psv-map canvas')"):
        fail('psv: no map drawn')
    # psv.json turns each node so that yaw is the compass bearing; keyframe 0's image centre faces east.
    north = b.evaluate("psv.vt.getCurrentNode().sphereCorrection.pan") * -180 / 3.141592653589793
    wrong = check_marks(b, 'psv', lambda az, el: "psv.viewer.rotate({yaw: %f, pitch: %f})" % (
        (az + north) * 3.141592653589793 / 180, el * 3.141592653589793 / 180), lambda: settle(b, 0.6))
    # The link to k1 as the plugin's own click handler follows it: PSV opens k1 looking along the link.
    b.evaluate("""(() => { const n = psv.vt.getCurrentNode(); const l = n.links.find(l => l.nodeId === 'k1');
      psv.vt.setCurrentNode(l.nodeId, undefined, l); })()""")
    b.wait_for("psv.node === 'k1'", timeout=30, what='PSV node k1')
    settle(b, 1.5)
    yaw = b.evaluate("psv.viewer.getPosition().yaw * 180 / Math.PI")
    b.evaluate("psv.viewer.rotate({yaw: psv.viewer.getPosition().yaw, pitch: 0})")
    settle(b, 0.6)
    seen, rgb = b.centre_colour()
    _, black = b.shot(shots + '/psv-walked.png')
    if black > 0.005:
        fail('psv: %.2f%% of the view after the walk is black' % (100 * black))
    print('psv: walked to k1, yaw %.1f, centre %s %s (expected red: east, the link\'s direction)' % (yaw, seen, rgb))
    if abs(yaw - 90) > 1 or seen != 'red':
        fail('psv: k1 does not open looking along the link (yaw %.1f, saw %s)' % (yaw, seen))
    return wrong


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        sys.exit(2)
    package, modules, shots = (os.path.abspath(a) for a in sys.argv[1:])
    root = tempfile.mkdtemp(prefix='plenopath-viewers-')
    os.symlink(package, root + '/pkg')
    os.symlink(modules, root + '/npm')
    with open(root + '/pannellum.html', 'w') as f:
        f.write(PANNELLUM_PAGE)
    with open(root + '/psv.html', 'w') as f:
        f.write(PSV_PAGE)
    # The Marzipano page of the package loads ./marzipano.js when there (else a CDN: not in a test).
    shutil.copy(modules + '/marzipano/dist/marzipano.js', package + '/marzipano.js')
    port = free_port()
    server = subprocess.Popen([sys.executable, '-m', 'http.server', str(port), '--bind', '127.0.0.1',
                               '--directory', root], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    b = Browser()
    failures = []
    try:
        url = 'http://127.0.0.1:%d' % port
        deadline = time.time() + 10
        while True:
            try:
                socket.create_connection(('127.0.0.1', port), timeout=1).close()
                break
            except OSError:
                if time.time() > deadline:
                    fail('the http server did not start')
                time.sleep(0.1)
        target = next(t for t in b.send('Target.getTargets', session=False)['targetInfos'] if t['type'] == 'page')
        b.session = b.send('Target.attachToTarget', {'targetId': target['targetId'], 'flatten': True},
                           session=False)['sessionId']
        for method in ('Page.enable', 'Runtime.enable', 'Log.enable'):
            b.send(method)
        b.send('Emulation.setDeviceMetricsOverride', {'width': WIDTH, 'height': HEIGHT, 'deviceScaleFactor': 1,
                                                      'mobile': False})
        for name, check in (('pannellum', check_pannellum), ('marzipano', check_marzipano), ('psv', check_psv)):
            wrong = check(b, url, shots)
            errors = b.errors()
            if wrong:
                failures.append('%s: marks not at their directions: %s' % (name, wrong))
            if errors:
                failures.append('%s: page errors: %s' % (name, errors))
            print('%s: %d of %d marks at their directions, %d page errors' %
                  (name, len(K0_MARKS) - len(wrong), len(K0_MARKS), len(errors)))
    finally:
        b.close()
        server.terminate()
        server.wait()
        shutil.rmtree(root, ignore_errors=True)
    if failures:
        fail('; '.join(failures))
    print('ok')


if __name__ == '__main__':
    main()
