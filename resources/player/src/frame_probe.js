// ---------------------------------------------------------------- frame probe: how long frames take
// performance.now() at each frame of the draw loop. A frame drawn because the previous one asked for it (a
// walk, a fade, a playing video: frames back to back) gives an interval, the time from one requestAnimationFrame
// callback to the next, which includes the GPU when it is the bottleneck; every frame gives its work, the time
// spent in the callback. window.plenopathFrameTimes(n) reports percentiles over the last n (for tests, and for
// anyone who wants to know how a tour plays on their device).
const FRAME_PROBE_KEEP = 600;
const frameProbe = { intervals: [], work: [], lastStart: 0, chained: false, started: 0 };

function probeFrameStart() {
  const now = performance.now();
  if (frameProbe.chained) frameProbe.intervals.push(now - frameProbe.lastStart);
  frameProbe.lastStart = now;
  frameProbe.started = now;
  if (frameProbe.intervals.length > FRAME_PROBE_KEEP) frameProbe.intervals.shift();
}

// `chained`: this frame has asked for the next one.
function probeFrameEnd(chained) {
  frameProbe.work.push(performance.now() - frameProbe.started);
  if (frameProbe.work.length > FRAME_PROBE_KEEP) frameProbe.work.shift();
  frameProbe.chained = chained;
}

function percentile(values, p) {
  if (values.length === 0) return null;
  const sorted = values.slice().sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.max(0, Math.ceil(p / 100 * sorted.length) - 1))];
}

window.plenopathFrameTimes = (n) => {
  const last = (v) => v.slice(-(n || FRAME_PROBE_KEEP));
  const intervals = last(frameProbe.intervals), work = last(frameProbe.work);
  return { frames: intervals.length, p50: percentile(intervals, 50), p95: percentile(intervals, 95),
    work_frames: work.length, work_p50: percentile(work, 50), work_p95: percentile(work, 95) };
};
// Forgets what was measured (a test measures the steady state after the images have loaded).
window.plenopathFrameTimes.reset = () => { frameProbe.intervals = []; frameProbe.work = []; };
