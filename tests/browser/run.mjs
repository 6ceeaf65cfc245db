// Runs the browser tests of the report (report.test.mjs) with node's test runner, or exits 77
// (ctest: skipped) when headless Chromium or the packages of report/ are missing.
// Usage: node run.mjs SOURCE_DIR CHASLES_BINARY
import { existsSync } from 'node:fs';
import { join, dirname } from 'node:path';
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const [source, chasles] = process.argv.slice(2);
const chromium = process.env.CHASLES_CHROMIUM || '/usr/bin/chromium';
const missing = [];
if (!existsSync(chromium)) missing.push(`${chromium} (apt package chromium)`);
if (!existsSync(join(source, 'report/node_modules/puppeteer-core/package.json'))) {
  missing.push('report/node_modules/puppeteer-core (scripts/setup.sh runs npm ci in report/)');
}
if (missing.length) {
  console.log(`browser tests skipped: missing ${missing.join(', ')}`);
  process.exit(77);
}
const test = join(dirname(fileURLToPath(import.meta.url)), 'report.test.mjs');
const r = spawnSync(process.execPath, ['--test', '--test-reporter=spec', test], {
  stdio: 'inherit',
  env: { ...process.env, CHASLES_SOURCE: source, CHASLES: chasles, CHASLES_CHROMIUM: chromium },
});
process.exit(r.status === null ? 1 : r.status);
