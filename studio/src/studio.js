// The live studio page (index.html): the viewer and the panels wired to the
// studio server's API. window.studio is what the browser tests drive.
import './style.css';
import { Viewer } from './viewer.js';
import { DefectPanel, renderReport, viewControls, el, fmt } from './panels.js';
import { api, getMesh, getDefects } from './api.js';
import { meshHash } from './payload.js';
import * as settings from './settings.js';

const $ = (id) => document.getElementById(id);

// the cleaning steps of `mrepair clean --only/--skip`, in pipeline order
const CLEAN_STEPS = ['remove_degenerate_vertices', 'relax_spikes', 'remove_unrelaxable_spikes',
  'clean_boundaries', 'remove_small_components', 'fill_small_holes', 'fix_near_degenerate_faces',
  'relax_spikes_again', 'ensure_valid_mesh'];

const viewer = new Viewer($('view'));
new DefectPanel($('defects'), viewer);
viewControls(viewer, $('viewbar'), $('labels'), $('notes'));

const forms = ['repair-form', 'gap-form', 'remesh-form', 'export-form'].map($);
const studio = { viewer, busy: 0, timings: {}, errors: [], state: null, reports: {}, ready: false };
window.studio = studio;

function status(text, kind = 'info') {
  $('status').replaceChildren(el('span', { class: kind }, text));
  if (kind === 'error') studio.errors.push(text);
}

// runs an action with the buttons disabled, its error on the status line
async function busy(label, f) {
  studio.busy++;
  document.body.classList.add('busy');
  if (label) status(label + '…');
  try {
    return await f();
  } catch (e) {
    status(e.message || String(e), 'error');
    return undefined;
  } finally {
    studio.busy--;
    if (!studio.busy) document.body.classList.remove('busy');
  }
}

function showReports() {
  const parts = [];
  if (studio.reports.after) parts.push(renderReport(studio.reports.after, studio.reports.afterTitle || 'result'));
  if (studio.reports.before) parts.push(renderReport(studio.reports.before, 'input (inspect)'));
  $('report').replaceChildren(...parts);
}

async function loadSide(side, withDefects = true) {
  const mesh = await getMesh(side);
  viewer.setMesh(side, mesh);
  if (withDefects) viewer.setDefects(side, await getDefects(side));
  return mesh;
}

// after a job: the new mesh drawn first (timed), then its defects and report
async function showResult(res, label, t0) {
  const mesh = await getMesh('after');
  viewer.setMesh('after', mesh);
  viewer.renderNow();
  const drawn = performance.now();
  studio.reports.after = res.report;
  studio.reports.afterTitle = label;
  showReports();
  viewer.setDefects('after', await getDefects('after'));
  viewer.renderNow();
  const t = { total_ms: drawn - t0, server_ms: res.seconds * 1000, faces: mesh.faces,
              drawn_faces: mesh.indices.length / 3, defects_ms: performance.now() - drawn };
  studio.timings[label] = t;
  status(`${label}: ${fmt(mesh.faces)} faces; click → redrawn mesh ${(t.total_ms / 1000).toFixed(2)} s ` +
         `(library ${res.seconds.toFixed(2)} s), defects +${(t.defects_ms / 1000).toFixed(2)} s`);
}

// ---- repair panel -------------------------------------------------------------------------------
$('steps').append(...CLEAN_STEPS.map((s) =>
  el('label', { class: 'step' }, el('input', { type: 'checkbox', name: 'step_' + s, checked: true }), s.replaceAll('_', ' '))));
function updateRepairForm() {
  const clean = $('repair-form').elements.mode.value === 'clean';
  for (const e of document.querySelectorAll('.clean-only')) e.classList.toggle('off', !clean);
  for (const e of document.querySelectorAll('.repair-only')) e.classList.toggle('off', clean);
}
$('repair-form').elements.mode.addEventListener('change', updateRepairForm);
$('repair-form').addEventListener('submit', (e) => {
  e.preventDefault();
  const v = settings.formValues($('repair-form'));
  const body = { mode: v.mode, profile: v.profile, params: {}, skip: [] };
  for (const [k, x] of Object.entries(v)) {
    // the steps are chosen one by one for the clean job only (repair runs its profile's)
    if (k.startsWith('step_')) { if (!x && v.mode === 'clean') body.skip.push(k.slice(5)); } else if (k !== 'mode' && k !== 'profile') body.params[k] = x;
  }
  busy('running ' + v.mode, async () => {
    const t0 = performance.now();
    const res = await api.run(body);
    await showResult(res, v.mode, t0);
  });
});

// ---- gap-closing scrubber -----------------------------------------------------------------------
const slider = $('gap-slider');
let gapQueue = null, gapRunning = false;
function gapStatus(g) {
  studio.gap = g;
  $('gap-status').textContent = `${fmt(g.position)} contractions (${fmt(g.size)} found so far), ` +
    `closing distance ${g.current_distance.toPrecision(4)} of ${g.max_distance.toPrecision(4)}, ${fmt(g.faces)} faces`;
  status(`gap closing: ${fmt(g.position)} contractions applied` + (g.position === 0 ? ' (the input)' : ''));
}
// moves the sequence; the latest request wins while one is running
function gapMove(move) {
  gapQueue = move;
  if (gapRunning) return;
  gapRunning = true;
  studio.busy++;
  (async () => {
    try {
      while (gapQueue) {
        const m = gapQueue;
        gapQueue = null;
        const g = await api.gapMove(m);
        gapStatus(g);
        if (m.distance === undefined) slider.value = String(g.current_distance);
        viewer.setDefects('after', null);
        viewer.setMesh('after', await getMesh('after'));
      }
    } catch (e) {
      status(e.message, 'error');
    } finally {
      gapRunning = false;
      studio.busy--;
    }
  })();
}
$('gap-form').addEventListener('submit', (e) => {
  e.preventDefault();
  const v = settings.formValues($('gap-form'));
  busy('building the gap-closing sequence', async () => {
    const g = await api.gapInit({ tolerance: v.tolerance, relative: v.relative, lambda_: v.lambda_, source: v.source });
    slider.max = String(g.max_distance);
    slider.step = String(g.max_distance / 1000 || 1);
    slider.value = '0';
    slider.disabled = false;
    gapStatus(g);
    studio.reports.after = null;
    showReports();
    viewer.setDefects('after', null);
    viewer.setMesh('after', await getMesh('after'));
    status(`gap-closing sequence up to distance ${g.max_distance.toPrecision(4)}: move the slider`);
  });
});
slider.addEventListener('input', () => gapMove({ distance: Number(slider.value) }));
slider.addEventListener('change', () => busy(null, async () => {
  while (gapRunning || gapQueue) await new Promise((r) => setTimeout(r, 20));
  viewer.setDefects('after', await getDefects('after'));
}));
$('gap-back').addEventListener('click', () => gapMove({ backward: 1 }));
$('gap-forward').addEventListener('click', () => gapMove({ forward: 1 }));

// ---- remeshing ----------------------------------------------------------------------------------
$('remesh-form').addEventListener('submit', (e) => {
  e.preventDefault();
  const v = settings.formValues($('remesh-form'));
  busy('remeshing', async () => {
    const t0 = performance.now();
    const res = await api.remesh(v);
    await showResult(res, 'remesh', t0);
  });
});

// ---- export, PNG, settings ----------------------------------------------------------------------
function download(href, name) {
  const a = el('a', { href, download: name });
  document.body.append(a);
  a.click();
  a.remove();
}
$('export-form').addEventListener('submit', (e) => {
  e.preventDefault();
  const v = settings.formValues($('export-form'));
  if (v.which === 'after' && !viewer.sides.after.mesh) { status('no result to export yet', 'error'); return; }
  download(api.exportUrl(v.which, v.format), `${v.which}.${v.format}`);
});
// the PNG carries the settings (a tEXt chunk), which Load settings reads back
$('png').addEventListener('click', () => {
  const bytes = Uint8Array.from(atob(viewer.png().split(',')[1]), (c) => c.charCodeAt(0));
  const png = settings.pngWithSettings(bytes, settings.collect(forms, viewer));
  download(URL.createObjectURL(new Blob([png], { type: 'image/png' })), 'mrepair-view.png');
});
$('save-settings').addEventListener('click', () => {
  const blob = new Blob([JSON.stringify(settings.collect(forms, viewer), null, 2)], { type: 'application/json' });
  download(URL.createObjectURL(blob), 'mrepair-settings.json');
});
$('load-settings').addEventListener('change', async (e) => {
  const file = e.target.files[0];
  if (!file) return;
  try {
    const bytes = new Uint8Array(await file.arrayBuffer());
    const loaded = settings.isPng(bytes) ? settings.settingsFromPng(bytes) : JSON.parse(new TextDecoder().decode(bytes));
    if (!loaded) throw new Error('this PNG holds no mrepair settings');
    settings.apply(loaded, forms, viewer);
    updateRepairForm();
    status(`settings loaded from ${file.name}`);
  } catch (err) {
    status(`${file.name}: ${err.message}`, 'error');
  }
  e.target.value = '';
});

// ---- for the tests ------------------------------------------------------------------------------
studio.meshHash = (side) => meshHash(viewer.sides[side].meshData);
studio.counts = (side) => Object.fromEntries(
  [...document.querySelectorAll(`#defects button.count[data-side=${side}]`)].map((b) => [b.dataset.kind, Number(b.textContent.replace(/[,*]/g, ''))]));
studio.settings = () => settings.collect(forms, viewer);

// ---- start --------------------------------------------------------------------------------------
busy('loading', async () => {
  const st = await api.state();
  studio.state = st;
  document.title = `${st.title} – mrepair studio`;
  $('title').textContent = `${st.title}: ${fmt(st.vertices)} vertices, ${fmt(st.faces)} faces`;
  $('repair-form').elements.mode.value = st.manifold ? 'clean' : 'repair';
  if (st.settings) settings.apply(st.settings, forms, viewer);
  updateRepairForm();
  studio.reports.before = st.report;
  showReports();
  await loadSide('before');
  viewer.frameAll();
  status(`${st.title} loaded`);
}).finally(() => { studio.ready = true; });
