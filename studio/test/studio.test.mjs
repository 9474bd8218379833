// The studio's browser test (CTest `studio_browser`, label studio): Debian's
// chromium, headless, driven by playwright-core. It generates a scan with
// known defects, starts `python3 -m mrepair.studio` on it and checks, against
// the library (oracle.py):
//   1. the defect counts shown equal mrepair.inspect's
//   2. Run (clean, all steps) and Run with fill_small_holes off show the counts of
//      mrepair.clean's results, and they differ (the holes stay)
//   3. the gap-closing slider mid-way, at 0 and back: the page's mesh arrays hash
//      like the GapClosingSequence's mesh at those distances; at 0, like the input
//   4. a mesh export reads back with the result's face count; Remesh shows mrepair.remesh's mesh
//   5. settings saved and loaded back restore the controls
//   6. a PNG of the view: not blank, the defect colours present
//   7. the HTML report (CLI --html when it has it, else mrepair.html_report) shows
//      the same counts.
// Environment: MREPAIR_PYTHON, PYTHONPATH (the package), MREPAIR_GENERATE,
// MREPAIR_CLI (optional), MREPAIR_STUDIO_ASSETS, MREPAIR_CHROMIUM (default
// /usr/bin/chromium), MREPAIR_NODE_MODULES (where playwright-core is),
// MREPAIR_STUDIO_SHOTS (optional: a folder for the screenshots).
// Exit code 77 (CTest: skipped) when chromium is not installed.
import { createRequire } from 'node:module';
import { spawn, execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, writeFileSync, rmSync, mkdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import assert from 'node:assert/strict';

const here = dirname(fileURLToPath(import.meta.url));
const env = process.env;
const chromiumPath = env.MREPAIR_CHROMIUM || '/usr/bin/chromium';
if (!existsSync(chromiumPath)) {
  console.log(`SKIPPED: ${chromiumPath} not found; install Debian's chromium (apt-get install chromium) ` +
              'to run the studio browser test (scripts/install_deps.sh does)');
  process.exit(77);
}
const modules = env.MREPAIR_NODE_MODULES || join(here, '..');
const { chromium } = createRequire(join(modules, 'package.json'))('playwright-core');
const python = env.MREPAIR_PYTHON || 'python3';
const generate = env.MREPAIR_GENERATE;
assert.ok(generate && existsSync(generate), 'MREPAIR_GENERATE: the mrepair-generate program');
const shots = env.MREPAIR_STUDIO_SHOTS;
if (shots) mkdirSync(shots, { recursive: true });

const work = mkdtempSync(join(tmpdir(), 'mrepair-studio-test-'));
const t0 = Date.now();
const log = (m) => console.log(`[${((Date.now() - t0) / 1000).toFixed(1)} s] ${m}`);
const oracle = (...args) => JSON.parse(execFileSync(python, [join(here, 'oracle.py'), ...args.map(String)],
                                                    { encoding: 'utf8', maxBuffer: 1 << 26 }));

let server = null, browser = null;
async function main() {
  // ---- a scan with known defects -----------------------------------------------------------
  const mesh = join(work, 'scan.ply');
  execFileSync(generate, ['scan', '--faces', '20000', '--seed', '7', '--output', mesh, '--spikes', '6',
                          '--holes', '4', '--jagged-holes', '2', '--islands', '3', '--slivers', '5',
                          '--nan', '0', '--nan-referenced', '0', '--isolated', '0']);
  const expected = oracle('counts', mesh);
  log(`generated ${mesh}: ${JSON.stringify(expected)}`);
  assert.ok(expected.spikes > 0 && expected.small_holes > 0 && expected.small_components > 0,
            'the generated scan has spikes, holes and small components');

  // ---- the studio ----------------------------------------------------------------------------
  server = spawn(python, ['-m', 'mrepair.studio', mesh, '--no-browser', '--port', '0', '--quiet'],
                 { stdio: ['ignore', 'pipe', 'inherit'] });
  const url = await new Promise((resolve, reject) => {
    let out = '';
    server.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) resolve(m[0]);
    });
    server.on('exit', (code) => reject(new Error(`the studio exited (${code}): ${out}`)));
    setTimeout(() => reject(new Error('the studio did not start in 30 s')), 30000);
  });
  log(`studio on ${url}`);

  browser = await chromium.launch({
    executablePath: chromiumPath, headless: true,
    args: ['--no-sandbox', '--disable-dev-shm-usage', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'] });
  const context = await browser.newContext({ viewport: { width: 1400, height: 800 }, acceptDownloads: true });
  const page = await context.newPage();
  const pageErrors = [];
  page.on('pageerror', (e) => pageErrors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'error') pageErrors.push(m.text()); });
  page.on('response', (r) => { if (r.status() >= 400) pageErrors.push(`${r.status()} ${r.url()}`); });
  const idle = () => page.waitForFunction(() => window.studio && window.studio.ready && window.studio.busy === 0,
                                          null, { timeout: 60000 });
  const noErrors = async (what) => {
    const errors = await page.evaluate(() => window.studio.errors);
    assert.deepEqual(errors, [], `${what}: errors on the status line`);
  };
  await page.goto(url);
  await idle();
  await noErrors('loading');

  // 1. the counts shown
  const shown = await page.evaluate(() => window.studio.counts('before'));
  assert.deepEqual(shown, expected, 'the counts shown for the input are those of mrepair.inspect');
  // a click on a count flies to the first instance
  const first = await page.evaluate(() => window.studio.viewer.sides.before.defects.kinds.spikes.first);
  await page.click('#defects button.count[data-kind=spikes][data-side=before]');
  await page.waitForFunction(() => !window.studio.viewer.flight, null, { timeout: 5000 });
  const target = await page.evaluate(() => window.studio.viewer.controls.target.toArray());
  assert.ok(target.every((x, i) => Math.abs(x - first[i]) < 1e-4), `the camera looks at the first spike (${target} vs ${first})`);
  await page.click('#frame');
  log('1. input counts shown = mrepair.inspect; a click on a count flies to the first instance');

  // 2. Run, then Run with a step off
  await page.selectOption('#repair-form select[name=mode]', 'clean');
  await page.click('#run');
  await page.waitForFunction(() => window.studio.timings.clean, null, { timeout: 60000 });
  await idle();
  await noErrors('run');
  const allSteps = await page.evaluate(() => window.studio.counts('after'));
  assert.deepEqual(allSteps, oracle('clean', mesh), 'the result shown is that of mrepair.clean');
  await page.evaluate(() => { delete window.studio.timings.clean; });
  await page.uncheck('#repair-form input[name=step_fill_small_holes]');
  await page.click('#run');
  await page.waitForFunction(() => window.studio.timings.clean, null, { timeout: 60000 });
  await idle();
  await noErrors('run without fill_small_holes');
  const noFill = await page.evaluate(() => window.studio.counts('after'));
  assert.deepEqual(noFill, oracle('clean', mesh, 'fill_small_holes'),
                   'the result shown is that of mrepair.clean(skip=fill_small_holes)');
  assert.ok(noFill.small_holes > allSteps.small_holes,
            `with fill_small_holes off the holes stay (${noFill.small_holes} > ${allSteps.small_holes})`);
  // the report shown is that of the run: the step is off there
  const stepOff = await page.evaluate(() => {
    const d = document.querySelector('#report details[data-section=fill_small_holes]');
    const cell = d && d.querySelector(':scope > table td[data-key=enabled]');
    return cell ? cell.textContent : null;
  });
  assert.equal(stepOff, 'false', 'the report shown says fill_small_holes did not run');
  log(`2. run: ${JSON.stringify(allSteps)}; without fill_small_holes: small holes ${noFill.small_holes}`);

  // 4. export of the result (before the gap sequence replaces it)
  await page.selectOption('#export-form select[name=format]', 'off');
  const [exported] = await Promise.all([page.waitForEvent('download'), page.click('#export')]);
  const exportPath = join(work, 'result.off');
  await exported.saveAs(exportPath);
  const back = oracle('faces', exportPath);
  const resultFaces = await page.evaluate(() => window.studio.viewer.sides.after.meshData.faces);
  assert.equal(back.faces, resultFaces, 'the exported mesh has the result\'s faces');
  log(`4. exported OFF: ${back.faces} faces`);

  // the remeshing panel, on the input
  await page.evaluate(() => { delete window.studio.timings.remesh; });
  await page.selectOption('#remesh-form select[name=mode]', 'uniform');
  await page.selectOption('#remesh-form select[name=source]', 'input');
  await page.fill('#remesh-form input[name=edge_length]', '0.05');
  await page.click('#remesh');
  await page.waitForFunction(() => window.studio.timings.remesh, null, { timeout: 60000 });
  await idle();
  await noErrors('remesh');
  const remeshed = await page.evaluate(() => window.studio.viewer.sides.after.meshData.faces);
  assert.equal(remeshed, oracle('remesh', mesh, 0.05).faces, 'the remeshed mesh is mrepair.remesh\'s');
  log(`remesh (uniform, edge 0.05): ${remeshed} faces`);

  // 3. the gap-closing scrubber
  await page.fill('#gap-form input[name=tolerance]', '0.02');
  await page.check('#gap-form input[name=relative]');
  await page.click('#gap-build');
  await idle();
  await noErrors('gap sequence');
  const gap = await page.evaluate(() => window.studio.gap);
  assert.equal(gap.position, 0, 'a new sequence starts at the input');
  const mid = gap.max_distance / 2;
  const scrub = async (d) => {
    await page.evaluate((v) => {
      const s = document.getElementById('gap-slider');
      s.value = String(v);
      s.dispatchEvent(new Event('input'));
      s.dispatchEvent(new Event('change'));
    }, d);
    await page.waitForTimeout(50);
    await idle();
    return page.evaluate(() => window.studio.meshHash('after'));
  };
  const sliderMid = Number(await page.evaluate((v) => {
    const s = document.getElementById('gap-slider'); s.value = String(v); return s.value; }, mid));
  const hMid = await scrub(sliderMid);
  const midPosition = await page.evaluate(() => window.studio.gap.position);
  if (shots) await page.screenshot({ path: join(shots, 'studio_gap_midway.png') });
  const h0 = await scrub(0);
  const hBack = await scrub(sliderMid);
  // the library's sequence moved the same way: mid-way, 0, mid-way
  const lib = oracle('gap', mesh, 0.02, 1, sliderMid, 0, sliderMid);
  const [libMid, lib0, libBack] = lib.hashes;
  assert.ok(libMid.position > 0, `mid-way the sequence has contractions (${libMid.position})`);
  assert.equal(midPosition, libMid.position, 'mid-way: the page\'s position is the library\'s');
  assert.equal(hMid, libMid.hash, 'mid-way: the page holds the GapClosingSequence\'s mesh');
  assert.notEqual(hMid, h0, 'mid-way the mesh differs from the input');
  // at 0 the page holds exactly the input arrays (the studio serves them at position 0); the
  // library's mesh there has the input's triangles (undone contractions may re-create faces
  // in another order, so its arrays are not compared)
  assert.equal(lib0.position, 0);
  assert.equal(lib0.triangles, lib0.input_triangles, 'at 0 the sequence has the input\'s triangles');
  assert.equal(h0, oracle('input-hash', mesh), 'at 0: the page holds exactly the input');
  assert.equal(hBack, libBack.hash, 'back mid-way: the page holds the sequence\'s mesh');
  assert.equal(libBack.triangles, libMid.triangles, 'back mid-way: the same triangles as the first time');
  await noErrors('gap scrubbing');
  log(`3. gap scrubber: mid-way (distance ${sliderMid}) position ${midPosition}; at 0 the input; hashes agree`);

  // 5. settings out and back in
  await page.fill('#repair-form input[name=spike_angle]', '95');
  const [saved] = await Promise.all([page.waitForEvent('download'), page.click('#save-settings')]);
  const settingsPath = join(work, 'settings.json');
  await saved.saveAs(settingsPath);
  const settings = JSON.parse(readFileSync(settingsPath, 'utf8'));
  assert.equal(settings.forms['repair-form'].spike_angle, 95);
  assert.equal(settings.forms['repair-form'].step_fill_small_holes, false);
  await page.fill('#repair-form input[name=spike_angle]', '60');
  await page.check('#repair-form input[name=step_fill_small_holes]');
  await page.fill('#gap-form input[name=tolerance]', '0.5');
  await page.setInputFiles('#load-settings', settingsPath);
  await page.waitForFunction(() => document.querySelector('#repair-form input[name=spike_angle]').value === '95');
  assert.equal(await page.isChecked('#repair-form input[name=step_fill_small_holes]'), false);
  assert.equal(await page.inputValue('#gap-form input[name=tolerance]'), '0.02');
  // the PNG of the view carries the settings too (thesis 4.6)
  const [pngDownload] = await Promise.all([page.waitForEvent('download'), page.click('#png')]);
  const pngPath = join(work, 'view.png');
  await pngDownload.saveAs(pngPath);
  assert.equal(readFileSync(pngPath).subarray(1, 4).toString(), 'PNG');
  await page.fill('#repair-form input[name=spike_angle]', '61');
  await page.setInputFiles('#load-settings', pngPath);
  await page.waitForFunction(() => document.querySelector('#repair-form input[name=spike_angle]').value === '95');
  await noErrors('settings');
  log('5. settings saved and loaded back, from the JSON and from the PNG of the view');

  // 6. a PNG of the view: before/after of the run, defects visible
  await page.evaluate(() => { delete window.studio.timings.clean; });
  await page.check('#repair-form input[name=step_fill_small_holes]');
  await page.fill('#repair-form input[name=spike_angle]', '');
  await page.click('#run');
  await page.waitForFunction(() => window.studio.timings.clean, null, { timeout: 60000 });
  await idle();
  const pixels = await page.evaluate(async () => {
    const url = window.studio.viewer.png();
    const img = new Image();
    await new Promise((r) => { img.onload = r; img.src = url; });
    const c = document.createElement('canvas');
    c.width = img.width; c.height = img.height;
    const g = c.getContext('2d');
    g.drawImage(img, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    const colours = new Set();
    const near = {};
    const kinds = { spikes: [0xe3, 0x77, 0xc2], boundary_loops: [0x1f, 0x77, 0xb4], small_holes: [0x17, 0xbe, 0xcf],
                    small_components: [0x94, 0x67, 0xbd], near_degenerate_faces: [0xbc, 0xbd, 0x22] };
    for (const k of Object.keys(kinds)) near[k] = 0;
    for (let i = 0; i < d.length; i += 4) {
      colours.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
      for (const [k, [r, g2, b]] of Object.entries(kinds)) {
        if (Math.abs(d[i] - r) <= 6 && Math.abs(d[i + 1] - g2) <= 6 && Math.abs(d[i + 2] - b) <= 6) near[k]++;
      }
    }
    return { url, width: c.width, height: c.height, colours: colours.size, near };
  });
  const png = Buffer.from(pixels.url.split(',')[1], 'base64');
  assert.ok(png.length > 10000, 'the PNG holds a picture');
  assert.ok(pixels.colours > 50, `the view is not blank (${pixels.colours} colours)`);
  for (const k of ['spikes', 'small_holes', 'small_components']) {
    assert.ok(pixels.near[k] > 0, `the ${k} colour is in the picture (${JSON.stringify(pixels.near)})`);
  }
  if (shots) {
    writeFileSync(join(shots, 'studio_view.png'), png);
    await page.screenshot({ path: join(shots, 'studio_before_after.png') });
  }
  log(`6. PNG ${pixels.width}x${pixels.height}, ${pixels.colours} colours, defect pixels ${JSON.stringify(pixels.near)}`);

  // 7. the HTML report in the same browser
  const report = join(work, 'report.html');
  let want;
  const cli = env.MREPAIR_CLI;
  let cliHasHtml = false;
  if (cli && existsSync(cli)) {
    try {
      cliHasHtml = execFileSync(cli, ['repair', '--help'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] })
        .includes('--html');
    } catch (e) {
      cliHasHtml = String(e.stdout || '').includes('--html');
    }
  }
  if (cliHasHtml) {
    const out = join(work, 'repaired.off');
    // the input's self-intersections counted too, as mrepair.inspect does
    execFileSync(cli, ['repair', mesh, out, '--html', report, '--input-self-intersections', '--quiet']);
    want = { before: expected, after: oracle('counts', out) };
    log('7. report written by mrepair repair --html');
  } else {
    want = oracle('html', report, mesh);
    log('7. report written by mrepair.html_report (the CLI has no --html)');
  }
  const rpage = await context.newPage();
  rpage.on('pageerror', (e) => pageErrors.push('report: ' + e.message));
  await rpage.goto('file://' + report);
  await rpage.waitForFunction(() => window.mrepairReport && window.mrepairReport.ready, null, { timeout: 60000 });
  assert.deepEqual(await rpage.evaluate(() => window.mrepairReport.errors), []);
  assert.deepEqual(await rpage.evaluate(() => window.mrepairReport.counts('before')), want.before,
                   'the report shows the input\'s counts');
  assert.deepEqual(await rpage.evaluate(() => window.mrepairReport.counts('after')), want.after,
                   'the report shows the result\'s counts');
  const requests = [];
  rpage.on('request', (r) => requests.push(r.url()));
  await rpage.reload();
  await rpage.waitForFunction(() => window.mrepairReport && window.mrepairReport.ready);
  assert.deepEqual(requests.filter((u) => !u.startsWith('file:') && !u.startsWith('data:')), [],
                   'the report loads nothing from the network');
  if (shots) await rpage.screenshot({ path: join(shots, 'report.png') });
  log('7. the HTML report shows the same counts, offline');

  assert.deepEqual(pageErrors, [], 'no JavaScript errors');
  log('studio browser test: all checks passed');
}

let code = 0;
try {
  await main();
} catch (e) {
  console.error('FAILED:', e.stack || e);
  code = 1;
} finally {
  if (browser) await browser.close();
  if (server) server.kill('SIGTERM');
  rmSync(work, { recursive: true, force: true });
}
process.exit(code);
