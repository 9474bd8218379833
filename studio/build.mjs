// Builds the studio's two outputs into --out DIR (default dist/):
//   index.html + assets/studio.js + assets/studio.css   the live studio page
//   report_template.html                                 one self-contained file (JS and CSS
//                                                        inlined) with the payload placeholder
// --modules DIR: where node_modules is (default: this folder), so that CMake
// can run `npm ci` in its build folder and leave the source tree alone.
import { createRequire } from 'node:module';
import { mkdirSync, readFileSync, writeFileSync, copyFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const arg = (name, fallback) => {
  const i = process.argv.indexOf(name);
  return i > 0 && process.argv[i + 1] ? resolve(process.argv[i + 1]) : fallback;
};
const out = arg('--out', join(here, 'dist'));
const modules = arg('--modules', here);
const esbuild = createRequire(join(modules, 'package.json'))('esbuild');
const common = { bundle: true, minify: true, target: ['es2020'], nodePaths: [join(modules, 'node_modules')],
                 legalComments: 'none', logLevel: 'warning', absWorkingDir: here };

mkdirSync(join(out, 'assets'), { recursive: true });

// 1. the studio page
await esbuild.build({ ...common, entryPoints: { studio: join(here, 'src/studio.js') }, format: 'esm',
                      outdir: join(out, 'assets') });
copyFileSync(join(here, 'index.html'), join(out, 'index.html'));

// 2. the report template: one file
const r = await esbuild.build({ ...common, entryPoints: { report: join(here, 'src/report.js') }, format: 'iife',
                                outdir: join(out, 'report'), write: false });
const file = (ext) => r.outputFiles.find((f) => f.path.endsWith(ext)).text;
// nothing in the inlined code may end its <script> or <style> element early
const js = file('.js').replace(/<\/(script)/gi, '<\\/$1');
const css = file('.css').replace(/<\/(style)/gi, '<\\/$1');
const template = readFileSync(join(here, 'report_template.html'), 'utf8');
const html = template.replace('/*MREPAIR_CSS*/', () => css).replace('/*MREPAIR_JS*/', () => js);
const placeholders = html.split('/*MREPAIR_PAYLOAD*/').length - 1;
if (placeholders !== 1) throw new Error(`report_template.html: ${placeholders} payload placeholders, expected 1`);
if (/\b(src|href)=["']https?:/i.test(html)) throw new Error('report_template.html refers to the network');
writeFileSync(join(out, 'report_template.html'), html);
console.log(`mrepair studio: built ${out}/index.html and ${out}/report_template.html (${(html.length / 1024).toFixed(0)} KiB)`);
