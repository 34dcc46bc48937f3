#!/usr/bin/env node
// Real-browser test of `inim place` (docs/place-api.md) and its page (web/place/): Debian's
// Chromium driven through puppeteer-core. scripts/browser-test.sh installs what it needs.
//
//   node tests/web/place_browser.mjs INIM OUTDIR [--field MODEL] [--[no-]predict] [--compare-eia]
//   (or INIM_PLACE_FIELD=MODEL): the same checks against a trained field, without the
//   scene-specific geometry and, unless asked for (--compare-eia, --predict), without the EIA
//   byte comparison and the predicted view (a trained field's full-panel EIA takes minutes).
//
// Checks: the token (403 without it); the level-0 preview and its red on-plane pixels, which
// move as geometry predicts when the scene moves along z; the diagram follows; a 400 shows in
// the status line and puts the control back; undo / redo / reset; "Write run file" gives the
// same EIA as the equivalent command line, byte for byte; a predicted view (optional). Writes
// OUTDIR/place-page.png and OUTDIR/place-latency.json (latencies are reported, never judged).
import {spawn} from 'node:child_process';
import {existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync, createWriteStream} from 'node:fs';
import {createRequire} from 'node:module';
import {tmpdir} from 'node:os';
import {dirname, join, resolve} from 'node:path';
import {createInterface} from 'node:readline';
import {fileURLToPath} from 'node:url';

const HERE = dirname(fileURLToPath(import.meta.url));
const ROOT = resolve(HERE, '..', '..');
const CHROMIUM = process.env.INIM_CHROMIUM || '/usr/bin/chromium';
const TOTAL_BUDGET_MS = 285000;  // the whole test stays under 5 minutes
const WAIT_MS = 30000;           // one image, one settle
const EIA_TIMEOUT_MS = 120000;

class TestFailure extends Error {}
const check = (cond, msg) => { if (!cond) throw new TestFailure(msg); };
const log = (msg) => console.log(`place-test: ${msg}`);
const pass = (msg) => console.log(`place-test: PASS ${msg}`);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

function withTimeout(promise, ms, what) {
  let timer;
  const timeout = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new TestFailure(`timed out after ${ms} ms: ${what}`)), ms);
  });
  return Promise.race([promise, timeout]).finally(() => clearTimeout(timer));
}

// ------------------------------------------------------------------ arguments

function parseArgs(argv) {
  const a = {field: process.env.INIM_PLACE_FIELD || '', predict: null, compareEia: false, positional: []};
  for (let i = 0; i < argv.length; ++i) {
    if (argv[i] === '--field') a.field = argv[++i] || '';
    else if (argv[i].startsWith('--field=')) a.field = argv[i].slice(8);
    else if (argv[i] === '--no-predict') a.predict = false;
    else if (argv[i] === '--predict') a.predict = true;
    else if (argv[i] === '--compare-eia') a.compareEia = true;
    else a.positional.push(argv[i]);
  }
  if (a.positional.length !== 2) {
    console.error('usage: node tests/web/place_browser.mjs INIM OUTDIR [--field MODEL] [--[no-]predict] [--compare-eia]');
    process.exit(2);
  }
  a.inim = resolve(a.positional[0]);
  a.out = resolve(a.positional[1]);
  // A trained field's full-panel EIA takes minutes: its EIA comparison and predicted view are asked for.
  a.compareEia = a.compareEia || !a.field;
  if (a.predict === null) a.predict = !a.field;
  return a;
}

// puppeteer-core from build/web-test (scripts/browser-test.sh), $INIM_WEB_MODULES or beside the script.
async function loadPuppeteer() {
  const dirs = [process.env.INIM_WEB_MODULES, join(ROOT, 'build', 'web-test'), HERE].filter(Boolean);
  for (const d of dirs) {
    try {
      return createRequire(join(d, 'package.json'))('puppeteer-core');
    } catch (e) { /* next */ }
  }
  return (await import('puppeteer-core')).default;
}

// ------------------------------------------------------------------ the server

function startServer(inim, outDir, field) {
  const argv = ['place', '--port', '0', '--out', join(outDir, 'place-out')];
  if (field) argv.push('--field', field);
  log(`starting ${inim} ${argv.join(' ')}`);
  const child = spawn(inim, argv, {stdio: ['ignore', 'pipe', 'pipe']});
  const logFile = createWriteStream(join(outDir, 'place-server.log'));
  child.stderr.pipe(logFile);
  const lines = createInterface({input: child.stdout});
  const url = new Promise((resolveUrl, reject) => {
    child.on('error', reject);
    child.on('exit', (code, sig) => reject(new TestFailure(
        `inim place exited (${code ?? sig}) before printing its URL; see ${join(outDir, 'place-server.log')}`)));
    lines.once('line', (line) => {
      lines.on('line', (l) => logFile.write(`[stdout] ${l}\n`));
      resolveUrl(line.trim());
    });
  });
  return {child, url: withTimeout(url, 60000, 'the URL line of inim place')};
}

async function stopServer(child) {
  if (!child || child.exitCode !== null || child.signalCode !== null) return;
  const exited = new Promise((r) => child.once('exit', r));
  const t0 = Date.now();
  child.kill('SIGINT');  // Ctrl-C, as a person stops it
  const done = await Promise.race([exited.then(() => true), sleep(15000).then(() => false)]);
  if (done) log(`inim place stopped ${Date.now() - t0} ms after SIGINT`);
  else {
    log('inim place did not stop within 15 s of SIGINT; killing it');
    child.kill('SIGKILL');
    await Promise.race([exited, sleep(5000)]);
  }
}

function serverApi(base, token) {
  const call = async (path, method = 'GET', body) => {
    const init = {method, headers: {'X-Inim-Token': token}, signal: AbortSignal.timeout(WAIT_MS)};
    if (body !== undefined) init.body = JSON.stringify(body);
    const res = await fetch(base + path, init);
    const text = await res.text();
    check(res.ok, `${method} ${path}: HTTP ${res.status} ${text}`);
    return JSON.parse(text);
  };
  return {get: (p) => call(p), put: (p, b) => call(p, 'PUT', b)};
}

async function checkToken(base, token) {
  const status = async (path, headers = {}) =>
    (await fetch(base + path, {headers, signal: AbortSignal.timeout(WAIT_MS)})).status;
  check(await status('/') === 403, 'GET / without the token must be 403');
  check(await status('/api/state') === 403, 'GET /api/state without the token must be 403');
  const wrong = token.replace(/./, (c) => (c === '0' ? '1' : '0'));
  check(await status('/api/state', {'X-Inim-Token': wrong}) === 403, 'a wrong token must be 403');
  check(await status(`/api/state?token=${token}`) === 200, 'the token as a query parameter must be accepted');
  pass('requests without the right token get 403');
}

// ------------------------------------------------------------------ the page

async function launchBrowser(puppeteer, profile) {
  return puppeteer.launch({
    executablePath: CHROMIUM,
    headless: true,
    timeout: WAIT_MS,
    protocolTimeout: 60000,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
           '--disable-component-update', '--disable-sync', `--user-data-dir=${profile}`],
  });
}

async function settle(page, what) {
  try {
    await page.waitForFunction(() => window.inimSettled && window.inimSettled(), {timeout: WAIT_MS, polling: 20});
  } catch (e) {
    const status = await page.$eval('#status', (el) => el.textContent).catch(() => '?');
    throw new TestFailure(`the page did not settle (${what}); status line: "${status}"`);
  }
}

// The red (on-plane) pixels of an image element, read back through a canvas.
function readPixels(page, selector) {
  return page.evaluate((sel) => {
    const img = document.querySelector(sel);
    const c = document.createElement('canvas');
    c.width = img.naturalWidth ?? img.width;  // an <img>, or a <canvas>
    c.height = img.naturalHeight ?? img.height;
    const g = c.getContext('2d', {willReadFrequently: true});
    g.drawImage(img, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    const red = [];
    let exactRed = 0;
    let hash = 2166136261;
    for (let j = 0; j < c.height; ++j) {
      for (let i = 0; i < c.width; ++i) {
        const k = 4 * (j * c.width + i);
        if (d[k] > 200 && d[k + 1] < 60 && d[k + 2] < 60) red.push([i, j]);
        if (d[k] === 255 && d[k + 1] === 0 && d[k + 2] === 0) ++exactRed;
      }
    }
    for (let k = 0; k < d.length; ++k) hash = Math.imul(hash ^ d[k], 16777619) >>> 0;
    return {width: c.width, height: c.height, red, exactRed, hash};
  }, selector);
}

// Lenslet (i, j) of the level-0 preview -> display mm (x right, y up; row 0 at the top).
function toMm(px, geo) {
  return [(px[0] + 0.5 - geo.width / 2) * geo.pitch[0], (geo.height / 2 - px[1] - 0.5) * geo.pitch[1]];
}

function redIn(pixels, geo, box) {
  const pts = pixels.red.map((p) => toMm(p, geo))
    .filter(([x, y]) => x >= box.x0 && x <= box.x1 && y >= box.y0 && y <= box.y1);
  const mean = (k) => pts.reduce((s, p) => s + p[k], 0) / Math.max(1, pts.length);
  return {count: pts.length, cx: mean(0), cy: mean(1)};
}

// Selects a field's text and inserts `text` as one input event (as a paste would), then Enter.
async function typeInto(page, selector, text) {
  await page.focus(selector);
  await page.keyboard.down('Control');
  await page.keyboard.press('KeyA');
  await page.keyboard.up('Control');
  await page.keyboard.sendCharacter(String(text));
  await page.keyboard.press('Enter');
}
const setNumber = (page, id, value) => typeInto(page, `#${id}-num`, value);

async function blur(page) {
  await page.evaluate(() => document.activeElement && document.activeElement.blur());
}

const onPlaneCount = async (page) => {
  const text = await page.$eval('#counts', (e) => e.textContent);
  const m = /on plane (\d+)/.exec(text);
  check(m, `#counts shows no on-plane count: "${text}"`);
  return Number(m[1]);
};

async function openPage(browser, url, errors) {
  const page = await browser.newPage();
  page.setDefaultTimeout(WAIT_MS);
  await page.setViewport({width: 1500, height: 1000});
  page.on('pageerror', (e) => errors.push(String(e && e.message ? e.message : e)));
  page.on('console', (m) => {
    if (m.type() === 'error' && !/409/.test(m.text())) log(`browser console: ${m.text()}`);
  });
  await page.goto(url, {waitUntil: 'load', timeout: WAIT_MS});
  await settle(page, 'the first level-0 preview');
  return page;
}

// ------------------------------------------------------------------ the checks

async function checkLevel0(page, geo) {
  const px = await readPixels(page, '#preview0');
  check(px.width === geo.width && px.height === geo.height,
        `level 0 is ${px.width} x ${px.height}, expected the ${geo.width} x ${geo.height} lenslets`);
  const counted = await onPlaneCount(page);
  check(px.exactRed === counted, `the image has ${px.exactRed} pure-red pixels, X-Inim-Counts says on_plane ${counted}`);
  pass(`level 0 is ${px.width} x ${px.height}, ${px.red.length} red pixels = X-Inim-Counts on_plane`);
  return px;
}

// The default scene's scale target lies on z = 0 at (0, 17) mm, 64 x 30 mm: red, upper middle.
async function checkDefaultScene(page, geo, state) {
  const p = state.placement;
  const identity = [...p.translate_mm, ...p.rotate_deg].every((v) => v === 0) && p.scale.every((v) => v === 1);
  if (!identity) return log('skipping the scale-target check: the start-up placement is not the identity');
  const px = await readPixels(page, '#preview0');
  const t = redIn(px, geo, {x0: -40, x1: 40, y0: 0, y1: 34});
  const area = (64 * 30) / (geo.pitch[0] * geo.pitch[1]);
  check(t.count > 0.8 * area && t.count < 1.2 * area,
        `the scale target (64 x 30 mm on the MLA plane) should be ~${area.toFixed(0)} red lenslets, found ${t.count}`);
  check(Math.abs(t.cx) < 2 && Math.abs(t.cy - 17) < 2,
        `the red scale target should be centred at (0, 17) mm, found (${t.cx.toFixed(1)}, ${t.cy.toFixed(1)})`);
  pass(`the scale target on z = 0 is red: ${t.count} lenslets centred at (${t.cx.toFixed(1)}, ${t.cy.toFixed(1)}) mm`);
}

// Presses an arrow key on a range until its value has moved by about `delta`; returns the presses.
async function nudgeRange(page, id, delta) {
  const step = Number(await page.$eval(`#${id}-range`, (e) => e.step));
  const n = Math.round(Math.abs(delta) / step);
  await page.focus(`#${id}-range`);
  for (let k = 0; k < n; ++k) await page.keyboard.press(delta > 0 ? 'ArrowRight' : 'ArrowLeft');
  return n;
}

// Turned about y by θ, the target plane crosses z = 0 on a vertical line; translating the scene
// by tz toward the viewer moves that line to x = tz / tan θ (R = Rz Ry Rx, right-handed).
async function checkBandMoves(page, geo, api) {
  const theta = 20;
  await setNumber(page, 'ry', theta);
  await settle(page, `rotate y = ${theta}`);
  const band = async (what) => {
    await settle(page, what);
    const s = await api.get('/api/state');
    const tz = s.placement.translate_mm[2];
    const predicted = tz / Math.tan((s.placement.rotate_deg[1] * Math.PI) / 180);
    const b = redIn(await readPixels(page, '#preview0'), geo, {x0: -28, x1: 28, y0: 4, y1: 30});
    check(b.count >= 15, `${what}: the tilted target's red band has only ${b.count} lenslets`);
    check(Math.abs(b.cx - predicted) <= 2,
          `${what}: the red band should be at x = ${predicted.toFixed(1)} mm (tz ${tz} / tan ${theta}°), ` +
          `found ${b.cx.toFixed(1)} mm`);
    pass(`${what}: the red band is at x = ${b.cx.toFixed(1)} mm, predicted ${predicted.toFixed(1)} mm (tz = ${tz} mm)`);
    return b.cx;
  };
  const x0 = await band('rotate y 20°, tz 0');
  const presses = await nudgeRange(page, 'tz', 4);
  const x1 = await band(`tz +4 mm (${presses} ArrowRight on #tz-range)`);
  await nudgeRange(page, 'tz', -8);
  const x2 = await band('tz -4 mm (ArrowLeft on #tz-range)');
  check(x1 > x0 && x2 < x0, 'moving the scene toward the viewer must move the band to +x, away to -x');
}

// A trained field: moving it along z must change which lenslets see the MLA plane.
async function checkFieldMoves(page) {
  const before = await readPixels(page, '#preview0');
  await nudgeRange(page, 'tz', 4);
  await settle(page, 'tz +4 mm');
  const after = await readPixels(page, '#preview0');
  check(before.red.length + after.red.length > 0, 'no on-plane (red) lenslets before or after moving the field 4 mm in z');
  const key = (px) => px.red.map((p) => p.join(',')).join(';');
  check(key(before) !== key(after), 'moving the field 4 mm in z did not change the red lenslets');
  pass(`moving the field 4 mm in z changed the red lenslets (${before.red.length} -> ${after.red.length})`);
}

// Changes go over the live channel (a WebSocket); closed, the page carries on over HTTP and
// opens it again.
async function checkLiveChannel(page, geo) {
  const live = () => page.evaluate(() => ({...window.inimLive}));
  check((await live()).open, 'the live channel (WebSocket /api/live) is not open');
  const before = await live();
  await nudgeRange(page, 'tz', 1);
  await settle(page, 'tz +1 mm over the live channel');
  check((await live()).httpChanges === before.httpChanges, 'a change went over HTTP while the live channel was open');
  await page.evaluate(() => window.inimLive.close());
  await page.waitForFunction(() => !window.inimLive.open, {timeout: WAIT_MS, polling: 20});
  await nudgeRange(page, 'tz', -1);
  await settle(page, 'tz -1 mm with the live channel closed');
  check((await live()).httpChanges > before.httpChanges, 'with the live channel closed, the change did not go over HTTP');
  await checkLevel0(page, geo);
  await page.waitForFunction(() => window.inimLive.open, {timeout: WAIT_MS, polling: 20})
    .catch(() => { throw new TestFailure('the live channel did not open again after a change'); });
  pass('changes go over the live channel; closed, over HTTP, and it opens again');
}

async function waitDiagram(page) {
  await page.waitForFunction(() => window.inimDiagram.revision === window.inimSync.revision,
                             {timeout: WAIT_MS, polling: 50})
    .catch(() => { throw new TestFailure('the diagram of the current revision did not arrive'); });
  return (await readPixels(page, '#diagram')).hash;
}

// 400: the status line names the key, the control goes back to the server's value.
async function checkRejected(page, api) {
  const before = await api.get('/api/state');
  await setNumber(page, 'vcp', 20000);
  await page.waitForFunction(() => document.querySelector('#status').classList.contains('error'),
                             {timeout: WAIT_MS, polling: 50})
    .catch(() => { throw new TestFailure('vcp_mm 20000 (out of range) did not show an error in #status'); });
  await settle(page, 'after the 400');
  const status = await page.$eval('#status', (e) => e.textContent);
  check(/vcp/.test(status), `the status line should name vcp_mm: "${status}"`);
  const after = await api.get('/api/state');
  const shown = Number(await page.$eval('#vcp-num', (e) => e.value));
  check(after.revision === before.revision && after.vcp_mm === before.vcp_mm, 'a 400 must change nothing');
  check(shown === after.vcp_mm, `#vcp-num shows ${shown}, the server has ${after.vcp_mm}`);
  pass(`vcp_mm 20000 -> 400 shown ("${status}"), #vcp-num back at ${shown}`);

  // Two changes in one frame travel as one patch: the valid one must survive the refused one.
  await page.evaluate(() => {
    const set = (id, v) => {
      const e = document.querySelector(id);
      e.value = v;
      e.dispatchEvent(new Event('input', {bubbles: true}));
    };
    set('#vd-num', '420');
    set('#vcp-num', '20000');
  });
  await settle(page, 'a merged patch with a refused key');
  const merged = await api.get('/api/state');
  const vcpShown = Number(await page.$eval('#vcp-num', (e) => e.value));
  check(merged.viewing_distance_mm === 420 && merged.vcp_mm === after.vcp_mm && vcpShown === after.vcp_mm,
        `vd 420 + vcp 20000 in one frame: the server has vd ${merged.viewing_distance_mm}, vcp ${merged.vcp_mm}; ` +
        `#vcp-num shows ${vcpShown}`);
  pass('a refused key does not take the valid change made in the same frame with it');
}

const placementKey = (s) => JSON.stringify([s.placement, s.vcp_mm, s.layout, s.viewing_distance_mm, s.display]);

async function checkHistory(page, api) {
  const moved = await api.get('/api/state');
  const defaults = (await api.get('/api/info')).defaults;
  await page.click('#reset');
  await settle(page, 'reset');
  check(placementKey(await api.get('/api/state')) === placementKey(defaults), 'Reset must restore /api/info defaults');
  await page.click('#undo');
  await settle(page, 'undo');
  check(placementKey(await api.get('/api/state')) === placementKey(moved), 'Undo after Reset must restore the state');
  await blur(page);
  await page.keyboard.down('Control');
  await page.keyboard.down('Shift');
  await page.keyboard.press('KeyZ');
  await page.keyboard.up('Shift');
  await page.keyboard.up('Control');
  await settle(page, 'Ctrl+Shift+Z');
  check(placementKey(await api.get('/api/state')) === placementKey(defaults), 'Ctrl+Shift+Z must redo the Reset');
  pass('Reset, Undo and Ctrl+Shift+Z (redo) move the server state as expected');
}

const PLACED = {tx: 3.5, ty: -2.25, tz: 4, rx: 5, ry: -10, rz: 15, scale: 1.25, vcp: 80, vd: 400};

// The toed-in layout needs a display whose EIs fit the panel when toed in (the paper's
// prototype's do not), so the toed-in display file goes with it when there is one.
async function placeNonDefault(page, api, info) {
  const toedIn = (info.displays || []).find((d) => /toed-in\.json$/.test(d.path));
  const layout = toedIn ? 'toed-in' : 'parallel';
  if (toedIn) {
    await page.select('#display', toedIn.path);
    await settle(page, `display ${toedIn.path}`);
  }
  await page.select('#layout', layout);
  await settle(page, `layout ${layout}`);
  // A trained field's scale is its own (mm per field unit): 1.25 times that.
  const placed = {...PLACED, scale: Number((info.defaults.placement.scale[0] * PLACED.scale).toPrecision(4))};
  for (const [id, v] of Object.entries(placed)) await setNumber(page, id, v);
  await settle(page, 'the non-default placement');
  const s = await api.get('/api/state');
  const status = await page.$eval('#status', (e) => e.textContent);
  const p = s.placement;
  const got = [...p.translate_mm, ...p.rotate_deg, p.scale[0], s.vcp_mm, s.viewing_distance_mm];
  const want = [placed.tx, placed.ty, placed.tz, placed.rx, placed.ry, placed.rz, placed.scale, placed.vcp, placed.vd];
  check(JSON.stringify(got) === JSON.stringify(want) && p.scale.every((v) => v === placed.scale) &&
        s.layout === layout && (!toedIn || s.display === toedIn.path),
        `typed ${JSON.stringify(placed)}, layout ${layout}, display ${toedIn ? toedIn.path : '(as it was)'}; the server has ${JSON.stringify(s)} (status: "${status}")`);
  pass('typed values reach the server state');
  return s;
}

async function runJob(page, button, what) {
  const before = await page.evaluate(() => (window.inimLastJob ? window.inimLastJob.id : 0));
  await page.click(button);
  const job = await page.waitForFunction(
      (b) => window.inimLastJob && window.inimLastJob.id > b &&
             ['done', 'failed'].includes(window.inimLastJob.state) && window.inimLastJob,
      {timeout: EIA_TIMEOUT_MS, polling: 100}, before)
    .catch(async () => {
      const last = await page.evaluate(() => window.inimLastJob).catch(() => null);
      throw new TestFailure(`the ${what} job did not finish in ${EIA_TIMEOUT_MS / 1000} s; last: ${JSON.stringify(last)}`);
    });
  const j = await job.jsonValue();
  check(j.state === 'done', `the ${what} job failed: ${j.error}`);
  return j;
}

function runInim(inim, args, what) {
  return withTimeout(new Promise((resolveRun, reject) => {
    const child = spawn(inim, args, {stdio: ['ignore', 'ignore', 'pipe']});
    let err = '';
    child.stderr.on('data', (d) => { err += d; });
    child.on('error', reject);
    child.on('exit', (code) => (code === 0 ? resolveRun()
      : reject(new TestFailure(`${what} failed (exit ${code}): inim ${args.join(' ')}\n${err}`))));
  }), EIA_TIMEOUT_MS, what);
}

function sameBytes(a, b) {
  const x = readFileSync(a);
  const y = readFileSync(b);
  if (x.equals(y)) return;
  let i = 0;
  while (i < Math.min(x.length, y.length) && x[i] === y[i]) ++i;
  throw new TestFailure(`${a} and ${b} differ (${x.length} vs ${y.length} bytes, first at byte ${i})`);
}

const vec = (v) => v.join(',');

async function checkRunFile(page, api, info, args) {
  const s = await placeNonDefault(page, api, info);
  await typeInto(page, '#run-name', 'placement');
  const j = await runJob(page, '#write-run', 'run file');
  check((j.files || []).includes('placement.json'), `the run-file job wrote ${JSON.stringify(j.files)}`);
  const listed = await page.$eval('#written-files', (e) => e.textContent);
  check(listed.includes('placement.json'), '#written-files does not list placement.json');
  const runFile = join(args.out, 'place-out', 'placement.json');
  check(existsSync(runFile), `${runFile} does not exist`);
  pass(`"Write run file" wrote ${runFile}`);
  if (!args.compareEia) return log('skipping the EIA byte comparison (a trained field; --compare-eia to run it)');

  const a = join(args.out, 'a.exr');
  const b = join(args.out, 'b.exr');
  const source = info.field.path.endsWith('.json') ? '--scene' : '--field';
  const flags = [source, info.field.path, '--display', s.display, '--translate-mm', vec(s.placement.translate_mm),
                 '--rotate-deg', vec(s.placement.rotate_deg), '--scale', vec(s.placement.scale),
                 '--vcp-mm', String(s.vcp_mm), '--layout', s.layout,
                 '--viewing-distance-mm', String(s.viewing_distance_mm)];
  const t0 = Date.now();
  await runInim(args.inim, ['eia', '--quiet', '--run', runFile, '--out', a], 'inim eia --run');
  await runInim(args.inim, ['eia', '--quiet', ...flags, '--out', b], 'inim eia with flags');
  sameBytes(a, b);
  sameBytes(a.replace(/\.exr$/, '.png'), b.replace(/\.exr$/, '.png'));
  pass(`inim eia --run placement.json == inim eia ${flags.join(' ')} (EXR and PNG byte-identical, ` +
       `${((Date.now() - t0) / 1000).toFixed(1)} s)`);
}

async function checkPredict(page) {
  await typeInto(page, '#predict-angle', 10);
  await typeInto(page, '#predict-width', 96);
  const j = await runJob(page, '#predict', 'predict');
  await page.waitForFunction(() => !document.querySelector('#predict-panel').hidden &&
                                   document.querySelector('#predict-view').naturalWidth > 0 &&
                                   document.querySelector('#predict-ref').naturalWidth > 0,
                             {timeout: WAIT_MS, polling: 100})
    .catch(() => { throw new TestFailure('the predicted view and its reference were not shown'); });
  const rows = await page.$$eval('#predict-metrics tr', (r) => r.length);
  pass(`"Predict view" (10 deg, 96 px): files ${JSON.stringify(j.files)}, ${rows} metrics shown`);
}

// ------------------------------------------------------------------ latency

function stats(xs) {
  const s = [...xs].sort((a, b) => a - b);
  const q = (p) => (s.length ? Math.round(10 * s[Math.min(s.length - 1, Math.ceil(p * s.length) - 1)]) / 10 : null);
  return {count: s.length, median_ms: q(0.5), p95_ms: q(0.95), max_ms: q(1)};
}

// A mouse drag over #tz-range: 30 moves at ~25 Hz, as a person drags.
async function dragTz(page) {
  const box = await (await page.$('#tz-range')).boundingBox();
  const y = box.y + box.height / 2;
  let x = box.x + box.width / 2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  for (let k = 0; k < 30; ++k) {
    x += k < 15 ? 3 : -3;
    await page.mouse.move(x, y);
    await sleep(40);
  }
  await page.mouse.up();
}

async function measureLatency(page, api, outDir) {
  await settle(page, 'before the drag');
  await page.evaluate(() => { window.inimLatency = []; window.inimServerMs = []; });
  const rev0 = (await api.get('/api/state')).revision;
  const http0 = await page.evaluate(() => window.inimLive.httpChanges);
  const t0 = Date.now();
  await dragTz(page);
  await settle(page, 'after the drag');
  const seconds = (Date.now() - t0) / 1000;
  const {latency, serverMs, live} = await page.evaluate(
      () => ({latency: window.inimLatency, serverMs: window.inimServerMs, live: {...window.inimLive}}));
  check(live.open && live.httpChanges === http0, 'the drag did not go over the live channel alone');
  const revisions = (await api.get('/api/state')).revision - rev0;
  const report = {
    browser_input_to_paint: stats(latency),
    server_level0_painted: stats(serverMs),
    server_api_latency: await api.get('/api/latency'),
    drag: {moves: 30, move_interval_ms: 40, seconds_to_settled: seconds, revisions,
           painted_level0: serverMs.length, painted_per_second: Math.round((10 * serverMs.length) / seconds) / 10},
  };
  writeFileSync(join(outDir, 'place-latency.json'), JSON.stringify(report, null, 2) + '\n');
  const f = (x) => (x === null ? '?' : x.toFixed(1));
  const b = report.browser_input_to_paint;
  const s = report.server_level0_painted;
  log(`latency: browser input -> paint median ${f(b.median_ms)} ms, p95 ${f(b.p95_ms)} ms (${b.count} inputs); ` +
      `server level 0 median ${f(s.median_ms)} ms, p95 ${f(s.p95_ms)} ms; ` +
      `${serverMs.length} frames in ${seconds.toFixed(1)} s (${report.drag.painted_per_second.toFixed(1)}/s), ` +
      `${revisions} revisions`);
  log(`latency report: ${join(outDir, 'place-latency.json')}`);
}

async function screenshot(page, outDir) {
  await page.waitForFunction(() => window.inimPainted.level === 2 && window.inimPainted.revision === window.inimSync.revision,
                             {timeout: WAIT_MS, polling: 100})
    .catch(() => { throw new TestFailure('levels 1 and 2 of the last revision did not arrive once still'); });
  pass('levels 1 and 2 followed once the controls were still');
  const path = join(outDir, 'place-page.png');
  await page.screenshot({path, fullPage: true});
  log(`screenshot: ${path}`);
}

// ------------------------------------------------------------------ main

async function run(args, cleanup) {
  const puppeteer = await loadPuppeteer();
  const server = startServer(args.inim, args.out, args.field);
  cleanup.push(() => stopServer(server.child));
  const url = await server.url;
  const m = /^(http:\/\/127\.0\.0\.1:\d+)\/\?token=([0-9a-f]{32})$/.exec(url);
  check(m, `inim place printed "${url}", expected http://127.0.0.1:PORT/?token=<32 hex digits>`);
  const [, base, token] = m;
  log(`server at ${base}`);
  await checkToken(base, token);
  const api = serverApi(base, token);
  const info = await api.get('/api/info');
  const state = await api.get('/api/state');
  const pitch = Array.isArray(info.display.pitch_mm) ? info.display.pitch_mm : [info.display.pitch_mm, info.display.pitch_mm];
  const geo = {width: info.display.lenslets[0], height: info.display.lenslets[1], pitch};

  const profile = mkdtempSync(join(tmpdir(), 'inim-chromium-'));
  cleanup.push(() => rmSync(profile, {recursive: true, force: true}));
  const browser = await launchBrowser(puppeteer, profile);
  cleanup.push(() => browser.close().catch(() => {}));
  const pageErrors = [];
  const page = await openPage(browser, url, pageErrors);
  pass('the page loaded and painted level 0');

  await checkLevel0(page, geo);
  const diagram0 = await waitDiagram(page);
  if (args.field) await checkFieldMoves(page);
  else {
    await checkDefaultScene(page, geo, state);
    await checkBandMoves(page, geo, api);
  }
  check(await waitDiagram(page) !== diagram0, 'the diagram did not change when the scene moved');
  pass('the diagram follows the placement');
  await checkLevel0(page, geo);
  await checkLiveChannel(page, geo);
  await checkRejected(page, api);
  await checkHistory(page, api);
  await checkRunFile(page, api, info, args);
  if (args.predict) await checkPredict(page);
  await measureLatency(page, api, args.out);
  await screenshot(page, args.out);
  check(pageErrors.length === 0, `the page threw: ${pageErrors.join(' | ')}`);
}

async function main() {
  const args = parseArgs(process.argv.slice(2));
  for (const [path, what] of [[args.inim, 'inim binary'], [CHROMIUM, 'Chromium']]) {
    if (!existsSync(path)) {
      console.error(`place-test: FAIL no ${what} at ${path}`);
      process.exit(1);
    }
  }
  mkdirSync(args.out, {recursive: true});
  const cleanup = [];
  const onSignal = () => { log('interrupted'); Promise.all(cleanup.map((f) => f())).finally(() => process.exit(130)); };
  process.once('SIGINT', onSignal);
  process.once('SIGTERM', onSignal);
  let code = 0;
  const t0 = Date.now();
  try {
    await withTimeout(run(args, cleanup), TOTAL_BUDGET_MS, 'the whole test');
    log(`all checks passed in ${((Date.now() - t0) / 1000).toFixed(1)} s`);
  } catch (e) {
    code = 1;
    console.error(`place-test: FAIL ${e instanceof TestFailure ? e.message : (e && e.stack) || e}`);
    console.error(`place-test: server log: ${join(args.out, 'place-server.log')}`);
  } finally {
    for (const f of cleanup.reverse()) await Promise.race([Promise.resolve().then(f).catch(() => {}), sleep(10000)]);
  }
  process.exit(code);
}

main();
