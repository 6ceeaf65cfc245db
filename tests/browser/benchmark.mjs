// The browser report's size and load time for a large run (docs/benchmarks.md, "Browser
// report"): ten tumbling boxes, 10,001 samples, written with --html, then opened in headless
// Chromium until window.chasles.ready. Usage: node benchmark.mjs SOURCE_DIR CHASLES_BINARY
import { createRequire } from 'node:module';
import { mkdtempSync, writeFileSync, statSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { execFileSync } from 'node:child_process';
import { pathToFileURL } from 'node:url';

const [source, chasles] = process.argv.slice(2).map((p) => resolve(p));
const require = createRequire(join(source, 'report/package.json'));
const puppeteer = require('puppeteer-core');
const work = mkdtempSync(join(tmpdir(), 'chasles-bench-'));

// Ten free boxes thrown with different spins under gravity: 10 bodies, 10 s at 1 ms.
let yaml = 'chasles: 1\ntitle: "Ten tumbling boxes"\nbodies:\n';
for (let k = 0; k < 10; k++) {
  yaml += `  - name: box${k}
    parts: [{shape: box, size: [${0.1 + 0.01 * k} m, 0.2 m, 0.3 m], mass: 1 kg}]
    initial: {position: [${k} m, 0, 0], velocity: [0, 1 m/s, 5 m/s], angular_velocity: [${1 + k} rad/s, 0.1 rad/s, ${0.5 * k} rad/s]}
`;
}
yaml += 'gravity: standard\nsimulation: {until: 10 s, tolerance: 1e-10, output_interval: 1 ms}\n';
writeFileSync(join(work, 'boxes.yaml'), yaml);
const html = join(work, 'boxes.html');
let t = performance.now();
execFileSync(chasles, ['simulate', join(work, 'boxes.yaml'), '--out', work, '--html', html, '--quiet'], { stdio: 'ignore' });
const simulate = (performance.now() - t) / 1000;
const size = statSync(html).size;

const browser = await puppeteer.launch({
  executablePath: process.env.CHASLES_CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
});
const times = [];
for (let run = 0; run < 3; run++) {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 760 });
  t = performance.now();
  await page.goto(pathToFileURL(html).href, { waitUntil: 'domcontentloaded' });
  await page.waitForFunction('window.chasles && window.chasles.ready', { timeout: 60000, polling: 10 });
  times.push((performance.now() - t) / 1000);
  const samples = await page.evaluate(() => window.chasles.data.samples);
  if (samples !== 10001) throw new Error(`expected 10001 samples, got ${samples}`);
  await page.close();
}
await browser.close();
rmSync(work, { recursive: true, force: true });
console.log(`simulate --html: ${simulate.toFixed(2)} s`);
console.log(`report size: ${(size / 1e6).toFixed(2)} MB (${size} bytes)`);
console.log(`time to window.chasles.ready: ${times.map((x) => x.toFixed(2)).join(', ')} s`);
