// Time-series plots (uPlot), each with the events marked, the replay time as a cursor line
// and, for contacts, each point's regime as coloured bands.
import uPlot from 'uplot';

const SERIES_COLORS = [
  '#4e79a7', '#f28e2b', '#e15759', '#76b7b2', '#59a14f', '#edc948', '#b07aa1', '#ff9da7',
  '#9c755f', '#bab0ac',
];
export const MODE_COLORS = ['rgba(150,150,150,0.55)', 'rgba(224,123,0,0.7)', 'rgba(46,157,58,0.7)'];
export const MODE_NAMES = ['separated', 'sliding', 'sticking'];

/** A plot's box with its title, appended to `parent`; uPlot draws into it. */
function plotBox(parent, title) {
  const box = document.createElement('div');
  box.className = 'plot';
  const head = document.createElement('div');
  head.className = 'plot-title';
  head.textContent = title;
  box.appendChild(head);
  parent.appendChild(box);
  return box;
}

/**
 * A plot of `names` (columns of `data`) against t in `parent`. `marks`: the event marks;
 * `bands`: [{name, modes: string of '0'/'1'/'2' per sample}] drawn as strips at the top.
 */
export class Plot {
  constructor(parent, data, title, names, marks, bands = []) {
    this.title = title;
    this.names = names;
    this.marks = marks;
    this.bands = bands;
    this.time = data.time;
    const box = plotBox(parent, title);
    this.box = box;
    const units = [...new Set(names.map((n) => data.byName.get(n).unit))];
    const series = [{ label: 't [s]' }];
    names.forEach((n, i) => {
      const u = data.byName.get(n).unit;
      series.push({
        label: u ? `${n} [${u}]` : n,
        stroke: SERIES_COLORS[i % SERIES_COLORS.length],
        width: 1.5,
        points: { show: false },
      });
    });
    const plotData = [Array.from(data.time), ...names.map((n) => Array.from(data.byName.get(n).values))];
    const self = this;
    const opts = {
      width: Math.max(parent.clientWidth - 16, 300),
      height: 210,
      scales: { x: { time: false } },
      series,
      axes: [{ label: 't [s]' }, { label: units.filter((u) => u).join(', ') }],
      legend: { live: true },
      cursor: { sync: { key: 'chasles' } },
      hooks: {
        draw: [(u) => self.drawOverlays(u)],
      },
    };
    this.u = new uPlot(opts, plotData, box);
    this.cursor = document.createElement('div');
    this.cursor.className = 'replay-cursor';
    this.u.over.appendChild(this.cursor);
    this.setTime(this.time.length ? this.time[0] : 0);
  }

  /** Event marks (dashed lines) and regime bands, drawn on the plot's canvas. */
  drawOverlays(u) {
    const ctx = u.ctx;
    const { left, top, width, height } = u.bbox;
    ctx.save();
    ctx.beginPath();
    ctx.rect(left, top, width, height);
    ctx.clip();
    const stripe = 6 * (window.devicePixelRatio || 1);
    this.bands.forEach((b, k) => {
      const y = top + k * (stripe + 1);
      for (let i = 0; i + 1 < this.time.length; i++) {
        const m = b.modes.charCodeAt(i) - 48;
        const x0 = u.valToPos(this.time[i], 'x', true);
        const x1 = u.valToPos(this.time[i + 1], 'x', true);
        ctx.fillStyle = MODE_COLORS[m] || MODE_COLORS[0];
        ctx.fillRect(x0, y, Math.max(x1 - x0, 0.5), stripe);
      }
    });
    ctx.setLineDash([4, 3]);
    ctx.lineWidth = 1;
    for (const m of this.marks) {
      const x = u.valToPos(m.t, 'x', true);
      ctx.strokeStyle = m.kind === 'event' ? '#b00020' : m.kind === 'impact' ? '#6a1b9a' : '#555';
      ctx.beginPath();
      ctx.moveTo(x, top);
      ctx.lineTo(x, top + height);
      ctx.stroke();
    }
    ctx.restore();
  }

  /** Moves the replay cursor to time t. */
  setTime(t) {
    const x = this.u.valToPos(t, 'x');
    this.cursor.style.left = `${x}px`;
  }

  resize(width) {
    this.u.setSize({ width: Math.max(width - 16, 300), height: 210 });
  }

  describe() {
    return { title: this.title, series: this.names.slice(), eventMarks: this.marks.map((m) => m.t) };
  }
}

/**
 * A plot of one quantity of a sweep against a swept parameter, one line (with its points) per
 * combination of the other parameters. `xs`: the parameter's values, ascending; `lines`:
 * [{label, y}] with y aligned to xs (null where the sweep has no value: a failed point).
 */
export class SweepPlot {
  constructor(parent, title, xLabel, yLabel, xs, lines) {
    this.title = title;
    this.xLabel = xLabel;
    this.xs = xs;
    this.lines = lines;
    const box = plotBox(parent, title);
    this.box = box;
    const series = [{ label: xLabel }];
    lines.forEach((l, i) => {
      const color = SERIES_COLORS[i % SERIES_COLORS.length];
      series.push({ label: l.label, stroke: color, width: 1.5, points: { show: true, size: 5, fill: color } });
    });
    this.u = new uPlot(
      {
        width: Math.max(parent.clientWidth - 16, 300),
        height: 230,
        scales: { x: { time: false } },
        series,
        axes: [{ label: xLabel }, { label: yLabel }],
        legend: { live: true },
      },
      [xs, ...lines.map((l) => l.y)],
      box,
    );
  }

  resize(width) {
    this.u.setSize({ width: Math.max(width - 16, 300), height: 230 });
  }

  describe() {
    return {
      title: this.title,
      x: this.xLabel,
      series: this.lines.map((l) => l.label),
      xs: this.xs.slice(),
      ys: this.lines.map((l) => l.y.slice()),
      eventMarks: [],
    };
  }
}
