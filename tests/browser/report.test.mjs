// The browser report in a real browser: headless Chromium (Debian's /usr/bin/chromium, driven
// by puppeteer-core) opens reports the program wrote, from file:// URLs with every network
// request refused, and the page is checked against the run's own CSV and JSON and against
// closed forms. Run by ctest through run.mjs (CHASLES_SOURCE, CHASLES set); set
// CHASLES_SCREENSHOTS=DIR to also save the screenshots docs/report.md shows.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { createRequire } from 'node:module';
import { mkdtempSync, readFileSync, rmSync, mkdirSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { execFileSync, spawnSync } from 'node:child_process';
import { pathToFileURL } from 'node:url';

const source = process.env.CHASLES_SOURCE;
const chasles = process.env.CHASLES;
const chromium = process.env.CHASLES_CHROMIUM || '/usr/bin/chromium';
const shots = process.env.CHASLES_SCREENSHOTS || '';
const require = createRequire(join(source, 'report/package.json'));
const puppeteer = require('puppeteer-core');

const work = mkdtempSync(join(tmpdir(), 'chasles-browser-'));
let browser;

function chaslesRun(args) {
  return execFileSync(chasles, args, { cwd: work, encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
}

function example(name) {
  return join(source, 'examples', name);
}

/** The CSV as column names and numeric rows (the program writes plain numbers). */
function readCsv(path) {
  const lines = readFileSync(path, 'utf8').trim().split('\n');
  // A header field is the column's name, then, for a column with a unit, one space and the
  // unit in brackets ("t [s]"): the column is found by its name.
  const names = lines[0].split(',').map((s) => s.replace(/^"|"$/g, '').replace(/ \[[^\]]*\]$/, ''));
  const rows = lines.slice(1).map((l) => l.split(',').map(Number));
  return { names, rows, col: (n) => names.indexOf(n) };
}

/** A seeded generator (LCG), so the sampled rows are the same at every run. */
function lcg(seed) {
  let s = seed >>> 0;
  return () => {
    s = (1664525 * s + 1013904223) >>> 0;
    return s / 2 ** 32;
  };
}

/** Opens a report; any http(s) request, console error or page error fails the test. */
async function openReport(file) {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 760 });
  const problems = [];
  await page.setRequestInterception(true);
  page.on('request', (req) => {
    const url = req.url();
    if (url.startsWith('file:') || url.startsWith('data:') || url.startsWith('blob:')) {
      req.continue();
    } else {
      problems.push(`network request: ${url}`);
      req.abort();
    }
  });
  page.on('console', (m) => {
    if (m.type() === 'error') problems.push(`console error: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  await page.goto(pathToFileURL(file).href, { waitUntil: 'load' });
  await page.waitForFunction('window.chasles && (window.chasles.ready || window.chasles.errors.length)', {
    timeout: 20000,
  });
  const errors = await page.evaluate(() => window.chasles.errors);
  assert.deepEqual(errors, [], 'the page reports errors');
  assert.equal(await page.evaluate(() => window.chasles.ready), true);
  return { page, problems };
}

/** The 3-D view is not blank: distinct colours and pixels other than the background. */
async function checkNotBlank(page) {
  const stats = await page.evaluate(() => {
    const c = document.querySelector('#view canvas');
    const w = c.width;
    const h = c.height;
    const g = document.createElement('canvas');
    g.width = w;
    g.height = h;
    const ctx = g.getContext('2d');
    ctx.drawImage(c, 0, 0);
    const px = ctx.getImageData(0, 0, w, h).data;
    const colours = new Set();
    let other = 0;
    for (let i = 0; i < px.length; i += 4) {
      colours.add((px[i] << 16) | (px[i + 1] << 8) | px[i + 2]);
      // Background: the clear colour (247, 247, 244).
      if (Math.abs(px[i] - 247) + Math.abs(px[i + 1] - 247) + Math.abs(px[i + 2] - 244) > 12) other++;
    }
    return { colours: colours.size, fraction: other / (w * h) };
  });
  assert.ok(stats.colours > 50, `only ${stats.colours} colours in the 3-D view`);
  assert.ok(stats.fraction > 0.01, `only ${(100 * stats.fraction).toFixed(2)}% of the view drawn`);
}

async function screenshot(page, name) {
  if (!shots) return;
  mkdirSync(shots, { recursive: true });
  await page.screenshot({ path: join(shots, name), type: 'png' });
}

/** The times the page must mark: events, contact-mode changes (not the initial modes),
 * impacts and jumps of the run's JSON summary. */
function expectedMarks(json) {
  const t = [];
  for (const e of json.events || []) t.push(e.t);
  for (const e of json.contact_events || []) if (e.reason !== 'initial') t.push(e.t);
  for (const e of json.impacts || []) t.push(e.t);
  for (const e of json.jumps || []) t.push(e.t);
  return t.sort((a, b) => a - b);
}

/**
 * The run's own origin and quaternion columns: the same run again without --html, asked for
 * those columns only (another --columns of `args` left out), in a folder of its own. The page's
 * poses are data of their own (recorded from the states, or read by `chasles report` from the
 * CSV); these columns are the independent record they are compared with.
 */
function referencePoses(stem, scene, args) {
  const dir = join(work, `reference-${stem}`);
  mkdirSync(dir, { recursive: true });
  const rest = args.filter((a, k) => a !== '--columns' && args[k - 1] !== '--columns');
  chaslesRun(['simulate', example(scene), '--out', dir, '--quiet', ...rest, '--columns', 'origin,quaternion']);
  return readCsv(join(dir, `${stem}.csv`));
}

/**
 * At seeded samples, seek(t) then bodyPose equals the reference run's origin and quaternion at
 * that row to 1e-9 (referencePoses). Returns the number of poses compared.
 */
async function comparePoses(page, stem, reference) {
  const bodies = await page.evaluate(() => window.chasles.data.bodies.map((b) => b.name));
  const n = reference.rows.length;
  const t = reference.col('t');
  const random = lcg(20261124);
  const picks = [0, n - 1, n >> 1];
  for (let k = 0; k < 6; k++) picks.push(Math.floor(random() * n));
  let compared = 0;
  for (const i of picks) {
    const ti = reference.rows[i][t];
    // A row repeated at one time (the state after an impulse) is shown as the later one.
    const unique = (i + 1 >= n || reference.rows[i + 1][t] !== ti) && (i === 0 || reference.rows[i - 1][t] !== ti);
    if (!unique) continue;
    await page.evaluate((x) => window.chasles.seek(x), ti);
    for (const b of bodies) {
      const pose = await page.evaluate((name) => window.chasles.bodyPose(name), b);
      const want = ['ox', 'oy', 'oz', 'qw', 'qx', 'qy', 'qz'].map((s) => reference.rows[i][reference.col(`${b}_${s}`)]);
      const got = [...pose.position, ...pose.quaternion];
      for (let c = 0; c < 7; c++) {
        assert.ok(
          Math.abs(got[c] - want[c]) <= 1e-9 * Math.max(1, Math.abs(want[c])),
          `${stem}: body ${b} at t = ${ti}: pose component ${c} is ${got[c]}, the run's ${want[c]}`,
        );
      }
      compared++;
    }
  }
  assert.ok(compared >= bodies.length * 3, `${stem}: only ${compared} poses compared`);
  return compared;
}

/**
 * A simulate report against its run: at seeded samples, seek(t) then bodyPose equals the run's
 * origin and quaternion at that row to 1e-9 (comparePoses); the ledger plot holds every energy
 * and work column; every plot marks every event.
 */
async function checkSimulation(stem, scene, args = [], fromJson = false) {
  const html = join(work, `${stem}.html`);
  if (fromJson) {
    // The run without --html, then `chasles report` from its JSON summary.
    chaslesRun(['simulate', example(scene), '--out', work, '--quiet', ...args]);
    chaslesRun(['report', join(work, `${stem}.json`), '-o', html]);
  } else {
    chaslesRun(['simulate', example(scene), '--out', work, '--html', html, '--quiet', ...args]);
  }
  const csv = readCsv(join(work, `${stem}.csv`));
  const json = JSON.parse(readFileSync(join(work, `${stem}.json`), 'utf8'));
  const { page, problems } = await openReport(html);
  // A finished run's files hold no states: `chasles report` reads the poses from the CSV.
  assert.equal(await page.evaluate(() => window.chasles.data.poses_from), fromJson ? 'columns' : 'states');
  await comparePoses(page, stem, referencePoses(stem, scene, args));

  const plots = await page.evaluate(() => window.chasles.plots());
  const ledger = plots.find((p) => p.title.startsWith('Energy ledger'));
  assert.ok(ledger, `${stem}: no energy ledger plot`);
  const ledgerColumns = csv.names.filter(
    (c) => ['T', 'V', 'E', 'W_nc', 'dissipated', 'residual'].includes(c) || c.startsWith('W_'),
  );
  for (const c of ledgerColumns) assert.ok(ledger.series.includes(c), `${stem}: ledger plot lacks ${c}`);
  for (const c of ['T', 'V', 'E', 'residual']) assert.ok(ledger.series.includes(c), `${stem}: no ${c}`);
  const marks = expectedMarks(json);
  for (const p of plots) {
    assert.equal(p.eventMarks.length, marks.length, `${stem}: plot '${p.title}' marks`);
    p.eventMarks.forEach((x, k) => assert.ok(Math.abs(x - marks[k]) <= 1e-12 * Math.max(1, Math.abs(marks[k]))));
  }
  await checkNotBlank(page);
  assert.deepEqual(problems, []);
  return { page, plots, csv, json };
}

before(async () => {
  browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--disable-gpu-sandbox'],
  });
});

after(async () => {
  if (browser) await browser.close();
  rmSync(work, { recursive: true, force: true });
});

test('mass report: two rods (Example 8.2) with the central inertia of the closed form', async () => {
  const html = join(work, 'two-rods.html');
  chaslesRun(['mass', example('example-8.2-two-rods.yaml'), '--html', html]);
  const { page, problems } = await openReport(html);
  // m = 1 kg, l = 1 m. Vertical rod 2m over [0, 2l] along z, horizontal rod m over [0, l]
  // along y at height l. Centre of mass (2m (0,0,l) + m (0,l/2,l)) / 3m = (0, l/6, l). A rod
  // of mass M, length L along u about its centre: M L²/12 (E − u uᵀ); moved by d from the
  // centre of mass: + M (|d|² E − d dᵀ) (eq. 8.29).
  const rod = (M, L, u, c, cm) => {
    const d = c.map((x, k) => x - cm[k]);
    const dd = d.reduce((s, x) => s + x * x, 0);
    return [0, 1, 2].map((i) =>
      [0, 1, 2].map((j) => ((M * L * L) / 12) * ((i === j) - u[i] * u[j]) + M * (dd * (i === j) - d[i] * d[j])),
    );
  };
  const cm = [0, 1 / 6, 1];
  const A = rod(2, 2, [0, 0, 1], [0, 0, 1], cm);
  const B = rod(1, 1, [0, 1, 0], [0, 0.5, 1], cm);
  const data = await page.evaluate(() => {
    const b = window.chasles.data.bodies[0];
    return { mass: b.mass, cm: b.center_of_mass, I: b.inertia, moments: b.principal_moments };
  });
  assert.ok(Math.abs(data.mass - 3) <= 1e-12);
  cm.forEach((x, k) => assert.ok(Math.abs(data.cm[k] - x) <= 1e-12, `centre of mass ${k}`));
  for (let i = 0; i < 3; i++) {
    for (let j = 0; j < 3; j++) {
      const want = A[i][j] + B[i][j];
      assert.ok(Math.abs(data.I[i][j] - want) <= 1e-12, `I[${i}][${j}] = ${data.I[i][j]}, closed form ${want}`);
    }
  }
  // The principal moments are the eigenvalues: their sum is the trace.
  const trace = [0, 1, 2].reduce((s, k) => s + A[k][k] + B[k][k], 0);
  assert.ok(Math.abs(data.moments.reduce((s, x) => s + x, 0) - trace) <= 1e-12 * trace);
  assert.deepEqual(await page.evaluate(() => window.chasles.plots()), []);
  await checkNotBlank(page);
  assert.deepEqual(problems, []);
  await page.close();
});

test('mass report: a mesh part (the L-bracket OBJ) drawn from its file, in metres', async () => {
  const html = join(work, 'bracket.html');
  chaslesRun(['mass', example('mesh-bracket-assembly.yaml'), '--html', html]);
  const { page, problems } = await openReport(html);
  // The OBJ's own vertices and triangles ("v" and "f" lines), scaled from mm to m.
  const obj = readFileSync(example('meshes/l-bracket.obj'), 'utf8').split('\n');
  const v = obj.filter((l) => l.startsWith('v ')).map((l) => l.split(/\s+/).slice(1, 4).map(Number));
  const f = obj.filter((l) => l.startsWith('f ')).map((l) => l.split(/\s+/).slice(1, 4).map((x) => Number(x.split('/')[0]) - 1));
  const mesh = await page.evaluate(() => {
    const p = window.chasles.data.bodies[0].parts.find((x) => x.mesh);
    return { positions: Array.from(p.mesh.positions), indices: Array.from(p.mesh.indices) };
  });
  assert.equal(mesh.positions.length, 3 * v.length);
  assert.deepEqual(mesh.indices, f.flat());
  v.flat().forEach((x, k) => assert.ok(Math.abs(mesh.positions[k] - x * 1e-3) <= 1e-7 * Math.max(1e-3, Math.abs(x * 1e-3))));
  await checkNotBlank(page);
  await screenshot(page, 'report-mass.png');
  assert.deepEqual(problems, []);
  await page.close();
});

/** A robot of two boxes and the L-bracket OBJ (in mm, scale 0.001), with one decimal slip. */
const AUDIT_URDF = `<?xml version="1.0"?>
<robot name="two_boxes">
  <link name="base">
    <inertial>
      <mass value="2"/>
      <inertia ixx="0.008333333333333333" iyy="0.028333333333333335" izz="0.03333333333333333" ixy="0" ixz="0" iyz="0"/>
    </inertial>
    <visual><geometry><box size="0.4 0.2 0.1"/></geometry></visual>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.05" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="10" velocity="1"/>
  </joint>
  <link name="arm">
    <inertial>
      <origin xyz="0 0 0.3"/>
      <mass value="1"/>
      <inertia ixx="0.030833333333333334" iyy="0.030833333333333334" izz="0.016666666666666666" ixy="0" ixz="0" iyz="0"/>
    </inertial>
    <visual><origin xyz="0 0 0.3"/><geometry><box size="0.1 0.1 0.6"/></geometry></visual>
  </link>
  <joint name="wrist" type="fixed">
    <parent link="arm"/><child link="tool"/><origin xyz="0 0 0.6"/>
  </joint>
  <link name="tool">
    <inertial>
      <mass value="0.1"/>
      <inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/>
    </inertial>
    <visual><geometry><mesh filename="${example('meshes/l-bracket.obj')}" scale="0.001 0.001 0.001"/></geometry></visual>
  </link>
</robot>
`;

test('audit report: links drawn from their geometry, the computed ellipsoid of a box in closed form, findings listed', async () => {
  const urdf = join(work, 'two_boxes.urdf');
  writeFileSync(urdf, AUDIT_URDF);
  const html = join(work, 'audit.html');
  const r = spawnSync(chasles, ['audit', urdf, '--html', html], { cwd: work, encoding: 'utf8' });
  assert.equal(r.status, 3, r.stderr);  // the decimal slip is an error
  const { page, problems } = await openReport(html);
  const data = await page.evaluate(() => {
    const d = window.chasles.data;
    return {
      audit: d.audit,
      bodies: d.bodies.map((b) => ({
        name: b.name,
        mass: b.mass,
        cm: b.center_of_mass,
        computed: b.computed,
        parts: b.parts.map((p) => ({ name: p.name, shape: p.shape, position: p.position, n: p.mesh ? p.mesh.positions.length : 0 })),
      })),
    };
  });
  assert.deepEqual(data.bodies.map((b) => b.name), ['base', 'arm', 'tool']);
  // Legendre's ellipsoid of a uniform box of edges s: I_x = m (s_y² + s_z²) / 12, so
  // a_x² = 5 (I_y + I_z − I_x) / (2m) = 5 s_x² / 12 (each axis alike), at any mass.
  const semi = (s) => s.map((x) => x * Math.sqrt(5 / 12)).sort((a, b) => a - b);
  const near = (a, b, what) => assert.ok(Math.abs(a - b) <= 1e-12 * Math.max(1, Math.abs(b)), `${what}: ${a}, closed form ${b}`);
  const [base, arm, tool] = data.bodies;
  [...base.computed.ellipsoid.semi_axes].sort((a, b) => a - b).forEach((x, k) => near(x, semi([0.4, 0.2, 0.1])[k], `base semi-axis ${k}`));
  [...arm.computed.ellipsoid.semi_axes].sort((a, b) => a - b).forEach((x, k) => near(x, semi([0.1, 0.1, 0.6])[k], `arm semi-axis ${k}`));
  assert.equal(base.computed.source, 'visual');
  // Each link at its pose in the base frame (zero configuration): the arm 0.05 m up, its box's
  // centre 0.3 m along its z; the tool 0.6 m further.
  [0, 0, 0.35].forEach((x, k) => near(arm.cm[k], x, `arm centre of mass ${k}`));
  [0, 0, 0.35].forEach((x, k) => near(arm.computed.ellipsoid.center[k], x, `arm computed centre ${k}`));
  near(arm.mass, 1, 'arm mass (the given one)');
  assert.deepEqual(arm.parts.map((p) => p.shape), ['box']);
  const bracket = tool.parts.find((p) => p.shape === 'mesh');
  const obj = readFileSync(example('meshes/l-bracket.obj'), 'utf8').split('\n');
  assert.equal(bracket.n, 3 * obj.filter((l) => l.startsWith('v ')).length);
  [0, 0, 0.65].forEach((x, k) => near(bracket.position[k], x, `bracket position ${k}`));
  // The findings, per link with its line, as the text report has them.
  const links = Object.fromEntries(data.audit[0].links.map((l) => [l.name, l]));
  assert.deepEqual(links.base.findings, []);
  assert.deepEqual(links.arm.findings.map((f) => [f.code, f.line]), [['decimal_slip', 19]]);
  assert.equal(links.tool.findings[0].code, 'placeholder_inertia');
  const text = await page.evaluate(() => document.body.innerText);
  assert.ok(text.includes('error decimal_slip (line 19)'), 'the error is listed');
  assert.ok(text.includes('orange wire ellipsoid'), 'the computed ellipsoid is explained');
  await checkNotBlank(page);
  await screenshot(page, 'report-audit.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('simulate report: the Dzhanibekov flip', async () => {
  const { page, json } = await checkSimulation('dzhanibekov', 'dzhanibekov.yaml');
  assert.ok(json.events.length > 0, 'the flip events');
  await page.evaluate(() => window.chasles.seek(3.3));
  await screenshot(page, 'report-dzhanibekov.png');
  await page.close();
});

test('simulate report: contacts of the spinning ball (Problem 8.26), regime bands', async () => {
  const { page, plots, csv } = await checkSimulation('problem-8.26-spinning-ball', 'problem-8.26-spinning-ball.yaml');
  const contacts = plots.find((p) => p.title.startsWith('Contacts'));
  assert.ok(contacts, 'no contacts plot');
  for (const c of csv.names.filter((c) => /_(N|f)$/.test(c) && csv.names.includes(c.replace(/_(N|f)$/, '_mode')))) {
    assert.ok(contacts.series.includes(c), `contacts plot lacks ${c}`);
  }
  // The bands are the CSV's mode columns, sample by sample.
  const modes = await page.evaluate(() => window.chasles.data.contacts.map((c) => ({ name: c.name, modes: c.modes })));
  assert.ok(modes.length > 0);
  for (const m of modes) {
    const col = csv.col(`${m.name}_mode`);
    assert.ok(col >= 0, `no mode column for ${m.name}`);
    assert.equal(m.modes, csv.rows.map((r) => String(r[col])).join(''), `${m.name}: regime bands`);
  }
  await page.close();
});

test('simulate report: planar sliding ladder (Example 8.4), reactions', async () => {
  const { page, plots, csv } = await checkSimulation('example-8.4-sliding-ladder-planar', 'example-8.4-sliding-ladder-planar.yaml');
  const reactions = plots.find((p) => p.title.startsWith('Reactions'));
  assert.ok(reactions, 'no reactions plot');
  for (const c of csv.names.filter((c) => /_F[xy]$/.test(c))) assert.ok(reactions.series.includes(c), `lacks ${c}`);
  assert.equal(await page.evaluate(() => window.chasles.data.planar), true);
  await page.close();
});

test('simulate report: applied forces drawn where they act (a pinned rod pushed sideways)', async () => {
  const { page, csv } = await checkSimulation('pinned-rod-world-force', 'pinned-rod-world-force.yaml');
  // The push (5 N along +x, world-fixed) and gravity (m g = 2 kg × 9.81 m/s² down) act at the
  // rod's centre of mass; the arrows' points and forces are the run's to f4 precision.
  const random = lcg(7);
  for (let k = 0; k < 4; k++) {
    const i = Math.floor(random() * csv.rows.length);
    await page.evaluate((x) => window.chasles.seek(x), csv.rows[i][csv.col('t')]);
    const arrows = await page.evaluate(() => window.chasles.arrows());
    const cm = ['rod_x', 'rod_y', 'rod_z'].map((c) => csv.rows[i][csv.col(c)]);
    for (const [name, force] of [['push on rod', [5, 0, 0]], ['gravity on rod', [0, 0, -2 * 9.81]]]) {
      const a = arrows.find((x) => x.kind === 'applied' && x.name === name);
      assert.ok(a, `no arrow '${name}' at row ${i}; arrows: ${arrows.map((x) => x.name)}`);
      for (let c = 0; c < 3; c++) {
        assert.ok(Math.abs(a.force[c] - force[c]) <= 1e-6 * 19.62, `${name} force ${a.force}`);
        assert.ok(Math.abs(a.origin[c] - cm[c]) <= 1e-6, `${name} at ${a.origin}, centre of mass ${cm}`);
      }
    }
    assert.ok(arrows.some((x) => x.kind === 'reaction' && x.name === 'pin'), 'the pin reaction');
  }
  const legend = await page.evaluate(() => document.getElementById('legend').innerText);
  assert.ok(legend.includes('applied force'), legend);
  await page.close();
});

test('simulate report: the replay needs no column names (every column renamed)', async () => {
  // The pinned rod's report with every column but the clock t renamed: the replay draws the
  // poses of the data's own block, by body index, so they still equal the run's origin and
  // quaternion (its centre of mass is off its origin at the pin, and it turns).
  const stem = 'pinned-rod-world-force';
  const dir = join(work, 'renamed');
  mkdirSync(dir, { recursive: true });
  const html = join(dir, `${stem}.html`);
  chaslesRun(['simulate', example(`${stem}.yaml`), '--out', dir, '--html', html, '--quiet']);
  const page0 = readFileSync(html, 'utf8');
  const block = /(<script type="application\/json" id="chasles-data">)(.*?)(<\/script>)/s;
  const m = page0.match(block);
  assert.ok(m, 'no data block');
  const data = JSON.parse(m[2]);
  assert.ok(data.columns.some((c) => c.name.startsWith('rod_')), 'the run has columns named after the rod');
  data.columns.forEach((c, k) => {
    if (c.name !== 't') c.name = `column ${k}`;
  });
  const renamed = join(dir, `${stem}-renamed.html`);
  const text = JSON.stringify(data).replace(/</g, '\\u003c');
  writeFileSync(renamed, page0.replace(block, (_, a, _b, c) => `${a}${text}${c}`));
  const { page, problems } = await openReport(renamed);
  const names = await page.evaluate(() => window.chasles.data.columns.map((c) => c.name));
  assert.ok(!names.some((n) => n.startsWith('rod_')), `columns still named after the rod: ${names}`);
  await comparePoses(page, stem, referencePoses(stem, `${stem}.yaml`, []));
  assert.deepEqual(problems, []);
  await page.close();
});

test('report from a finished run: projectile with drag, apex and ground events', async () => {
  const { page, json } = await checkSimulation(
    'projectile-drag',
    'projectile-drag.yaml',
    ['--columns', 'position,quaternion,energy,work,residual'],
    true,
  );
  assert.ok(json.events.some((e) => e.name === 'ground' && e.stopped), 'the ground event');
  assert.deepEqual(await page.evaluate(() => window.chasles.data.reactions), []);
  await page.close();
});

test('solve report: the ladder at its solved instant', async () => {
  const html = join(work, 'ladder-solve.html');
  chaslesRun(['solve', example('example-8.4-sliding-ladder-planar.yaml'), '--html', html]);
  const { page, problems } = await openReport(html);
  const data = await page.evaluate(() => ({ poses: window.chasles.data.poses, reactions: window.chasles.data.solve_reactions }));
  assert.ok(data.reactions.length > 0);
  for (const p of data.poses) {
    const pose = await page.evaluate((name) => window.chasles.bodyPose(name), p.name);
    assert.deepEqual(pose.position, p.origin);
  }
  await checkNotBlank(page);
  assert.deepEqual(problems, []);
  await page.close();
});

/**
 * A sweep report against its table: every plot's points equal the table's (the JSON form, full
 * doubles) at the same parameter values, one line per value of the other parameter.
 */
function checkSweepPlots(plots, table, xName, otherName) {
  const col = (n) => table.columns.indexOf(n);
  for (const p of plots) {
    const q = p.title.replace(/ \[[^\]]*\]/, '').replace(/ against .*$/, '');
    assert.ok(col(q) >= 0, `plot '${p.title}' of no column`);
    const xs = [...new Set(table.rows.map((r) => r[col(xName)]))].sort((a, b) => a - b);
    assert.deepEqual(p.xs, xs);
    table.rows.forEach((r, k) => {
      const line = otherName ? [...new Set(table.rows.map((s) => s[col(otherName)]))].indexOf(r[col(otherName)]) : 0;
      const got = p.ys[line][xs.indexOf(r[col(xName)])];
      const want = r[col(q)];
      if (want === null) assert.equal(got, null, `row ${k}`);
      else assert.ok(Math.abs(got - want) <= 1e-9 * Math.max(1, Math.abs(want)), `${q} row ${k}: ${got} vs ${want}`);
    });
  }
}

test('sweep report: a planar pendulum over length and amplitude (simulate --sweep)', async () => {
  const html = join(work, 'pendulum-sweep.html');
  const args = ['simulate', example('pendulum.yaml'), '--sweep', 'L=0.5 m:2 m:4', '--sweep', 'theta0=10 deg:80 deg:8',
    '--quantity', 'event(bottom)', '--quantity', 'min(ball_vx)', '--quiet'];
  const table = JSON.parse(chaslesRun([...args, '--format', 'json', '--html', html]));
  assert.equal(table.rows.length, 32);
  const { page, problems } = await openReport(html);
  assert.equal(await page.evaluate(() => window.chasles.data.planar), true);
  const plots = await page.evaluate(() => window.chasles.plots());
  // One plot per quantity against theta0 (the last parameter), one line per length.
  assert.deepEqual(plots.map((p) => p.title), ['event(bottom) [s] against theta0', 'min(ball_vx) [m/s] against theta0']);
  for (const p of plots) assert.deepEqual(p.series, ['L = 0.5 m', 'L = 1 m', 'L = 1.5 m', 'L = 2 m']);
  checkSweepPlots(plots, table, 'theta0', 'L');
  // The quarter period grows with the amplitude on every line (K(sin(theta0/2)) increases).
  for (const y of plots[0].ys) for (let i = 1; i < y.length; i++) assert.ok(y[i] > y[i - 1]);
  // Against L instead: one line per amplitude.
  await page.select('#sweep-x', 'L');
  const byL = await page.evaluate(() => window.chasles.plots());
  assert.equal(byL[0].series.length, 8);
  checkSweepPlots(byL, table, 'L', 'theta0');
  // The scene drawn at its own values: the body frame at the pin, the ball's centre at
  // L (sin 30°, -cos 30°) in it with L = 1 m.
  const pose = await page.evaluate(() => window.chasles.bodyPose('ball'));
  assert.deepEqual(pose, { position: [0, 0, 0], quaternion: [1, 0, 0, 0] });
  const c = await page.evaluate(() => window.chasles.data.bodies[0].center_of_mass);
  assert.ok(Math.abs(c[0] - 0.5) < 1e-12 && Math.abs(c[1] + Math.sqrt(3) / 2) < 1e-12, `${c}`);
  await checkNotBlank(page);
  await screenshot(page, 'report-sweep.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('sweep report: a failed point is listed and left out of the plots (mass --sweep)', async () => {
  const html = join(work, 'cylinder-sweep.html');
  // R from -1 cm: the first point is a negative radius, a failed row with its reason.
  const table = JSON.parse(chaslesRun(['mass', example('example-8.1-cylinder.yaml'), '--sweep', 'R=-1 cm:8 cm:4',
    '--quantity', 'cylinder.Izz', '--quantity', 'cylinder.mass', '--format', 'json', '--quiet', '--html', html]));
  assert.ok(table.errors[0], 'the negative radius fails');
  const { page, problems } = await openReport(html);
  const plots = await page.evaluate(() => window.chasles.plots());
  assert.equal(plots.length, 2);
  checkSweepPlots(plots, table, 'R', null);
  assert.equal(plots[0].ys[0][0], null);
  const text = await page.evaluate(() => document.body.innerText);
  assert.ok(text.includes('Failed points'), 'the failed points are listed');
  assert.ok(text.includes(table.errors[0]), 'with their reason');
  assert.deepEqual(problems, []);
  await page.close();
});

test('sweep report: a solve sweep plots the forces and regimes that vary, not round-off (solve --sweep)', async () => {
  const html = join(work, 'incline-sweep.html');
  const table = JSON.parse(chaslesRun(['solve', example('contact-cylinder-incline.yaml'), '--sweep', 'theta=30 deg:40 deg:11',
    '--format', 'json', '--quiet', '--html', html]));
  const { page, problems } = await openReport(html);
  const plots = await page.evaluate(() => window.chasles.plots());
  const titles = plots.map((p) => p.title.replace(/ \[[^\]]*\]/, '').replace(/ against .*$/, ''));
  assert.ok(plots.length <= 8 && plots.length > 0, titles.join(', '));
  assert.equal(titles[0], 'incline_0_mode', titles.join(', '));
  // y is out of the plane of motion: its acceleration is round-off, not plotted.
  assert.ok(!titles.includes('cylinder_ay'), titles.join(', '));
  checkSweepPlots(plots, table, 'theta', null);
  // Rolls (2, sticking) while tan(theta) / 3 <= mu_s = 0.25, i.e. theta <= atan(0.75); slides (1) above.
  const mode = plots[0];
  mode.xs.forEach((x, i) => assert.equal(mode.ys[0][i], x <= Math.atan(0.75) ? 2 : 1, `theta ${x}`));
  assert.deepEqual(problems, []);
  await page.close();
});

/** Hamilton product of quaternions [w, x, y, z]. */
function qmul(a, b) {
  return [
    a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
    a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
    a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
    a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
  ];
}

/** v turned by the unit quaternion q: q v q*. */
function rotate(q, v) {
  const r = qmul(qmul(q, [0, ...v]), [q[0], -q[1], -q[2], -q[3]]);
  return r.slice(1);
}

/**
 * The pose a mode moves a body to at time t, worked out here from the data alone (docs/report.md,
 * "Modes"): Bcm = Bcm0 + Re(dp e^{λt}), R = exp(δθ) R0 with δθ = Re(dθ e^{λt}) about W's axes,
 * and the frame origin Bo = Bcm − R p_BoBcm_B.
 */
function expectedModePose(base, p_BoBcm_B, motion, lambda, t) {
  const re = (d) => [0, 1, 2].map((i) => Math.exp(lambda[0] * t) * (d.re[i] * Math.cos(lambda[1] * t) - d.im[i] * Math.sin(lambda[1] * t)));
  const dp = re(motion.dp);
  const dtheta = re(motion.dtheta);
  const a = Math.hypot(...dtheta);
  const s = a > 0 ? Math.sin(a / 2) / a : 0.5;
  const q = qmul([Math.cos(a / 2), dtheta[0] * s, dtheta[1] * s, dtheta[2] * s], base.quaternion);
  const offset = rotate(q, p_BoBcm_B);
  return { position: base.center_of_mass.map((x, i) => x + dp[i] - offset[i]), quaternion: q };
}

/** |a − b| of two poses: positions, and quaternions up to their sign. */
function poseGap(a, b) {
  const dp = Math.hypot(...a.position.map((x, i) => x - b.position[i]));
  const plus = Math.hypot(...a.quaternion.map((x, i) => x - b.quaternion[i]));
  const minus = Math.hypot(...a.quaternion.map((x, i) => x + b.quaternion[i]));
  return { position: dp, quaternion: Math.min(plus, minus) };
}

test('modes report: the pendulum swings about its pin at the closed-form frequency', async () => {
  const html = join(work, 'pendulum-modes.html');
  chaslesRun(['modes', example('pendulum.yaml'), '--set', 'theta0=0 deg', '--html', html]);
  const { page, problems } = await openReport(html);
  // The example's ball: m = 1.5 kg, radius r = 0.05 m, its centre L = 1 m below the pin at Wo.
  // I_O = (2/5) m r² + m L² (eq. 8.39), ω² = m g L / I_O.
  const m = 1.5;
  const r = 0.05;
  const L = 1;
  const w = Math.sqrt((m * 9.80665 * L) / (0.4 * m * r * r + m * L * L));
  const data = await page.evaluate(() => ({ modes: window.chasles.data.modes, amplitude: window.chasles.data.amplitude }));
  assert.equal(data.modes.length, 1);
  const mode = data.modes[0];
  assert.ok(mode.animated && !mode.rigid && mode.stable);
  assert.ok(Math.abs(mode.eigenvalue[1] - w) <= 1e-10 * w);
  // The shape's unit entry is the pin angle φ: the ball turns by φ z about the pin and its
  // centre moves by φ z × (0, -L, 0) = φ (L, 0, 0): tangent to its circle, |δp| = L |δθ|.
  const eps = mode.scale;
  const dp = mode.bodies[0].dp;
  const dtheta = mode.bodies[0].dtheta;
  [eps * L, 0, 0].forEach((x, i) => assert.ok(Math.abs(dp.re[i] - x) <= 1e-9 * eps * L && Math.abs(dp.im[i]) <= 1e-9 * eps * L, `dp ${i}`));
  [0, 0, eps].forEach((x, i) => assert.ok(Math.abs(dtheta.re[i] - x) <= 1e-9 * eps && Math.abs(dtheta.im[i]) <= 1e-9 * eps, `dtheta ${i}`));
  // The largest excursion |δp| + ρ|δθ| (ρ² = tr(I)/(2m) = (3/5) r² for a solid ball) is 10 %
  // of the scene's size: the pin to the ball's centre, L, plus 2ρ.
  const rho = Math.sqrt(0.6) * r;
  assert.ok(Math.abs(data.amplitude.scene_size - (L + 2 * rho)) <= 1e-12);
  assert.ok(Math.abs(eps * (L + rho) - 0.1 * data.amplitude.scene_size) <= 1e-12);
  // One period at constant amplitude.
  assert.equal(mode.shown, 'oscillation');
  assert.deepEqual(mode.loop[0], 0);
  assert.ok(Math.abs(mode.loop[1] - (2 * Math.PI) / w) <= 1e-9);
  // The selector: one option, its label the frequency.
  const options = await page.$$eval('#mode option', (o) => o.map((x) => ({ text: x.textContent, disabled: x.disabled })));
  assert.equal(options.length, 1);
  assert.ok(options[0].text.includes(`${Number((w / (2 * Math.PI)).toPrecision(6))} Hz`), options[0].text);
  assert.equal(options[0].disabled, false);
  // The ball at φ(t) = ε cos ωt: q = [cos φ/2, 0, 0, sin φ/2], and its frame origin (at the pin
  // when it hangs) at Bcm − R p_BoBcm_B = (Lφ, −L, 0) − R (0, −L, 0) = (L (φ − sin φ), L (cos φ − 1), 0).
  const random = lcg(11);
  for (let k = 0; k < 6; k++) {
    const t = random() * mode.loop[1];
    const pose = await page.evaluate((x) => {
      window.chasles.seek(x);
      return window.chasles.bodyPose('ball');
    }, t);
    const phi = eps * Math.exp(mode.eigenvalue[0] * t) * Math.cos(w * t);
    const want = { position: [L * (phi - Math.sin(phi)), L * (Math.cos(phi) - 1), 0], quaternion: [Math.cos(phi / 2), 0, 0, Math.sin(phi / 2)] };
    const gap = poseGap(pose, want);
    assert.ok(gap.position <= 1e-9 && gap.quaternion <= 1e-9, `t = ${t}: ${JSON.stringify(pose)} vs ${JSON.stringify(want)}`);
  }
  await checkNotBlank(page);
  assert.deepEqual(problems, []);
  await page.close();
});

test('modes report: the bicycle at 2 m/s, every mode in the selector, growing and decaying loops', async () => {
  const html = join(work, 'bicycle-modes.html');
  chaslesRun(['modes', example('whipple-bicycle.yaml'), '--set', 'v=2 m/s', '--html', html]);
  const { page, problems } = await openReport(html);
  const data = await page.evaluate(() => ({ modes: window.chasles.data.modes, bodies: window.chasles.data.bodies, poses: window.chasles.data.poses }));
  const options = await page.$$eval('#mode option', (o) => o.map((x) => ({ value: x.value, text: x.textContent, disabled: x.disabled })));
  assert.equal(options.length, data.modes.length);
  const labels = await page.evaluate(() => window.chasles.modes());
  data.modes.forEach((m, k) => {
    assert.equal(options[k].disabled, !m.animated, `mode ${k + 1}`);
    assert.equal(options[k].text, labels[k].label);
    assert.equal(m.animated, !m.rigid, `mode ${k + 1}: every non-rigid mode moves a body`);
    assert.ok(options[k].text.includes(m.rigid ? `frees ${m.frees}` : m.stable ? 'stable' : 'UNSTABLE'), options[k].text);
  });
  // Table 2 of Meijaard et al. (2007) at 2 m/s: the capsize and castering modes decay, the
  // weave pair grows (Re λ = 2.68 1/s): each looped until its amplitude has changed tenfold,
  // ending at full size for the growing one (and less than one period of the weave).
  const animated = data.modes.map((m, k) => [m, k]).filter(([m]) => m.animated);
  assert.equal(animated.length, 3);
  for (const [m, k] of animated) {
    const [sigma, omega] = m.eigenvalue;
    const fade = Math.log(10) / Math.abs(sigma);
    if (sigma > 0) assert.deepEqual([Math.abs(m.loop[0] + fade) <= 1e-12 * fade, m.loop[1]], [true, 0]);
    else assert.deepEqual([m.loop[0], Math.abs(m.loop[1] - fade) <= 1e-12 * fade], [0, true]);
    assert.equal(m.shown, omega > 0 ? (sigma > 0 ? 'growing oscillation' : 'decaying oscillation') : sigma > 0 ? 'growth' : 'decay');
    if (omega > 0) assert.ok(fade < (2 * Math.PI) / omega);
    // Chosen in the selector as a reader would; every body's pose as worked out from the data.
    await page.select('#mode', String(k));
    assert.equal(await page.evaluate(() => window.chasles.mode), k);
    for (const f of [0, 0.37, 1]) {
      const t = m.loop[0] + f * (m.loop[1] - m.loop[0]);
      await page.evaluate((x) => window.chasles.seek(x), t);
      for (const b of data.bodies) {
        const pose = await page.evaluate((name) => window.chasles.bodyPose(name), b.name);
        const base = data.poses.find((p) => p.name === b.name);
        const motion = m.bodies.find((x) => x.name === b.name);
        const gap = poseGap(pose, expectedModePose(base, b.center_of_mass, motion, m.eigenvalue, t));
        assert.ok(gap.position <= 1e-9 && gap.quaternion <= 1e-9, `mode ${k + 1}, ${b.name}, t = ${t}`);
      }
    }
  }
  // A rigid mode cannot be chosen.
  const rigid = data.modes.findIndex((m) => m.rigid);
  assert.equal(await page.evaluate((k) => { try { window.chasles.selectMode(k); return 'chosen'; } catch (e) { return 'refused'; } }, rigid), 'refused');
  const note = await page.$eval('#amplitude', (e) => e.textContent);
  assert.ok(note.includes("10 % of the scene's size"), note);
  await checkNotBlank(page);
  assert.deepEqual(problems, []);
  await page.close();
});
