// Renders every case of CASES/cases.json with three-vrm in headless Chromium and writes
// OUT/<name>-<view>.png, OUT/VERSIONS and OUT/cases.sha256. Run through render-references.sh.
//
//   node render-references.mjs PAGE_DIR NODE_MODULES CASES OUT CHROMIUM
import { chromium } from 'playwright-core';
import { createServer } from 'node:http';
import { readFileSync, writeFileSync, copyFileSync, existsSync } from 'node:fs';
import { join, normalize, extname } from 'node:path';

const [pageDir, nodeModules, casesDir, outDir, chromiumPath] = process.argv.slice(2);
if (!chromiumPath) {
  console.error('usage: node render-references.mjs PAGE_DIR NODE_MODULES CASES OUT CHROMIUM');
  process.exit(2);
}

const TYPES = { '.html': 'text/html', '.mjs': 'text/javascript', '.js': 'text/javascript',
                '.vrm': 'application/octet-stream', '.json': 'application/json' };
// Three roots only: the page, node_modules and the cases; no path leaves them.
const ROOTS = [['/node_modules/', nodeModules], ['/cases/', casesDir], ['/', pageDir]];
const server = createServer((request, response) => {
  const path = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
  if (path === '/favicon.ico') { // asked for by every page; not an error
    response.writeHead(204);
    response.end();
    return;
  }
  for (const [prefix, root] of ROOTS) {
    if (!path.startsWith(prefix)) continue;
    const relative = normalize(path.slice(prefix.length) || 'page.html');
    if (relative.startsWith('..')) break;
    const file = join(root, relative);
    if (!existsSync(file)) break;
    response.writeHead(200, { 'Content-Type': TYPES[extname(file)] || 'application/octet-stream' });
    response.end(readFileSync(file));
    return;
  }
  response.writeHead(404);
  response.end();
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const base = `http://127.0.0.1:${server.address().port}`;

// SwiftShader: WebGL 2 in software, the same on every machine, no GPU needed.
const browser = await chromium.launch({
  executablePath: chromiumPath,
  args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
});
const page = await browser.newPage({ viewport: { width: 512, height: 512 }, deviceScaleFactor: 1 });
const errors = [];
page.on('pageerror', (error) => errors.push(String(error)));
page.on('console', (message) => {
  if (message.type() === 'error' || message.type() === 'warning') errors.push(message.text());
});
await page.goto(`${base}/page.html`);
await page.waitForFunction(() => window.pageReady === true);

const { cases } = JSON.parse(readFileSync(join(casesDir, 'cases.json'), 'utf8'));
let count = 0;
for (const entry of cases) {
  for (const view of entry.views) {
    const url = await page.evaluate(([file, v, t]) => window.renderCase(file, v, t),
                                    [`/cases/${entry.file}`, view, entry.time]);
    const png = Buffer.from(url.slice(url.indexOf(',') + 1), 'base64');
    writeFileSync(join(outDir, `${entry.name}-${view}.png`), png);
    count += 1;
  }
}
if (errors.length) {
  console.error(`render-references.mjs: the page reported:\n  ${errors.join('\n  ')}`);
}

const page_versions = await page.evaluate(() => window.versions());
const packageVersion = (name) => JSON.parse(readFileSync(join(nodeModules, name, 'package.json'), 'utf8')).version;
const lines = [
  `three ${packageVersion('three')} (REVISION ${page_versions.three})`,
  `@pixiv/three-vrm ${packageVersion('@pixiv/three-vrm')}`,
  `playwright-core ${packageVersion('playwright-core')}`,
  `chromium ${browser.version()} (headless, --use-angle=swiftshader)`,
  `WebGL ${page_versions.webglVersion}`,
  `WebGL renderer ${page_versions.webglRenderer}`,
  `MSAA samples ${page_versions.samples}`,
  `pictures ${count}, 512x512, sRGB PNG`,
];
writeFileSync(join(outDir, 'VERSIONS'), lines.join('\n') + '\n');
copyFileSync(join(casesDir, 'cases.sha256'), join(outDir, 'cases.sha256'));
console.log(lines.join('\n'));
await browser.close();
server.close();
if (errors.length) process.exit(1);
