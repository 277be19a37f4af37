// ---------------------------------------------------------------- device orientation: where the screen looks
// The view of a phone or tablet held up like a window, from a deviceorientation event (alpha, beta, gamma:
// the device frame - x to the right of the screen in its natural orientation, y to its top, z out of it - is
// turned into the earth frame - x east, y north, z up - by Rz(alpha) Rx(beta) Ry(gamma), W3C) and the angle
// the browser has turned the page by (screen.orientation.angle, window.orientation: 90 when the device is
// turned a quarter counter-clockwise to landscape). The camera looks out of the back of the device (-z); the
// page's up is the device's y turned by -angle about z.

function screenAngle() {
  if (window.screen && screen.orientation && typeof screen.orientation.angle === 'number') return screen.orientation.angle;
  return typeof window.orientation === 'number' ? window.orientation : 0;
}

// {yaw, pitch, roll} in radians: yaw counter-clockwise from east, pitch up from level, roll positive when the
// page's right edge dips. Looking straight up or down, the yaw is that of the page's up (down when looking up).
function viewFromDeviceOrientation(alpha, beta, gamma, angle) {
  const a = alpha * DEG, b = beta * DEG, g = gamma * DEG, s = -angle * DEG;
  const ca = Math.cos(a), sa = Math.sin(a), cb = Math.cos(b), sb = Math.sin(b), cg = Math.cos(g), sg = Math.sin(g);
  // R = Rz(a) Rx(b) Ry(g), row-major.
  const R = [
    [ca * cg - sa * sb * sg, -sa * cb, ca * sg + sa * sb * cg],
    [sa * cg + ca * sb * sg, ca * cb, sa * sg - ca * sb * cg],
    [-cb * sg, sb, cb * cg],
  ];
  const apply = (v) => R.map((row) => row[0] * v[0] + row[1] * v[1] + row[2] * v[2]);
  const forward = apply([0, 0, -1]);
  const up = apply([-Math.sin(s), Math.cos(s), 0]);
  const right = apply([Math.cos(s), Math.sin(s), 0]);
  const pitch = Math.asin(Math.max(-1, Math.min(1, forward[2])));
  const level = [forward[0] - forward[2] * up[0], forward[1] - forward[2] * up[1]];
  return { yaw: Math.atan2(level[1], level[0]), pitch, roll: Math.atan2(-right[2], up[2]) };
}
