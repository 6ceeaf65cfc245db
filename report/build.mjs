// Bundles the browser report: src/main.js with three.js, its OrbitControls and uPlot into one
// minified IIFE script, and uPlot's CSS with src/report.css into one style sheet. The program
// embeds both (cmake/report.cmake). Usage: node build.mjs OUT.js OUT.css
import { build } from 'esbuild';
import { readFileSync, writeFileSync, mkdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const [outJs = join(here, 'dist/report.js'), outCss = join(here, 'dist/report.css')] =
  process.argv.slice(2);
mkdirSync(dirname(outJs), { recursive: true });
mkdirSync(dirname(outCss), { recursive: true });
await build({
  entryPoints: [join(here, 'src/main.js')],
  bundle: true,
  minify: true,
  format: 'iife',
  target: 'es2020',
  legalComments: 'none',
  outfile: outJs,
  logLevel: 'warning',
});
const css =
  readFileSync(join(here, 'node_modules/uplot/dist/uPlot.min.css'), 'utf8') +
  '\n' +
  readFileSync(join(here, 'src/report.css'), 'utf8');
writeFileSync(outCss, css);
