// The studio's settings: every named control of the panels' forms, as one JSON
// object {version, forms: {formId: {name: value}}, view: {...}} that can be
// saved and loaded again.

export const SETTINGS_VERSION = 1;

export function formValues(form) {
  const out = {};
  for (const e of form.elements) {
    if (!e.name) continue;
    if (e.type === 'checkbox') out[e.name] = e.checked;
    else if (e.type === 'number') out[e.name] = e.value === '' ? null : Number(e.value);
    else out[e.name] = e.value;
  }
  return out;
}

export function setFormValues(form, values) {
  for (const e of form.elements) {
    if (!e.name || !(e.name in values)) continue;
    const v = values[e.name];
    if (e.type === 'checkbox') e.checked = !!v;
    else e.value = v === null || v === undefined ? '' : String(v);
  }
}

export function collect(forms, viewer) {
  const s = { version: SETTINGS_VERSION, forms: {}, view: {} };
  for (const f of forms) s.forms[f.id] = formValues(f);
  s.view = { wireframe: viewer.wireframe, layout: viewer.layout, shown: viewer.shown,
             hidden: [...viewer.sides.before.hidden] };
  return s;
}

export function apply(settings, forms, viewer) {
  if (!settings || typeof settings !== 'object' || settings.version !== SETTINGS_VERSION) {
    throw new Error('not an mrepair studio settings file (version ' + SETTINGS_VERSION + ')');
  }
  for (const f of forms) if (settings.forms && settings.forms[f.id]) setFormValues(f, settings.forms[f.id]);
  const v = settings.view || {};
  if (v.layout) viewer.setLayout(v.layout);
  if (v.shown) viewer.shown = v.shown;
  if (typeof v.wireframe === 'boolean') viewer.setWireframe(v.wireframe);
  if (Array.isArray(v.hidden)) {
    for (const b of document.querySelectorAll('#defects input[type=checkbox]')) {
      const on = !v.hidden.includes(b.dataset.kind);
      if (b.checked !== on) { b.checked = on; b.dispatchEvent(new Event('change')); }
    }
  }
}

// ---- settings inside a PNG (thesis 4.6: "a PNG image with metadata containing the current
// settings"): a tEXt chunk with the keyword "mrepair-settings" and the JSON after IHDR.
const PNG_KEY = 'mrepair-settings';
let crcTable = null;
function crc32(bytes) {
  if (!crcTable) {
    crcTable = new Uint32Array(256);
    for (let n = 0; n < 256; n++) {
      let c = n;
      for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
      crcTable[n] = c >>> 0;
    }
  }
  let c = 0xffffffff;
  for (const b of bytes) c = crcTable[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

// png: Uint8Array of a PNG file; returns a new one with the settings in a tEXt chunk
export function pngWithSettings(png, settingsObject) {
  // tEXt is Latin-1: the JSON is escaped to ASCII
  const json = JSON.stringify(settingsObject).replace(/[\u0080-\uffff]/g, (c) => '\\u' + c.charCodeAt(0).toString(16).padStart(4, '0'));
  const data = new TextEncoder().encode(PNG_KEY + '\0' + json);
  const chunk = new Uint8Array(12 + data.length);
  const view = new DataView(chunk.buffer);
  view.setUint32(0, data.length);
  chunk.set(new TextEncoder().encode('tEXt'), 4);
  chunk.set(data, 8);
  view.setUint32(8 + data.length, crc32(chunk.subarray(4, 8 + data.length)));
  const ihdrEnd = 8 + 12 + new DataView(png.buffer, png.byteOffset).getUint32(8);
  const out = new Uint8Array(png.length + chunk.length);
  out.set(png.subarray(0, ihdrEnd), 0);
  out.set(chunk, ihdrEnd);
  out.set(png.subarray(ihdrEnd), ihdrEnd + chunk.length);
  return out;
}

// the settings of a PNG written by pngWithSettings, or null
export function settingsFromPng(png) {
  const view = new DataView(png.buffer, png.byteOffset, png.byteLength);
  for (let at = 8; at + 12 <= png.length;) {
    const length = view.getUint32(at);
    const type = String.fromCharCode(...png.subarray(at + 4, at + 8));
    if (type === 'tEXt') {
      const text = new TextDecoder('latin1').decode(png.subarray(at + 8, at + 8 + length));
      if (text.startsWith(PNG_KEY + '\0')) return JSON.parse(text.slice(PNG_KEY.length + 1));
    }
    if (type === 'IEND') break;
    at += 12 + length;
  }
  return null;
}

export function isPng(bytes) {
  return bytes.length > 8 && bytes[0] === 0x89 && bytes[1] === 0x50 && bytes[2] === 0x4e && bytes[3] === 0x47;
}
