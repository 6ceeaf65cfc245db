// Reading the report's data (docs/report.md, "The data"): the JSON object the program embeds
// in <script type="application/json" id="chasles-data">, with long arrays as base64 text of
// little-endian numbers.

export const FORMAT_MAJOR = 'chasles-report 2';

/** The bytes of a base64 string. */
export function bytesOf(base64) {
  const text = atob(base64);
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i);
  return bytes;
}

/** 64-bit floats ("f8"), exact. */
export function f8(base64) {
  return new Float64Array(bytesOf(base64).buffer);
}

/** 32-bit floats ("f4"). */
export function f4(base64) {
  return new Float32Array(bytesOf(base64).buffer);
}

/** 32-bit unsigned integers (mesh triangles). */
export function u4(base64) {
  return new Uint32Array(bytesOf(base64).buffer);
}

/** The embedded data, decoded: columns as typed arrays by name, a run's poses by body index. */
export function readData(doc) {
  const node = doc.getElementById('chasles-data');
  if (!node) throw new Error('this page has no chasles-data element');
  const data = JSON.parse(node.textContent);
  if (data.format !== FORMAT_MAJOR) {
    throw new Error(`report data of format '${data.format}', expected '${FORMAT_MAJOR}'`);
  }
  data.byName = new Map();
  for (const c of data.columns || []) {
    c.values = c.type === 'f8' ? f8(c.data) : f4(c.data);
    delete c.data;
    data.byName.set(c.name, c);
  }
  data.time = data.byName.has('t') ? data.byName.get('t').values : new Float64Array(0);
  if (data.kind === 'simulate') {
    // Every body's origin and quaternion at every sample, placed by the body's index in
    // data.bodies (not by any name).
    const poses = new Array(data.bodies.length).fill(null);
    for (const p of data.poses || []) {
      poses[p.body] = { body: p.body, origin: f8(p.origin), quaternion: f8(p.quaternion) };
    }
    data.poses = poses;
  }
  for (const r of data.reactions || []) r.values = f4(r.data);
  for (const c of data.contacts || []) c.values = f4(c.data);
  for (const f of data.forces || []) f.values = f4(f.data);
  for (const b of data.bodies) {
    for (const p of b.parts) {
      if (p.mesh) {
        p.mesh.positions = new Float32Array(bytesOf(p.mesh.vertices).buffer);
        p.mesh.indices = u4(p.mesh.triangles);
      }
    }
  }
  return data;
}

/** Every time to mark on the plots: user events, contact-mode changes, impacts, jumps. */
export function eventMarks(data) {
  const marks = [];
  for (const e of data.events || []) marks.push({ t: e.t, label: e.name, kind: 'event' });
  for (const e of data.contact_events || []) {
    if (e.reason === 'initial') continue;
    marks.push({ t: e.t, label: `${e.point}: ${e.from} → ${e.to}`, kind: 'contact' });
  }
  for (const e of data.impacts || []) marks.push({ t: e.t, label: `impact ${e.point}`, kind: 'impact' });
  for (const e of data.jumps || []) marks.push({ t: e.t, label: e.description, kind: 'jump' });
  marks.sort((a, b) => a.t - b.t);
  return marks;
}

/** Index of the last sample at or before t (the first sample before the run). */
export function sampleAt(time, t) {
  let lo = 0;
  let hi = time.length - 1;
  if (hi < 0 || t <= time[0]) return 0;
  if (t >= time[hi]) return hi;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (time[mid] <= t) lo = mid;
    else hi = mid;
  }
  return lo;
}
