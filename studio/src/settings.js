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
