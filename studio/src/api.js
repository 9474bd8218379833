// The client of the studio server's API (python/mrepair/studio/server.py).
import { decodeBinaryMesh, decodeOverlay } from './payload.js';

async function check(r) {
  if (r.ok) return r;
  let message = `${r.status} ${r.statusText}`;
  try { message = (await r.json()).error || message; } catch (e) { /* not JSON */ }
  throw new Error(message);
}

export async function getJSON(path) {
  return (await check(await fetch(path))).json();
}

export async function postJSON(path, body) {
  const r = await fetch(path, { method: 'POST', headers: { 'Content-Type': 'application/json' },
                                body: JSON.stringify(body || {}) });
  return (await check(r)).json();
}

// which: 'before' | 'after'
export async function getMesh(which) {
  const r = await check(await fetch(`/api/mesh/${which}`));
  return decodeBinaryMesh(await r.arrayBuffer());
}

export async function getDefects(which) {
  return decodeOverlay(await getJSON(`/api/defects/${which}`));
}

export const api = {
  state: () => getJSON('/api/state'),
  run: (settings) => postJSON('/api/run', settings),
  remesh: (settings) => postJSON('/api/remesh', settings),
  gapInit: (settings) => postJSON('/api/gap/init', settings),
  gapMove: (move) => postJSON('/api/gap/move', move),
  reset: () => postJSON('/api/reset', {}),
  exportUrl: (which, format) => `/api/export/${which}?format=${encodeURIComponent(format)}`,
};
