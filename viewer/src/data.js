// The document `tumble view` embeds (crates/tumble-io/src/viewer/mod.rs): shapes once, then flat
// per-frame arrays. Helpers here read it; nothing here draws.

export const FORMAT = 'tumble-viewer-1';

export function readDocument() {
  const element = document.getElementById('tumble-data');
  if (!element) throw new Error('this page has no Tumble data');
  const doc = JSON.parse(element.textContent);
  if (doc.format !== FORMAT) {
    throw new Error(`this page's data is ${doc.format}; this viewer reads ${FORMAT}`);
  }
  return doc;
}

/** The frame shown at time `t`: the last frame at or before it. */
export function frameAt(doc, t) {
  const times = doc.t;
  let lo = 0;
  let hi = times.length - 1;
  if (t <= times[0]) return 0;
  if (t >= times[hi]) return hi;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (times[mid] <= t) lo = mid;
    else hi = mid;
  }
  return lo;
}

/** Body `i`'s pose at frame `f`: position [x, y, z] and quaternion [x, y, z, w]. */
export function poseOf(doc, f, i) {
  const p = doc.pose[f];
  const k = 7 * i;
  return { position: [p[k], p[k + 1], p[k + 2]], quaternion: [p[k + 3], p[k + 4], p[k + 5], p[k + 6]] };
}

/** Body `i`'s 3-vector from a per-body series (`omega`, `L`, `v`) at frame `f`. */
export function vectorOf(series, f, i) {
  const s = series[f];
  return [s[3 * i], s[3 * i + 1], s[3 * i + 2]];
}

/** Largest length of a per-body vector series over all frames and bodies (0 if none). */
export function maxLength(series) {
  let max = 0;
  for (const frame of series) {
    for (let k = 0; k + 2 < frame.length; k += 3) {
      max = Math.max(max, Math.hypot(frame[k], frame[k + 1], frame[k + 2]));
    }
  }
  return max;
}
