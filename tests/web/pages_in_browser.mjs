// Opens every interactive page of a `volspline demo` folder in headless Chromium (Debian's
// /usr/bin/chromium, driven by puppeteer-core, which downloads nothing) from file:// and checks
// what a user would see (docs/web-pages.md, "Tests"):
//   - the page opens without console errors or failed requests, in under MAX_OPEN_MS;
//   - the file is under MAX_PAGE_BYTES;
//   - the canvas is not blank: the object covers a sensible share of it, in several colours,
//     and fits it (nothing drawn on its outermost pixels);
//   - switching a part off and moving a probe's slider change the picture;
//   - the gallery (index.html) links every page, and shows a thumbnail for each.
// A screenshot of every page is kept in OUT_DIR.
//
//   node pages_in_browser.mjs DEMO_DIR OUT_DIR
//
// Exit 0: passed; 1: failed; 77: skipped (no Chromium, no puppeteer-core): ctest's
// SKIP_RETURN_CODE (tests/CMakeLists.txt).
import { existsSync, mkdirSync, readdirSync, readFileSync, statSync, mkdtempSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const MAX_PAGE_BYTES = 5 * 1024 * 1024;
const MAX_OPEN_MS = 2000;
const CHROMIUM = process.env.VOLSPLINE_CHROMIUM || '/usr/bin/chromium';

const [demoDir, outDir] = process.argv.slice(2).map((p) => p && resolve(p));
if (!demoDir || !outDir) {
  console.error('usage: node pages_in_browser.mjs DEMO_DIR OUT_DIR');
  process.exit(2);
}
function skip(why) {
  console.log(`SKIPPED: ${why}`);
  process.exit(77);
}
if (!existsSync(CHROMIUM)) skip(`${CHROMIUM} is not installed (scripts/install-deps installs Debian's chromium)`);
let puppeteer;
try {
  // puppeteer-core lives in web/node_modules (scripts/install-web-deps), beside the viewer.
  const require = createRequire(join(resolve(import.meta.dirname, '..', '..', 'web'), 'package.json'));
  puppeteer = require('puppeteer-core');
} catch (e) {
  skip(`puppeteer-core is not installed in web/node_modules (run scripts/install-web-deps): ${e.message}`);
}

const pages = readdirSync(demoDir).filter((f) => f.endsWith('.html') && f !== 'index.html').sort();
const failures = [];
function check(ok, what) {
  if (!ok) failures.push(what);
  return ok;
}
check(pages.length > 0, `${demoDir} holds no interactive pages`);
mkdirSync(outDir, { recursive: true });

// What the canvas shows: the share of pixels that are not the white background, the number of
// distinct colours (quantised), and a checksum to tell two pictures apart.
async function canvasStatistics(page) {
  return page.evaluate(() => {
    window.volsplinePage.draw();
    const source = document.getElementById('vs-canvas');
    // A 400 x 256 copy: enough to see the object and any change, cheap to scan.
    const copy = document.createElement('canvas');
    copy.width = 400;
    copy.height = 256;
    const context = copy.getContext('2d');
    context.drawImage(source, 0, 0, copy.width, copy.height);
    const pixels = context.getImageData(0, 0, copy.width, copy.height).data;
    let covered = 0;
    let border = 0;
    let checksum = 0;
    const colours = new Set();
    for (let i = 0; i < pixels.length; i += 4) {
      const [r, g, b] = [pixels[i], pixels[i + 1], pixels[i + 2]];
      if (r < 245 || g < 245 || b < 245) {
        ++covered;
        colours.add(((r >> 4) << 8) | ((g >> 4) << 4) | (b >> 4));
        const x = (i / 4) % copy.width, y = Math.floor(i / 4 / copy.width);
        if (x === 0 || y === 0 || x === copy.width - 1 || y === copy.height - 1) ++border;
      }
      checksum = (checksum * 31 + r + 7 * g + 13 * b) % 1000000007;
    }
    return { covered: covered / (pixels.length / 4), border, colours: colours.size, checksum, width: copy.width, height: copy.height };
  });
}

const profile = mkdtempSync(join(tmpdir(), 'volspline-chromium-'));
const browser = await puppeteer.launch({
  executablePath: CHROMIUM,
  headless: true,
  userDataDir: profile,
  args: [
    '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
  ],
});
const report = [];
try {
  // The first WebGL context of a browser costs a second (SwiftShader starting): spent here, on a
  // page of its own, not charged to the first page measured.
  {
    const warm = await browser.newPage();
    await warm.goto('about:blank');
    await warm.evaluate(() => document.createElement('canvas').getContext('webgl2') !== null);
    await warm.close();
  }
  for (const name of pages) {
    const file = join(demoDir, name);
    const bytes = statSync(file).size;
    check(bytes < MAX_PAGE_BYTES, `${name}: ${bytes} bytes, the limit is ${MAX_PAGE_BYTES}`);
    const page = await browser.newPage();
    // 640 x 400: the canvas beside the panel is taller than wide, as in a narrow window, which
    // the fit must handle (the border check below); SwiftShader also has fewer pixels to draw.
    await page.setViewport({ width: 640, height: 400 });
    const errors = [];
    page.on('console', (m) => {
      if (m.type() === 'error') errors.push(m.text());
    });
    page.on('pageerror', (e) => errors.push(String(e)));
    page.on('requestfailed', (r) => errors.push(`request failed: ${r.url().slice(0, 80)}`));
    page.on('request', (r) => {
      if (!r.url().startsWith('file:') && !r.url().startsWith('data:') && !r.url().startsWith('blob:'))
        errors.push(`network request: ${r.url()}`);
    });
    // As the test saw it (from the request to navigate until the viewer has drawn: what the
    // limit applies to), and by the page's own clock from the start of its navigation.
    const open = async () => {
      const started = Date.now();
      await page.goto(pathToFileURL(file).href, { waitUntil: 'load' });
      await page.waitForFunction(() => document.body && document.body.dataset.ready, { timeout: 20000 });
      return [Date.now() - started, await page.evaluate(() => Math.round(window.volsplinePage.readyAt))];
    };
    let [wallMs, openMs] = await open();
    if (wallMs >= MAX_OPEN_MS) {
      // Once more before failing: on a shared 2-core machine another test's burst can stall one
      // open (2,088 ms seen, the page's own clock 1,078 ms); a page slow twice is slow.
      console.log(`${name}: opened in ${wallMs} ms, over the limit; opening it again`);
      [wallMs, openMs] = await open();
    }
    const ready = await page.evaluate(() => document.body.dataset.ready);
    check(ready === '1', `${name}: the viewer did not finish (${ready})`);
    check(wallMs < MAX_OPEN_MS, `${name}: opened in ${wallMs} ms, the limit is ${MAX_OPEN_MS}`);
    const before = await canvasStatistics(page);
    check(before.covered > 0.01 && before.covered < 0.95, `${name}: the object covers ${(100 * before.covered).toFixed(1)}% of the canvas`);
    check(before.colours >= 4, `${name}: only ${before.colours} colours on the canvas`);
    // The object fits the canvas as the page opens: nothing drawn on its outermost pixels.
    check(before.border === 0, `${name}: the object touches the canvas's border at ${before.border} pixels (cut off)`);
    await page.screenshot({ path: join(outDir, name.replace(/\.html$/, '.png')) });

    // Switch off the part with the most triangles: the picture changes; on again: it is back.
    const part = await page.evaluate(() => {
      let best = null;
      for (const box of document.querySelectorAll('input[data-part]')) {
        const n = Number(box.parentElement.textContent.match(/(\d+) triangles/)[1]);
        if (!best || n > best.n) best = { name: box.dataset.part, n };
      }
      return best && best.name;
    });
    let partChange = null;
    if (check(part !== null, `${name}: no parts listed`)) {
      await page.click(`input[data-part="${part}"]`);
      const off = await canvasStatistics(page);
      partChange = off.checksum !== before.checksum;
      check(partChange, `${name}: switching off ${part} did not change the picture`);
      await page.click(`input[data-part="${part}"]`);
      const on = await canvasStatistics(page);
      check(on.checksum === before.checksum, `${name}: switching ${part} on again did not restore the picture`);
    }
    // Move the u probe (or the first there is), switched on, to its other end.
    const probe = await page.evaluate(() => {
      const boxes = [...document.querySelectorAll('input[data-probe-toggle]')];
      const box = boxes.find((b) => b.dataset.probeToggle === 'u') || boxes[0];
      if (!box) return null;
      if (!box.checked) box.click();
      return box.dataset.probeToggle;
    });
    let probeChange = null;
    if (probe !== null) {
      const shown = await canvasStatistics(page);
      const moved = await page.evaluate((p) => {
        const slider = document.querySelector(`input[data-probe="${p}"]`);
        slider.value = String(Number(slider.value) > 0 ? 0 : Number(slider.max));
        slider.dispatchEvent(new Event('input'));
        return slider.value;
      }, probe);
      const after = await canvasStatistics(page);
      probeChange = after.checksum !== shown.checksum;
      check(probeChange, `${name}: moving the ${probe} probe to ${moved} did not change the picture`);
    }
    check(errors.length === 0, `${name}: ${errors.join('; ')}`);
    report.push({ name, bytes, openMs, wallMs, loadMs: await page.evaluate(() => Math.round(window.volsplinePage.loadMilliseconds)),
      covered: before.covered, colours: before.colours, part, probe });
    await page.close();
  }
  // The gallery: a thumbnail for every page, linking to it.
  const index = join(demoDir, 'index.html');
  if (check(existsSync(index), 'the demo folder has no index.html')) {
    const html = readFileSync(index, 'utf8');
    for (const name of pages) check(html.includes(`href="${name}"`), `index.html does not link ${name}`);
    const page = await browser.newPage();
    await page.setViewport({ width: 1200, height: 900 });
    await page.goto(pathToFileURL(index).href, { waitUntil: 'load' });
    // The thumbnails load lazily: load them all, then look for broken ones.
    const broken = await page.evaluate(async () => {
      const images = [...document.images];
      for (const i of images) i.loading = 'eager';
      await Promise.all(images.map((i) => i.decode().catch(() => null)));
      return images.filter((i) => i.naturalWidth === 0).map((i) => i.src);
    });
    check(broken.length === 0, `index.html: broken thumbnails ${broken.join(' ')}`);
    await page.screenshot({ path: join(outDir, 'index.png') });
    await page.close();
  }
} finally {
  await browser.close();
  rmSync(profile, { recursive: true, force: true });
}
for (const r of report)
  console.log(`${r.name}: ${(r.bytes / 1e6).toFixed(2)} MB, opened in ${r.openMs} ms (viewer ${r.loadMs} ms, ${r.wallMs} ms seen by the test), ` +
    `covers ${(100 * r.covered).toFixed(1)}%, ${r.colours} colours; toggled ${r.part}, probe ${r.probe ?? 'none'}`);
if (report.length > 0) {
  const largest = report.reduce((a, b) => (a.bytes > b.bytes ? a : b));
  const slowest = report.reduce((a, b) => (a.openMs > b.openMs ? a : b));
  console.log(`${report.length} pages; largest ${largest.name} ${(largest.bytes / 1e6).toFixed(2)} MB; slowest ${slowest.name} ${slowest.openMs} ms`);
}
console.log(`screenshots in ${outDir}`);
if (failures.length > 0) {
  for (const f of failures) console.log(`FAILED: ${f}`);
  process.exit(1);
}
