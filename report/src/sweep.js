// The report of a sweep (docs/report.md, "Sweeps"): each quantity plotted against a swept
// parameter, one line per combination of the others; the scene drawn at its own parameter
// values; the failed points listed with their reasons.
import { SweepPlot } from './plots.js';

/** The sweep's table as columns: parameters, quantities, rows (null for a failed value). */
export function sweepTable(sweep) {
  const params = sweep.parameters && sweep.parameters.length ? sweep.parameters : [sweep.columns[0]];
  const unit = (c) => (sweep.column_units ? sweep.column_units[c] : '');
  const columns = sweep.columns.map((name, c) => ({
    name,
    unit: unit(c),
    label: unit(c) ? `${name} [${unit(c)}]` : name,
    values: sweep.rows.map((r) => (r[c] === null || r[c] === undefined ? null : r[c])),
  }));
  return {
    params: columns.slice(0, params.length),
    quantities: columns.slice(params.length),
    rows: sweep.rows.length,
    errors: sweep.errors || [],
  };
}

/**
 * Plot data of `quantity` against parameter `x`: xs ascending (every value the parameter takes)
 * and one line per combination of the other parameters, in the order the table first has it
 * (at most `maxLines`; `dropped` says how many more there were).
 */
export function sweepLines(table, x, quantity, maxLines = 12) {
  const xs = [...new Set(x.values)].sort((a, b) => a - b);
  const others = table.params.filter((p) => p !== x);
  const groups = new Map();
  for (let r = 0; r < table.rows; r++) {
    const key = others.map((p) => p.values[r]).join('\u0000');
    if (!groups.has(key)) {
      const label = others.length
        ? others.map((p) => `${p.name} = ${Number(p.values[r].toPrecision(6))}${p.unit ? ` ${p.unit}` : ''}`).join(', ')
        : quantity.label;
      groups.set(key, { label, y: new Array(xs.length).fill(null) });
    }
    groups.get(key).y[xs.indexOf(x.values[r])] = quantity.values[r];
  }
  const all = [...groups.values()];
  return { xs, lines: all.slice(0, maxLines), dropped: Math.max(all.length - maxLines, 0) };
}

/**
 * The quantities plotted at first: all when few; else those that vary, at most `n`: forces and
 * contact regimes first, then accelerations, then the rest. A column varies when its range is
 * more than 1e-9 of the largest value of any column of its unit (round-off next to zero, such
 * as an acceleration out of the plane of motion, does not).
 */
export function defaultQuantities(table, n = 8) {
  if (table.quantities.length <= n) return table.quantities;
  const finite = (q) => q.values.filter((x) => x !== null);
  const scale = new Map();
  for (const q of table.quantities) {
    const m = Math.max(0, ...finite(q).map(Math.abs));
    scale.set(q.unit, Math.max(scale.get(q.unit) || 0, m));
  }
  const varying = table.quantities.filter((q) => {
    const v = finite(q);
    if (!v.length) return false;
    return Math.max(...v) - Math.min(...v) > 1e-9 * Math.max(scale.get(q.unit), 1e-300);
  });
  const rank = (q) => (/_(N|f|f_over_N|mode|F[xyz]|M[xyz])$/.test(q.name) ? 0 : /_(a[xyz]|al[xyz]|a_[xy]|alpha)$/.test(q.name) ? 1 : 2);
  return varying
    .map((q, i) => ({ q, i }))
    .sort((a, b) => rank(a.q) - rank(b.q) || a.i - b.i)
    .slice(0, n)
    .map((x) => x.q);
}

/** Fills the side panel with the sweep's plots; returns the plots (for the page's API). */
export function sweepPlots(data, side, el) {
  const table = sweepTable(data.sweep);
  const failed = table.errors.filter((e) => e).length;
  const what = { simulate: 'runs', mass: 'mass properties', solve: 'instantaneous solves' }[data.command] || data.command;
  side.append(
    el('h2', {}, `Sweep of ${table.params.map((p) => p.name).join(' × ')}: ${table.rows} ${what}${failed ? `, ${failed} failed` : ''}`),
  );
  const plots = [];
  const xPicker = el('select', { id: 'sweep-x' });
  for (const p of table.params) xPicker.append(el('option', { value: p.name }, p.label));
  xPicker.value = table.params[table.params.length - 1].name;
  const qPicker = el('select', { id: 'column-picker' });
  for (const q of table.quantities) qPicker.append(el('option', { value: q.name }, q.label));
  const addButton = el('button', { type: 'button', id: 'add-plot' }, 'Plot');
  side.append(el('div', { class: 'picker' }, el('label', {}, 'against ', xPicker), el('label', {}, 'quantity ', qPicker), addButton));
  const area = el('div', { id: 'plots' });
  side.append(area);
  const shown = [];
  const draw = () => {
    area.replaceChildren();
    plots.length = 0;
    const x = table.params.find((p) => p.name === xPicker.value);
    for (const q of shown) {
      const { xs, lines, dropped } = sweepLines(table, x, q);
      plots.push(new SweepPlot(area, `${q.label} against ${x.name}`, x.label, q.label, xs, lines));
      if (dropped) area.append(el('p', { class: 'note' }, `${dropped} more lines not drawn (the first ${lines.length} shown); plot against another parameter to see them.`));
    }
  };
  shown.push(...defaultQuantities(table));
  draw();
  xPicker.addEventListener('change', draw);
  addButton.addEventListener('click', () => {
    const q = table.quantities.find((c) => c.name === qPicker.value);
    if (q && !shown.includes(q)) shown.push(q);
    draw();
  });
  if (failed) {
    const list = el('ul', { class: 'events' });
    table.errors.forEach((e, r) => {
      if (!e) return;
      const at = table.params.map((p) => `${p.name} = ${Number(p.values[r].toPrecision(9))}`).join(', ');
      list.append(el('li', {}, `${at}: ${e}`));
    });
    side.append(el('h2', {}, 'Failed points (left out of the plots)'), list);
  }
  window.addEventListener('resize', () => plots.forEach((p) => p.resize(area.clientWidth)));
  return plots;
}
