// The report of `chasles modes --html` (docs/report.md, "Modes"): the bodies at the operating
// point, and the motion of the mode chosen in the selector, x(t) = x0 + ε Re(shape e^{λt}),
// drawn through each body's displacement and rotation as the program computed them (the data's
// modes[].bodies: ε times the complex δp and δθ of the body per unit of the shape).
import { makeBody, quat, View, THREE } from './scene3d.js';

/** Wall-clock seconds one loop of a mode takes at speed 1×. */
const LOOP_SECONDS = 4;

/** Re(D e^{λt}) for D = re + i im (3-vectors): e^{σt} (re cos ωt − im sin ωt). */
function motionAt(d, lambda, t) {
  const [sigma, omega] = lambda;
  const g = Math.exp(sigma * t);
  const c = Math.cos(omega * t);
  const s = Math.sin(omega * t);
  return [0, 1, 2].map((i) => g * (d.re[i] * c - d.im[i] * s));
}

/**
 * The pose of body `body` (its data entry) at the operating point `base` moved by the mode at
 * time t: Bcm = Bcm0 + δp, R = exp(δθ) R0 (δθ about W's axes, as the linearisation perturbs),
 * and the frame origin Bo = Bcm − R p_BoBcm_B. No mode, or a body it does not move: `base`.
 */
function modePose(body, base, mode, t) {
  const m = mode && mode.animated ? mode.bodies.find((b) => b.name === body.name) : null;
  if (!m) return { position: base.origin.slice(), quaternion: base.quaternion.slice() };
  const dp = motionAt(m.dp, mode.eigenvalue, t);
  const dtheta = new THREE.Vector3(...motionAt(m.dtheta, mode.eigenvalue, t));
  const angle = dtheta.length();
  const turn = new THREE.Quaternion();
  if (angle > 0) turn.setFromAxisAngle(dtheta.clone().divideScalar(angle), angle);
  const q = turn.multiply(quat(base.quaternion));
  const com = base.center_of_mass.map((x, i) => x + dp[i]);
  const offset = new THREE.Vector3(...body.center_of_mass).applyQuaternion(q);
  return { position: [com[0] - offset.x, com[1] - offset.y, com[2] - offset.z], quaternion: [q.w, q.x, q.y, q.z] };
}

/** The selector's text of a mode: frequency and damping, or the rate, and the verdict. */
function modeLabel(mode, k, fmt) {
  if (mode.rigid) return `${k + 1}: rigid, frees ${mode.frees} (not animated)`;
  const [re, im] = mode.eigenvalue;
  let what;
  if (im > 0 && mode.neutral) {
    what = `${fmt(mode.frequency_hz, 6)} Hz, undamped`;
  } else if (im > 0) {
    what = `${fmt(mode.frequency_hz, 6)} Hz, damping ratio ${fmt(mode.damping_ratio, 3)}`;
    if (!mode.stable) what += `, grows at ${fmt(mode.growth_rate, 6)} 1/s`;
  } else {
    what = mode.stable ? `decays at ${fmt(-re, 6)} 1/s` : `grows at ${fmt(mode.growth_rate, 6)} 1/s`;
  }
  return `${k + 1}: ${what}: ${mode.stable ? 'stable' : 'UNSTABLE'}${mode.animated ? '' : ' (moves no body; not animated)'}`;
}

/** What the loop shows, in words. */
function loopText(mode, fmt) {
  const [t0, t1] = mode.loop;
  const span = `t = ${fmt(t0, 4)} s to ${fmt(t1, 4)} s`;
  const periods = `${fmt(mode.periods, 3)} period${mode.periods === 1 ? '' : 's'}`;
  switch (mode.shown) {
    case 'oscillation':
      return `one period (${span}) at constant amplitude, looped`;
    case 'decaying oscillation':
      return `${periods} (${span}), the amplitude decaying from its full size${mode.periods < 1 ? ' to 1/10' : ''}, looped`;
    case 'growing oscillation':
      return `${periods} (${span}), the amplitude growing${mode.periods < 1 ? ' tenfold' : ''} to its full size at t = 0, looped`;
    case 'decay':
      return `the excursion decaying to 1/10 (${span}), looped`;
    case 'growth':
      return `the excursion growing tenfold to its full size at t = 0 (${span}), looped`;
    default:
      return `a constant displacement (λ = 0)`;
  }
}

/** The side panel of a mode: its numbers, the amplitude scale and the shape over the coordinates. */
function modePanel(data, mode, k, h) {
  const { el, fmt, table } = h;
  const names = [...data.coordinates, ...data.speeds];
  // A neutral mode's Re λ and damping ratio are round-off: shown as 0, as in the text report.
  const [re, im] = [mode.neutral ? 0 : mode.eigenvalue[0], mode.eigenvalue[1]];
  const rows = [
    ['eigenvalue λ', `${fmt(re, 12)} ${im < 0 ? '−' : '+'} ${fmt(Math.abs(im), 12)}i 1/s`],
    ['frequency', `${fmt(mode.frequency_hz, 9)} Hz`],
    ['damping ratio', mode.neutral ? '0 (undamped)' : fmt(mode.damping_ratio, 6)],
    ['growth rate', `${fmt(mode.growth_rate, 9)} 1/s`],
    ['verdict', mode.rigid ? `rigid: frees ${mode.frees}` : mode.stable ? 'stable' : 'UNSTABLE'],
  ];
  const out = [el('h2', {}, `Mode ${k + 1}`), table(rows)];
  if (!mode.animated) {
    out.push(el('p', { class: 'note' }, mode.rigid
      ? 'A rigid mode (a zero eigenvalue a symmetry leaves): listed, not animated.'
      : 'This mode moves no body\'s position or attitude: not animated.'));
    return out;
  }
  const ref = names[mode.reference];
  const frac = 100 * data.amplitude.fraction;
  out.push(el('p', { class: 'note', id: 'amplitude' },
    `Shown: ${loopText(mode, fmt)}. Amplitude scale ε = ${fmt(mode.scale, 4)} ${ref.unit} of ${ref.name} ` +
    `(the shape's unit entry): the largest excursion of a body, |δp| + ρ|δθ| with ρ its mass's ` +
    `root-mean-square distance from its centre of mass, is ${fmt(frac, 3)} % of the scene's size ` +
    `(${fmt(data.amplitude.scene_size, 4)} m). Each loop plays in ${LOOP_SECONDS} s at 1×.`));
  const shape = [];
  mode.shape.forEach(([a, b], i) => {
    const mag = Math.hypot(a, b);
    if (mag < 1e-9) return;
    shape.push([`${names[i].name} [${names[i].unit}]`, `${fmt(mode.scale * mag, 6)} at ${fmt((Math.atan2(b, a) * 180) / Math.PI, 4)}°`]);
  });
  out.push(el('h3', {}, 'Shape × ε (amplitude and phase)'), table(shape));
  return out;
}

/**
 * The poses to frame the camera on: per body [ox, oy, oz, qw, qx, qy, qz] arrays over the
 * operating point and 24 instants of every animated mode's loop, so the view stays put when
 * another mode is chosen.
 */
function framingPoses(data, bases) {
  return data.bodies.map((b, k) => {
    const cols = [[], [], [], [], [], [], []];
    const push = (p) => [...p.position, ...p.quaternion].forEach((x, c) => cols[c].push(x));
    push(modePose(b, bases[k], null, 0));
    for (const m of data.modes) {
      if (!m.animated) continue;
      for (let i = 0; i < 24; i++) push(modePose(b, bases[k], m, m.loop[0] + ((m.loop[1] - m.loop[0]) * i) / 23));
    }
    return cols;
  });
}

/** The modes report: the view, the selector, play / pause, the scrubber and the side panel. */
export function modesReport(data, parts, api, h) {
  const { el, fmt, extent, addPlanes } = h;
  const bases = data.bodies.map((b) => data.poses.find((p) => p.name === b.name));
  if (bases.some((p) => !p)) throw new Error('the data has no operating-point pose for every body');
  const { center, size, body, floor } = extent(data, framingPoses(data, bases));
  const view = new View(parts.view, { planar: data.planar, center, size, floor });
  addPlanes(view, data, size, center);
  const groups = data.bodies.map((b, i) => {
    const g = makeBody(b, i, body);
    view.scene.add(g);
    return g;
  });

  const select = el('select', { id: 'mode' });
  data.modes.forEach((m, k) => {
    const o = el('option', { value: String(k) }, modeLabel(m, k, fmt));
    if (!m.animated) o.disabled = true;
    select.append(o);
  });
  const play = el('button', { type: 'button', id: 'play' }, 'Pause');
  const slider = el('input', { type: 'range', id: 'scrub', min: '0', max: '1000', value: '0', step: '1' });
  const speed = el('select', { id: 'speed' });
  for (const s of [0.1, 0.25, 0.5, 1, 2, 5]) {
    const o = el('option', { value: String(s) }, `${s}×`);
    if (s === 1) o.selected = true;
    speed.append(o);
  }
  const clock = el('span', { id: 'clock' });
  parts.controls.append(el('label', {}, 'mode ', select), play, slider, el('label', {}, 'speed ', speed), clock);
  const panel = el('div', { id: 'mode-panel' });
  const op = data.operating_point;
  parts.side.append(
    el('h2', {}, 'Operating point'),
    h.table([
      ['kind', op.kind === 'equilibrium' ? 'static equilibrium' : 'steady motion'],
      ['residual', fmt(op.residual, 3)],
      ['coordinates', data.coordinates.map((c) => `${c.name} [${c.unit}]`).join(', ')],
      ['speeds', data.speeds.map((c) => `${c.name} [${c.unit}]`).join(', ')],
      ['verdict', data.stable ? 'stable (no mode grows)' : 'UNSTABLE'],
    ]),
    panel,
  );
  parts.legend.append(
    el('span', { class: 'legend-item' }, 'x(t) = x0 + ε Re(shape e^{λt}), drawn through each body\'s δp and δθ'),
    el('span', { class: 'legend-item' }, 'axes: x red, y green, z blue'),
  );
  if (op.kind !== 'equilibrium') {
    parts.legend.append(el('span', { class: 'legend-item' },
      'steady motion: the modes are drawn in the frame that moves with it (its turn and spins are not drawn)'));
  }

  let current = data.modes.findIndex((m) => m.animated);
  let shown = 0;
  const mode = () => (current >= 0 ? data.modes[current] : null);
  const loop = () => (mode() ? mode().loop : [0, 0]);
  const update = (t) => {
    const [t0, t1] = loop();
    shown = Math.min(Math.max(t, t0), t1);
    groups.forEach((g, k) => {
      const p = modePose(data.bodies[k], bases[k], mode(), shown);
      g.position.fromArray(p.position);
      g.quaternion.copy(quat(p.quaternion));
    });
    view.render();
    slider.value = String(t1 > t0 ? Math.round((1000 * (shown - t0)) / (t1 - t0)) : 0);
    clock.textContent = mode() ? `t = ${fmt(shown, 4)} s of the mode's motion` : 'no mode to animate';
  };
  const choose = (k) => {
    current = k;
    select.value = String(k);
    panel.replaceChildren(...modePanel(data, data.modes[k], k, h));
    update(loop()[0]);
  };

  let playing = current >= 0;
  let last = 0;
  const tick = (now) => {
    if (!playing) return;
    const [t0, t1] = loop();
    const dt = (((now - last) / 1000) * Number(speed.value) * (t1 - t0)) / LOOP_SECONDS;
    last = now;
    let t = shown + dt;
    if (t >= t1) t = t0 + ((t - t0) % (t1 - t0));
    update(t);
    requestAnimationFrame(tick);
  };
  const start = () => {
    last = performance.now();
    requestAnimationFrame(tick);
  };
  const pause = () => {
    playing = false;
    play.textContent = 'Play';
  };
  play.addEventListener('click', () => {
    playing = !playing && current >= 0;
    play.textContent = playing ? 'Pause' : 'Play';
    if (playing) start();
  });
  select.addEventListener('change', () => choose(Number(select.value)));
  slider.addEventListener('input', () => {
    const [t0, t1] = loop();
    update(t0 + ((t1 - t0) * Number(slider.value)) / 1000);
  });

  api.modes = () => data.modes.map((m, k) => ({ index: k, label: modeLabel(m, k, fmt), animated: m.animated }));
  api.selectMode = (k) => {
    if (!data.modes[k] || !data.modes[k].animated) throw new Error(`mode ${k + 1} is not animated`);
    choose(k);
  };
  api.seek = (t) => {
    pause();
    update(Number(t));
  };
  api.bodyPose = (name) => {
    const k = data.bodies.findIndex((b) => b.name === name);
    return k < 0 ? null : modePose(data.bodies[k], bases[k], mode(), shown);
  };
  Object.defineProperty(api, 'time', { get: () => shown, configurable: true });
  Object.defineProperty(api, 'mode', { get: () => current, configurable: true });
  if (current >= 0) {
    choose(current);
    if (playing) start();
  } else {
    play.disabled = true;
    panel.append(el('p', { class: 'note' }, 'No mode to animate: every mode is rigid.'));
    update(0);
  }
}
