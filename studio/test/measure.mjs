// Measures the studio on a mesh and takes the screenshots of the README and the
// lead's note (not a test; run by hand):
//   node studio/test/measure.mjs MESH OUTDIR [--gap TOL]
// with the environment of studio.test.mjs (MREPAIR_PYTHON, PYTHONPATH,
// MREPAIR_STUDIO_ASSETS, MREPAIR_NODE_MODULES, MREPAIR_CHROMIUM). Prints the time
// from the click on Run to the redrawn mesh (the page's performance.now(): the
// click handler starts the clock; it stops after the new mesh is drawn and
// gl.finish() returned), the library's share, and the defect layer's extra time.
import { createRequire } from 'node:module';
import { spawn } from 'node:child_process';
import { mkdirSync } from 'node:fs';
import { join, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const [mesh, out] = process.argv.slice(2);
const opt = (name) => { const i = process.argv.indexOf(name); return i > 0 ? process.argv[i + 1] : null; };
const gapTol = opt('--gap');            // build a gap-closing sequence with this relative tolerance
const gapSource = opt('--gap-source');  // input | result
const mode = opt('--mode');             // clean | repair
const closeGaps = opt('--close-gaps');  // repair's close gaps tolerance (0: off)
const fly = opt('--fly');               // a defect kind: fly to its first instance before the screenshots
const runs = Number(opt('--runs') || 3);
const env = process.env;
const { chromium } = createRequire(join(env.MREPAIR_NODE_MODULES || join(here, '..'), 'package.json'))('playwright-core');
mkdirSync(out, { recursive: true });
const budget = opt('--face-budget');
const server = spawn(env.MREPAIR_PYTHON || 'python3', ['-m', 'mrepair.studio', mesh, '--no-browser', '--quiet',
                                                       ...(budget ? ['--face-budget', budget] : [])],
                     { stdio: ['ignore', 'pipe', 'inherit'] });
const url = await new Promise((resolve) => {
  let s = '';
  server.stdout.on('data', (d) => { s += d; const m = s.match(/http:\/\/127\.0\.0\.1:\d+\//); if (m) resolve(m[0]); });
});
const browser = await chromium.launch({ executablePath: env.MREPAIR_CHROMIUM || '/usr/bin/chromium', headless: true,
  args: ['--no-sandbox', '--disable-dev-shm-usage', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'] });
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 800 } });
  const idle = () => page.waitForFunction(() => window.studio && window.studio.ready && window.studio.busy === 0,
                                          null, { timeout: 600000 });
  const t0 = Date.now();
  await page.goto(url);
  await idle();
  console.log(`load (read, inspect, mesh and defects drawn): ${((Date.now() - t0) / 1000).toFixed(2)} s`);
  if (mode) await page.selectOption('#repair-form select[name=mode]', mode);
  if (closeGaps !== null) await page.fill('#repair-form input[name=close_gaps]', closeGaps);
  for (let i = 0; i < runs; i++) {
    await page.evaluate(() => { delete window.studio.timings.clean; delete window.studio.timings.repair; });
    await page.click('#run');
    await page.waitForFunction(() => window.studio.timings.clean || window.studio.timings.repair, null, { timeout: 600000 });
    await idle();
    const t = await page.evaluate(() => window.studio.timings.clean || window.studio.timings.repair);
    console.log(`run ${i + 1}: click -> redrawn mesh ${(t.total_ms / 1000).toFixed(2)} s (library ${(t.server_ms / 1000).toFixed(2)} s, ` +
                `${t.faces} faces, ${t.drawn_faces} drawn), defects +${(t.defects_ms / 1000).toFixed(2)} s`);
  }
  const flyTo = async (side) => {
    if (!fly) return;
    await page.click(`#defects button.count[data-kind=${fly}][data-side=${side}]`);
    await page.waitForTimeout(1000);
  };
  await flyTo('before');
  await page.evaluate(() => document.getElementById('side').scrollTo(0, 0));
  await page.screenshot({ path: join(out, 'studio_before_after.png') });
  if (gapTol) {
    await page.fill('#gap-form input[name=tolerance]', gapTol);
    if (gapSource) await page.selectOption('#gap-form select[name=source]', gapSource);
    await page.click('#gap-build');
    await idle();
    const max = await page.evaluate(() => window.studio.gap.max_distance);
    await page.evaluate((v) => {
      const s = document.getElementById('gap-slider');
      s.value = String(v);
      s.dispatchEvent(new Event('input'));
      s.dispatchEvent(new Event('change'));
    }, max / 2);
    await page.waitForTimeout(100);
    await idle();
    await page.evaluate(() => document.querySelector('#gap-form').scrollIntoView());
    await page.screenshot({ path: join(out, 'studio_gap_midway.png') });
    console.log(`gap scrubber mid-way: ${JSON.stringify(await page.evaluate(() => window.studio.gap.position))} contractions`);
  }
} finally {
  await browser.close();
  server.kill('SIGTERM');
}
