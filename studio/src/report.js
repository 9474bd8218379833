// The self-contained HTML report (report_template.html): the payload that
// `mrepair repair --html` or mrepair.html_report() put in the page, shown with
// the studio's viewer and panels. No server, no network.
import './style.css';
import { Viewer } from './viewer.js';
import { DefectPanel, renderReport, viewControls, el, fmt } from './panels.js';
import { decodePayloadMesh, decodeOverlay } from './payload.js';

const $ = (id) => document.getElementById(id);
const report = { ready: false, errors: [] };
window.mrepairReport = report;

function fail(message) {
  report.errors.push(message);
  $('status').replaceChildren(el('span', { class: 'error' }, message));
}

let payload = null;
try {
  const text = $('mrepair-payload').textContent.trim();
  if (text.startsWith('/*')) throw new Error('this is the report template: it holds no report (the placeholder was not replaced)');
  payload = JSON.parse(text);
  if (payload.version !== 1) throw new Error(`payload version ${payload.version}: this page reads version 1`);
} catch (e) {
  fail(e.message);
}

if (payload) {
  const viewer = new Viewer($('view'));
  report.viewer = viewer;
  new DefectPanel($('defects'), viewer);
  viewControls(viewer, $('viewbar'), $('labels'), $('notes'));
  document.title = `${payload.title} – mrepair report`;
  for (const side of ['before', 'after']) {
    const m = payload.meshes && payload.meshes[side];
    if (m) viewer.setMesh(side, decodePayloadMesh(m));
    const d = payload.defects && payload.defects[side];
    if (d) viewer.setDefects(side, decodeOverlay(d));
  }
  const faces = (s) => (payload.meshes[s] ? fmt(payload.meshes[s].faces) : '–');
  $('title').textContent = `${payload.title}: ${faces('before')} → ${faces('after')} faces`;
  $('report').replaceChildren(renderReport(payload.report, 'repair report'));
  $('settings').replaceChildren(renderReport(payload.settings || {}, 'settings'));
  viewer.frameAll();
  report.counts = (side) => Object.fromEntries(
    [...document.querySelectorAll(`#defects button.count[data-side=${side}]`)].map((b) => [b.dataset.kind, Number(b.textContent.replace(/[,*]/g, ''))]));
  $('status').textContent = 'mrepair report: drag to orbit, wheel to zoom; W wireframe, S side by side, T before/after';
}
report.ready = true;
