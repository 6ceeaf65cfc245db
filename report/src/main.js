// The chasles browser report (docs/report.md): a 3-D replay of a run with plots synchronised
// to it, or the configuration of a mass report or a solve. Reads the data the program embedded
// in the page and exposes a small read-only API for tests as window.chasles.
import { readData, eventMarks, sampleAt } from './data.js';
import { View, makeBody, partSize, quat, ForceArrow, FORCE_COLORS, THREE } from './scene3d.js';
import { Plot, MODE_COLORS, MODE_NAMES } from './plots.js';
import { sweepPlots } from './sweep.js';
import { modesReport } from './modes.js';

const api = {
  ready: false,
  errors: [],
  time: 0,
  seek: () => {},
  bodyPose: () => null,
  plots: () => [],
  arrows: () => [],
};
window.chasles = api;
window.addEventListener('error', (e) => api.errors.push(String(e.message || e)));

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

function fmt(x, digits = 6) {
  return Number.isFinite(x) ? Number(x.toPrecision(digits)).toString() : String(x);
}

function vec(v, digits = 6) {
  return `[${v.map((x) => fmt(x, digits)).join(', ')}]`;
}

/** The layout: header, the 3-D view and its controls, the side panel. */
function layout(data) {
  const kinds = { simulate: 'simulation', mass: 'mass properties', solve: 'instantaneous solve', sweep: 'sweep', modes: 'modes' };
  const header = el(
    'header',
    {},
    el('h1', {}, data.title || data.scene || 'chasles report'),
    el('span', { class: 'sub' }, `${kinds[data.kind] || data.kind} · ${data.scene} · SI units${data.planar ? ' · planar' : ''}`),
  );
  const view = el('div', { id: 'view' });
  const controls = el('div', { id: 'controls' });
  const legend = el('div', { id: 'legend' });
  const left = el('section', { id: 'left' }, view, controls, legend);
  const side = el('section', { id: 'side' });
  const main = el('main', {}, left, side);
  document.body.append(header, main);
  return { view, controls, legend, side };
}

/**
 * Body k's pose at every sample from the data's poses (by the body's index, whatever the
 * columns are called): [ox, oy, oz, qw, qx, qy, qz] arrays.
 */
function posesOf(data, k) {
  const p = data.poses[k];
  const n = data.time.length;
  if (!p) throw new Error(`the data has no poses for body ${k} ('${data.bodies[k].name}')`);
  if (p.origin.length !== 3 * n || p.quaternion.length !== 4 * n) {
    throw new Error(`the poses of body ${k} ('${data.bodies[k].name}') are not ${n} samples long`);
  }
  const component = (values, stride, c) => {
    const out = new Float64Array(n);
    for (let i = 0; i < n; i++) out[i] = values[stride * i + c];
    return out;
  };
  return [
    ...[0, 1, 2].map((c) => component(p.origin, 3, c)),
    ...[0, 1, 2, 3].map((c) => component(p.quaternion, 4, c)),
  ];
}

/**
 * Centre and size of everything drawn over the run, for the camera and the arrows' scale: the
 * bodies' bounding boxes at up to 200 of the poses ([ox, oy, oz, qw, qx, qy, qz] arrays per
 * body; none: at the body frame's origin).
 */
function extent(data, poses) {
  let body = 1e-3;
  for (const b of data.bodies) for (const p of b.parts) body = Math.max(body, partSize(p));
  const box = new THREE.Box3();
  data.bodies.forEach((b, k) => {
    const g = makeBody(b, k, body);
    const P = poses[k];
    const n = P ? P[0].length : 1;
    const step = Math.max(1, Math.floor(n / 200));
    for (let i = 0; i < n; i += Math.min(step, Math.max(n - 1 - i, 1))) {
      if (P) {
        g.position.set(P[0][i], P[1][i], P[2][i]);
        g.quaternion.set(P[4][i], P[5][i], P[6][i], P[3][i]);
      }
      g.updateMatrixWorld(true);
      box.expandByObject(g);
    }
  });
  const center = box.getCenter(new THREE.Vector3());
  const size = Math.max(0.6 * box.getSize(new THREE.Vector3()).length(), 1e-3);
  return { center: center.toArray(), size, body, floor: box.min.z };
}

function addPlanes(view, data, size, center) {
  for (const p of data.planes || []) {
    // Centred at the foot of the view's centre on the plane.
    const n = new THREE.Vector3(...p.normal).normalize();
    const c = new THREE.Vector3(...center);
    const d = c.clone().sub(new THREE.Vector3(...p.point)).dot(n);
    view.addPlane(c.sub(n.multiplyScalar(d)).toArray(), p.normal, 3 * size);
  }
}

function legendItem(color, text) {
  const swatch = el('span', { class: 'swatch' });
  swatch.style.background = `#${color.toString(16).padStart(6, '0')}`;
  return el('span', { class: 'legend-item' }, swatch, text);
}

/** A table of name/value rows. */
function table(rows) {
  const t = el('table');
  for (const [k, v] of rows) t.append(el('tr', {}, el('th', {}, k), el('td', {}, v)));
  return t;
}

function bodyTable(b) {
  return table([
    ['mass', `${fmt(b.mass, 9)} kg`],
    ['centre of mass (B)', `${vec(b.center_of_mass, 9)} m`],
    ['principal moments', `${vec(b.principal_moments, 9)} kg·m²`],
    ['principal axes (B)', b.principal_axes.map((a) => vec(a, 4)).join(' ')],
  ]);
}

/** The replay of a run. */
function simulateReport(data, parts) {
  const poses = data.bodies.map((b, k) => posesOf(data, k));
  const { center, size, body, floor } = extent(data, poses);
  const view = new View(parts.view, { planar: data.planar, center, size, floor });
  addPlanes(view, data, size, center);
  const groups = data.bodies.map((b, i) => {
    const g = makeBody(b, i, body);
    view.scene.add(g);
    return g;
  });
  const n = data.time.length;
  // Trails of the centres of mass: Bcm = Bo + R_WB p_BoBcm_B at every sample.
  const trails = data.bodies.map((b, k) => {
    const P = poses[k];
    const pos = new Float32Array(3 * n);
    const q = new THREE.Quaternion();
    const v = new THREE.Vector3();
    for (let i = 0; i < n; i++) {
      q.set(P[4][i], P[5][i], P[6][i], P[3][i]);
      v.fromArray(b.center_of_mass).applyQuaternion(q);
      pos[3 * i] = P[0][i] + v.x;
      pos[3 * i + 1] = P[1][i] + v.y;
      pos[3 * i + 2] = P[2][i] + v.z;
    }
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    const line = new THREE.Line(g, new THREE.LineBasicMaterial({ color: 0x333333, transparent: true, opacity: 0.6 }));
    view.scene.add(line);
    return line;
  });
  // Force arrows: the largest force of the run is drawn 0.6 of the scene's size long.
  let fmax = 0;
  for (const r of data.reactions) {
    for (let i = 0; i < n; i++) fmax = Math.max(fmax, Math.hypot(r.values[6 * i + 3], r.values[6 * i + 4], r.values[6 * i + 5]));
  }
  for (const c of data.contacts) {
    for (let i = 0; i < n; i++) {
      const o = 9 * i;
      fmax = Math.max(fmax, Math.hypot(c.values[o + 3], c.values[o + 4], c.values[o + 5]));
      fmax = Math.max(fmax, Math.hypot(c.values[o + 6], c.values[o + 7], c.values[o + 8]));
    }
  }
  const applied = data.forces || [];
  for (const f of applied) {
    for (let i = 0; i < n; i++) fmax = Math.max(fmax, Math.hypot(f.values[6 * i + 3], f.values[6 * i + 4], f.values[6 * i + 5]));
  }
  const forceScale = fmax > 0 ? (0.6 * size) / fmax : 0;
  const appliedArrows = applied.map(() => new ForceArrow(FORCE_COLORS.applied, view.scene, size));
  const reactionArrows = data.reactions.map(() => new ForceArrow(FORCE_COLORS.reaction, view.scene, size));
  const contactArrows = data.contacts.map(() => ({
    normal: new ForceArrow(FORCE_COLORS.normal, view.scene, size),
    friction: new ForceArrow(FORCE_COLORS.friction, view.scene, size),
    dot: (() => {
      const m = new THREE.Mesh(new THREE.SphereGeometry(0.02 * body, 10, 8), new THREE.MeshBasicMaterial({ color: 0x000000 }));
      view.scene.add(m);
      return m;
    })(),
  }));

  // Legend.
  if (applied.length) parts.legend.append(legendItem(FORCE_COLORS.applied, 'applied force (gravity, forces, springs, dampers, drag, cables)'));
  if (data.reactions.length) parts.legend.append(legendItem(FORCE_COLORS.reaction, 'reaction on the child (at the joint point)'));
  if (data.contacts.length) {
    parts.legend.append(legendItem(FORCE_COLORS.normal, 'contact normal force'), legendItem(FORCE_COLORS.friction, 'friction force'));
  }
  parts.legend.append(
    el('span', { class: 'legend-item' }, fmax > 0 ? `arrows: ${fmt(0.6 * size, 3)} m = ${fmt(fmax, 3)} N` : 'no forces to draw'),
    el('span', { class: 'legend-item' }, 'axes: x red, y green, z blue'),
  );

  // State at a time: poses interpolated between samples (exact at a sample's time), forces at
  // the sample at or before it.
  let current = 0;
  let shownTime = n ? data.time[0] : 0;
  const poseAt = (k, t) => {
    const P = poses[k];
    const i = sampleAt(data.time, t);
    const j = Math.min(i + 1, n - 1);
    const dt = data.time[j] - data.time[i];
    const a = j > i && dt > 0 && t > data.time[i] ? Math.min((t - data.time[i]) / dt, 1) : 0;
    const position = [0, 1, 2].map((c) => P[c][i]);
    const quaternion = [3, 4, 5, 6].map((c) => P[c][i]);
    if (a === 0) return { position, quaternion };
    const q0 = quat(quaternion);
    const q1 = quat([3, 4, 5, 6].map((c) => P[c][j]));
    q0.slerp(q1, a);
    return {
      position: [0, 1, 2].map((c) => P[c][i] + a * (P[c][j] - P[c][i])),
      quaternion: [q0.w, q0.x, q0.y, q0.z],
    };
  };
  const showArrows = { on: true };
  const update = (t) => {
    shownTime = t;
    current = sampleAt(data.time, t);
    groups.forEach((g, k) => {
      const p = poseAt(k, t);
      g.position.fromArray(p.position);
      g.quaternion.copy(quat(p.quaternion));
    });
    trails.forEach((line) => line.geometry.setDrawRange(0, current + 1));
    applied.forEach((f, k) => {
      const o = 6 * current;
      const v = f.values;
      if (showArrows.on) appliedArrows[k].set([v[o], v[o + 1], v[o + 2]], [v[o + 3], v[o + 4], v[o + 5]], forceScale);
      else appliedArrows[k].arrow.visible = false;
    });
    data.reactions.forEach((r, k) => {
      const o = 6 * current;
      const v = r.values;
      if (showArrows.on) reactionArrows[k].set([v[o], v[o + 1], v[o + 2]], [v[o + 3], v[o + 4], v[o + 5]], forceScale);
      else reactionArrows[k].arrow.visible = false;
    });
    data.contacts.forEach((c, k) => {
      const o = 9 * current;
      const v = c.values;
      const touching = c.modes[current] !== '0';
      const a = contactArrows[k];
      a.dot.visible = touching;
      a.dot.position.set(v[o], v[o + 1], v[o + 2]);
      if (touching && showArrows.on) {
        a.normal.set([v[o], v[o + 1], v[o + 2]], [v[o + 3], v[o + 4], v[o + 5]], forceScale);
        a.friction.set([v[o], v[o + 1], v[o + 2]], [v[o + 6], v[o + 7], v[o + 8]], forceScale);
      } else {
        a.normal.arrow.visible = false;
        a.friction.arrow.visible = false;
      }
    });
    view.render();
    for (const p of plots) p.setTime(t);
    slider.value = String(current);
    clock.textContent = `t = ${fmt(t, 6)} s (sample ${current + 1} of ${n})`;
  };

  // Controls: play / pause, scrub, speed.
  const play = el('button', { type: 'button', id: 'play' }, 'Play');
  const slider = el('input', { type: 'range', id: 'scrub', min: '0', max: String(Math.max(n - 1, 0)), value: '0', step: '1' });
  const speed = el('select', { id: 'speed' });
  for (const s of [0.1, 0.25, 0.5, 1, 2, 5, 10]) {
    const o = el('option', { value: String(s) }, `${s}×`);
    if (s === 1) o.selected = true;
    speed.append(o);
  }
  const arrows = el('input', { type: 'checkbox', id: 'arrows', checked: '' });
  const clock = el('span', { id: 'clock' });
  parts.controls.append(play, slider, el('label', {}, 'speed ', speed), el('label', {}, arrows, ' forces'), clock);
  let playing = false;
  let last = 0;
  const t0 = n ? data.time[0] : 0;
  const t1 = n ? data.time[n - 1] : 0;
  const tick = (now) => {
    if (!playing) return;
    const dt = ((now - last) / 1000) * Number(speed.value);
    last = now;
    let t = shownTime + dt;
    if (t >= t1) {
      t = t1;
      playing = false;
      play.textContent = 'Play';
    }
    update(t);
    if (playing) requestAnimationFrame(tick);
  };
  play.addEventListener('click', () => {
    playing = !playing;
    play.textContent = playing ? 'Pause' : 'Play';
    if (playing) {
      if (shownTime >= t1) update(t0);
      last = performance.now();
      requestAnimationFrame(tick);
    }
  });
  slider.addEventListener('input', () => update(data.time[Number(slider.value)]));
  arrows.addEventListener('change', () => {
    showArrows.on = arrows.checked;
    update(shownTime);
  });

  // Plots.
  const marks = eventMarks(data);
  const plots = [];
  const side = parts.side;
  const cols = data.columns.filter((c) => c.name !== 't');
  const named = (pred) => cols.filter(pred).map((c) => c.name);
  const picker = el('select', { id: 'column-picker' });
  for (const c of cols) picker.append(el('option', { value: c.name }, c.unit ? `${c.name} [${c.unit}]` : c.name));
  const addButton = el('button', { type: 'button', id: 'add-plot' }, 'Plot');
  side.append(el('div', { class: 'picker' }, el('label', {}, 'column ', picker), addButton));
  const plotArea = el('div', { id: 'plots' });
  side.append(plotArea);
  const addPlot = (title, names, bands) => {
    if (!names.length) return null;
    const p = new Plot(plotArea, data, title, names, marks, bands);
    p.setTime(shownTime);
    plots.push(p);
    return p;
  };
  addButton.addEventListener('click', () => addPlot(picker.value, [picker.value]));
  // The energy ledger: kinetic, potential, work of each force, dissipated, residual.
  addPlot(
    'Energy ledger [J]',
    named((c) => ['energy', 'work', 'residual'].includes(c.group) && !['T_trans', 'T_rot'].includes(c.name)),
  );
  // Reactions in W (on the child at the joint point).
  addPlot(
    'Reactions (on the child, world frame)',
    named((c) => c.group === 'reactions' && !c.name.endsWith('_B') && /_F[xyz]$/.test(c.name)),
  );
  // Contacts: N and |f| of each point, its regime as bands.
  if (data.contacts.length) {
    addPlot(
      'Contacts: normal force N and friction |f|',
      named((c) => c.group === 'contacts' && /_(N|f)$/.test(c.name)),
      data.contacts.map((c) => ({ name: c.name, modes: c.modes })),
    );
    const key = el('div', { class: 'legend-row' }, 'regime bands: ');
    MODE_NAMES.forEach((m, i) => {
      const s = el('span', { class: 'swatch' });
      s.style.background = MODE_COLORS[i];
      key.append(el('span', { class: 'legend-item' }, s, m));
    });
    side.append(key);
  }
  // The first body's motion: the first of these groups the run has.
  const b0 = data.bodies[0].name;
  const groups3 = data.planar
    ? [['planar', ['x', 'y', 'theta']]]
    : [];
  groups3.push(
    ['angular velocity (body frame)', ['wbx', 'wby', 'wbz']],
    ['angular velocity', ['wx', 'wy', 'wz']],
    ['centre of mass', ['x', 'y', 'z']],
    ['origin', ['ox', 'oy', 'oz']],
  );
  for (const [what, suffixes] of groups3) {
    const names = suffixes.map((s) => `${b0}_${s}`).filter((m) => data.byName.has(m));
    if (names.length) {
      addPlot(`${b0}: ${what}`, names);
      break;
    }
  }
  if (marks.length) {
    const list = el('ul', { class: 'events' });
    for (const m of marks.slice(0, 200)) list.append(el('li', {}, `t = ${fmt(m.t, 9)} s: ${m.label}`));
    side.append(el('h2', {}, 'Events'), list);
  }
  window.addEventListener('resize', () => plots.forEach((p) => p.resize(plotArea.clientWidth)));

  api.seek = (t) => update(Number(t));
  api.bodyPose = (name) => {
    const k = data.bodies.findIndex((b) => b.name === name);
    if (k < 0) return null;
    return poseAt(k, shownTime);
  };
  api.plots = () => plots.map((p) => p.describe());
  // The arrows drawn at the time shown: kind, name, the point and the force (N, unscaled).
  api.arrows = () => {
    const out = [];
    const add = (kind, name, a) => {
      if (a.arrow.visible && a.shown) out.push({ kind, name, origin: a.shown.origin, force: a.shown.force });
    };
    applied.forEach((f, k) => add('applied', `${f.element} on ${f.body}`, appliedArrows[k]));
    data.reactions.forEach((r, k) => add('reaction', r.name, reactionArrows[k]));
    data.contacts.forEach((c, k) => {
      add('normal', c.name, contactArrows[k].normal);
      add('friction', c.name, contactArrows[k].friction);
    });
    return out;
  };
  Object.defineProperty(api, 'time', { get: () => shownTime, configurable: true });
  update(t0);
}

/**
 * chasles audit: the uniform ellipsoid of a link's geometry at the given mass (orange wire),
 * beside the violet one of the given inertial, and a note saying which geometry it is.
 */
function computedEllipsoid(c, side) {
  const e = c.ellipsoid;
  const ell = new THREE.Mesh(
    new THREE.SphereGeometry(1, 32, 16).scale(...e.semi_axes.map((x) => Math.max(x, 1e-9))),
    new THREE.MeshBasicMaterial({ color: 0xe07b00, wireframe: true, transparent: true, opacity: 0.6 }),
  );
  ell.name = 'computed';
  ell.position.fromArray(e.center);
  ell.quaternion.copy(quat(e.quaternion));
  side.append(el('p', { class: 'note' },
    `The orange wire ellipsoid is the ${c.source} geometry's (${c.method}) at the given mass, centre ${vec(e.center, 4)} m, semi-axes ${vec(e.semi_axes, 4)} m; the violet one is the given inertial's.`));
  return ell;
}

/** chasles audit: per file its counts, and per link its findings (errors first, as found). */
function auditPanel(audit, side) {
  for (const f of audit) {
    side.append(el('h2', {}, `${f.path} (${f.format}, robot '${f.robot}')`),
      el('p', {}, `${f.errors} errors, ${f.warnings} warnings, ${f.notes} notes`));
    for (const l of f.links) {
      if (!l.findings.length) continue;
      side.append(el('h3', {}, `link '${l.name}' (line ${l.line})${l.body === null ? ': not drawn, no valid given inertial' : ''}`));
      for (const x of l.findings) {
        side.append(el('p', { class: `finding ${x.severity}` }, `${x.severity} ${x.code} (line ${x.line}): ${x.message}`));
      }
    }
  }
}

/** The body (or bodies) with principal axes and the equivalent inertia ellipsoid. */
function massReport(data, parts) {
  if (data.audit) auditPanel(data.audit, parts.side);
  const { center, size, body, floor } = extent(data, []);
  const view = new View(parts.view, { planar: false, center, size, floor });
  data.bodies.forEach((b, i) => {
    const g = makeBody(b, i, body);
    view.scene.add(g);
    // Principal axes through the centre of mass, and Legendre's ellipsoid: the uniform solid
    // ellipsoid of the same mass and central inertia, semi-axes
    //   a_i² = 5 (I_j + I_k − I_i) / (2 m)   (from I_i = m (a_j² + a_k²) / 5).
    const semi = b.ellipsoid;
    const R = new THREE.Matrix4();
    const e = b.principal_axes.map((a) => new THREE.Vector3(...a));
    R.makeBasis(e[0], e[1], e[2]);
    const frame = new THREE.Group();
    frame.position.fromArray(b.center_of_mass);
    frame.quaternion.setFromRotationMatrix(R);
    const ell = new THREE.Mesh(
      new THREE.SphereGeometry(1, 48, 24).scale(Math.max(semi[0], 1e-9), Math.max(semi[1], 1e-9), Math.max(semi[2], 1e-9)),
      new THREE.MeshStandardMaterial({ color: 0x8e44ad, transparent: true, opacity: 0.25, depthWrite: false }),
    );
    frame.add(ell);
    const colors = [0xd62728, 0x2ca02c, 0x1f77b4];
    e.forEach((_, k) => {
      const L = Math.max(1.3 * semi[k], 0.4 * body);
      const dir = new THREE.Vector3(k === 0 ? 1 : 0, k === 1 ? 1 : 0, k === 2 ? 1 : 0);
      frame.add(new THREE.ArrowHelper(dir, new THREE.Vector3(), L, colors[k]));
      frame.add(new THREE.ArrowHelper(dir.clone().negate(), new THREE.Vector3(), L, colors[k], 0));
    });
    g.add(frame);
    parts.side.append(el('h2', {}, b.name), bodyTable(b), el('p', { class: 'note' },
      `Principal axes e1, e2, e3 (red, green, blue) through the centre of mass; the violet ellipsoid is the uniform ellipsoid of the same mass and central inertia, semi-axes ${vec(semi, 4)} m.`));
    if (b.computed) g.add(computedEllipsoid(b.computed, parts.side));
  });
  parts.legend.append(el('span', { class: 'legend-item' }, 'body axes at the body origin: x red, y green, z blue'));
  view.render();
  api.bodyPose = (name) => (data.bodies.some((b) => b.name === name) ? { position: [0, 0, 0], quaternion: [1, 0, 0, 0] } : null);
  api.seek = () => view.render();
}

/** The configuration of a solve with the forces of the solved instant. */
function solveReport(data, parts) {
  const poses = data.poses.map((p) => [...p.origin, ...p.quaternion].map((x) => [x]));
  const { center, size, body, floor } = extent(data, poses);
  const view = new View(parts.view, { planar: data.planar, center, size, floor });
  addPlanes(view, data, size, center);
  data.bodies.forEach((b, i) => {
    const g = makeBody(b, i, body);
    const p = data.poses[i];
    if (p) {
      g.position.fromArray(p.origin);
      g.quaternion.copy(quat(p.quaternion));
    }
    view.scene.add(g);
  });
  let fmax = 0;
  for (const r of data.solve_reactions) fmax = Math.max(fmax, Math.hypot(...r.force));
  for (const c of data.solve_contacts) fmax = Math.max(fmax, Math.hypot(...c.normal_force), Math.hypot(...c.friction_force));
  const scale = fmax > 0 ? (0.6 * size) / fmax : 0;
  const rows = [];
  for (const r of data.solve_reactions) {
    new ForceArrow(FORCE_COLORS.reaction, view.scene, size).set(r.point, r.force, scale);
    rows.push([`${r.name} (${r.kind})`, `F ${vec(r.force)} N at ${vec(r.point)} m`]);
  }
  for (const c of data.solve_contacts) {
    new ForceArrow(FORCE_COLORS.normal, view.scene, size).set(c.position, c.normal_force, scale);
    new ForceArrow(FORCE_COLORS.friction, view.scene, size).set(c.position, c.friction_force, scale);
    rows.push([`${c.name} (${c.regime})`, `N ${vec(c.normal_force)} N, f ${vec(c.friction_force)} N`]);
  }
  for (const a of data.accelerations) rows.push([`${a.name}`, `a ${vec(a.acceleration)} m/s², α ${vec(a.angular_acceleration)} rad/s²`]);
  parts.side.append(el('h2', {}, 'Forces and accelerations'), table(rows));
  parts.legend.append(
    legendItem(FORCE_COLORS.reaction, 'reaction on the child'),
    legendItem(FORCE_COLORS.normal, 'contact normal force'),
    legendItem(FORCE_COLORS.friction, 'friction force'),
    el('span', { class: 'legend-item' }, fmax > 0 ? `arrows: ${fmt(0.6 * size, 3)} m = ${fmt(fmax, 3)} N` : 'no forces'),
  );
  view.render();
  api.bodyPose = (name) => {
    const p = data.poses.find((x) => x.name === name);
    return p ? { position: p.origin.slice(), quaternion: p.quaternion.slice() } : null;
  };
  api.seek = () => view.render();
}

/** A sweep: the scene at its own parameter values, and each quantity against the parameters. */
function sweepReport(data, parts) {
  const poses = (data.poses || []).map((p) => [...p.origin, ...p.quaternion].map((x) => [x]));
  const { center, size, body, floor } = extent(data, poses);
  const view = new View(parts.view, { planar: data.planar, center, size, floor });
  addPlanes(view, data, size, center);
  data.bodies.forEach((b, i) => {
    const g = makeBody(b, i, body);
    const p = (data.poses || [])[i];
    if (p) {
      g.position.fromArray(p.origin);
      g.quaternion.copy(quat(p.quaternion));
    }
    view.scene.add(g);
  });
  const swept = new Set(data.sweep.parameters && data.sweep.parameters.length ? data.sweep.parameters : [data.sweep.columns[0]]);
  const own = Object.entries(data.parameter_values || {})
    .filter(([k]) => swept.has(k))
    .map(([k, v]) => `${k} = ${fmt(v, 9)}`);
  parts.legend.append(
    el('span', { class: 'legend-item' }, `drawn at the scene's own values${own.length ? ` (${own.join(', ')}, SI)` : ''}`),
    el('span', { class: 'legend-item' }, 'axes: x red, y green, z blue'),
  );
  view.render();
  const plots = sweepPlots(data, parts.side, el);
  api.plots = () => plots.map((p) => p.describe());
  api.bodyPose = (name) => {
    const k = data.bodies.findIndex((b) => b.name === name);
    if (k < 0) return null;
    const p = (data.poses || [])[k];
    return p ? { position: p.origin.slice(), quaternion: p.quaternion.slice() } : { position: [0, 0, 0], quaternion: [1, 0, 0, 0] };
  };
  api.seek = () => view.render();
}

function start() {
  try {
    const data = readData(document);
    api.data = data;
    const parts = layout(data);
    if (data.kind === 'simulate') simulateReport(data, parts);
    else if (data.kind === 'mass') massReport(data, parts);
    else if (data.kind === 'solve') solveReport(data, parts);
    else if (data.kind === 'sweep') sweepReport(data, parts);
    else if (data.kind === 'modes') modesReport(data, parts, api, { el, fmt, table, extent, addPlanes });
    else throw new Error(`unknown report kind '${data.kind}'`);
    api.ready = true;
  } catch (e) {
    api.errors.push(String(e && e.stack ? e.stack : e));
    console.error(e);
    document.body.append(el('pre', { class: 'error' }, `chasles report: ${e}`));
  }
}

if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start);
else start();
