// DOM panels shared by the studio and the HTML report: the defect table
// (visibility toggles, counts per side, click to fly to the first instance),
// the report tables and the on-screen notes.
import { KINDS } from './defects.js';

export function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else if (v !== undefined && v !== null && v !== false) e.setAttribute(k, v === true ? '' : v);
  }
  for (const c of children.flat(Infinity)) if (c !== null && c !== undefined) e.append(c);
  return e;
}

export const fmt = (n) => (n === null || n === undefined ? '–' : Number(n).toLocaleString('en-US'));

// The defect table. viewer: Viewer. Rebuilt on every viewer change.
export class DefectPanel {
  constructor(container, viewer) {
    this.container = container;
    this.viewer = viewer;
    this.visible = Object.fromEntries(KINDS.map(([k]) => [k, true]));
    viewer.onChange(() => this.update());
    this.update();
  }

  update() {
    const sides = ['before', 'after'].filter((s) => this.viewer.sides[s].defects);
    const rows = KINDS.map(([key, label, color]) => {
      const cells = sides.map((side) => {
        const k = this.viewer.sides[side].defects.kinds[key];
        if (!k) return el('td', { class: 'count' }, '–');
        const title = k.first ? `fly to the first of the ${side} ${label}` +
          (k.truncated ? ` (${fmt(k.drawn)} drawn)` : '') : '';
        return el('td', {},
          el('button', { class: 'count' + (k.count ? ' nonzero' : ''), 'data-kind': key,
                         'data-side': side, title, disabled: !k.first,
                         onclick: () => k.first && this.viewer.flyTo(k.first, k.firstRadius) },
             fmt(k.count) + (k.truncated ? '*' : '')));
      });
      const box = el('input', { type: 'checkbox', 'data-kind': key, checked: this.visible[key],
        onchange: (e) => { this.visible[key] = e.target.checked; this.viewer.setKindVisible(key, e.target.checked); } });
      return el('tr', {}, el('td', {}, el('label', {}, box, el('span', { class: 'swatch', style: `background:${color}` }), label)), cells);
    });
    const head = el('tr', {}, el('th', {}, 'defect'), sides.map((s) => el('th', {}, s)));
    this.container.replaceChildren(el('table', { class: 'defects' }, el('thead', {}, head), el('tbody', {}, rows)),
      el('p', { class: 'hint' }, 'click a count to fly to the first instance; * = not all drawn'));
  }
}

// A report object (the JSON of the mrepair commands) as nested tables: a
// section per object, scalars as key/value rows, arrays of scalars joined.
export function renderReport(report, title = 'report') {
  const scalar = (v) => (v === null ? 'null' : typeof v === 'number' ? fmt(Number.isInteger(v) ? v : Number(v.toPrecision(6))) : String(v));
  const table = (obj) => {
    const rows = [], sub = [];
    for (const [k, v] of Object.entries(obj)) {
      if (v && typeof v === 'object' && !Array.isArray(v)) sub.push([k, v]);
      else if (Array.isArray(v) && v.some((x) => x && typeof x === 'object')) {
        v.forEach((x, i) => sub.push([`${k}[${i}]`, x && typeof x === 'object' ? x : { value: x }]));
      } else rows.push(el('tr', {}, el('td', {}, k), el('td', { 'data-key': k }, Array.isArray(v) ? v.map(scalar).join(', ') : scalar(v))));
    }
    return [rows.length ? el('table', { class: 'kv' }, el('tbody', {}, rows)) : null,
            sub.map(([k, v]) => el('details', { 'data-section': k }, el('summary', {}, k), table(v)))];
  };
  return el('details', { class: 'report', open: true }, el('summary', {}, title), table(report || {}));
}

// One line of notes under the view (decimated previews, truncated layers).
export function meshNotes(viewer) {
  const notes = [];
  for (const side of ['before', 'after']) {
    const m = viewer.sides[side].meshData;
    if (m && m.decimated) {
      notes.push(`${side}: decimated preview, ${fmt(m.indices.length / 3)} of ${fmt(m.faces)} faces drawn`);
    }
  }
  return notes;
}

// The view bar: flat/wireframe, split/single, before/after, frame; keys W, S, T, F.
export function viewControls(viewer, bar, labels, notes) {
  const wire = el('button', { id: 'wireframe', title: 'W', onclick: () => viewer.setWireframe(!viewer.wireframe) });
  const layout = el('button', { id: 'layout', title: 'S', onclick: () => viewer.setLayout(viewer.layout === 'split' ? 'single' : 'split') });
  const toggle = el('button', { id: 'toggle', title: 'T', onclick: () => viewer.toggleShown() }, 'before/after (T)');
  const frame = el('button', { id: 'frame', title: 'F', onclick: () => viewer.frameAll() }, 'frame (F)');
  bar.replaceChildren(wire, layout, toggle, frame);
  const update = () => {
    wire.textContent = viewer.wireframe ? 'flat (W)' : 'wireframe (W)';
    layout.textContent = viewer.layout === 'split' ? 'single (S)' : 'side by side (S)';
    const sides = viewer.visibleSides();
    // the side's name and its size (thesis 4.6: the counts are in the viewing area)
    labels.replaceChildren(...sides.map((s) => {
      const m = viewer.sides[s].meshData;
      const size = m ? `${fmt(m.decimated ? m.faces : m.indices.length / 3)} faces` +
        (m.decimated ? '' : `, ${fmt(m.positions.length / 3)} vertices`) : '';
      return el('span', { class: 'side-label' }, s, el('small', {}, size));
    }));
    labels.style.gridTemplateColumns = `repeat(${sides.length}, 1fr)`;
    const n = meshNotes(viewer);
    notes.replaceChildren(...n.map((t) => el('div', { class: 'note' }, t)));
  };
  viewer.onChange(update);
  update();
  window.addEventListener('keydown', (e) => {
    if (e.target && ['INPUT', 'SELECT', 'TEXTAREA'].includes(e.target.tagName)) return;
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const k = e.key.toLowerCase();
    if (k === 'w') wire.click();
    else if (k === 's') layout.click();
    else if (k === 't') toggle.click();
    else if (k === 'f') frame.click();
  });
}
