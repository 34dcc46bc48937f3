/* inim place: the placement page (docs/place-api.md). Plain JavaScript, no framework.
 *
 * Element ids (tests/web/place_browser.mjs relies on them):
 *   #preview0            level-0 lenslet preview (a K x L canvas), #preview1 its level-1 overlay (4K x 4L)
 *   #preview2            level 2, the viewer's view; #diagram the top and side diagrams
 *   #preview-level #preview-meta #counts #latency-readout #preview2-meta #diagram-meta
 *   #tx-range #tx-num  #ty-range #ty-num  #tz-range #tz-num     translation, mm
 *   #rx-range #rx-num  #ry-range #ry-num  #rz-range #rz-num     rotation, deg
 *   #scale-range (log10 of the scale) #scale-num (the scale)    uniform scale; #scale-note
 *   #vcp-range #vcp-num (D_VCP, mm)  #vd-range #vd-num (viewing distance, mm)
 *   #layout #display (selects) #display-info #field-info
 *   #undo #redo #reset
 *   #run-name #write-run #write-eia #write-sdf
 *   #predict-angle #predict-width #predict-name #predict
 *   #job-state #job-progress #jobs #written-files #out-dir
 *   #predict-panel #predict-view #predict-ref #predict-metrics #predict-meta
 *   #status              the status line (class "error" after a refused or failed request)
 *
 * Globals for tests:
 *   window.inimLatency   ms from each control input to the paint of the first level-0 image showing it
 *   window.inimServerMs  X-Inim-Server-Ms of each painted level-0 image
 *   window.inimPainted   {revision, level} of the last painted main preview
 *   window.inimDiagram   {revision} of the diagram shown
 *   window.inimSync      {revision, busy, pending}: the server's revision, a PUT cycle in flight, a change waiting
 *   window.inimSettled() true when no change waits and the current revision's level 0 is painted
 *   window.inimLive      {open, httpChanges, close()}: whether changes go over the live channel (a
 *                        WebSocket), how many went over HTTP; close() closes the channel, the page
 *                        carries on over HTTP and opens it again at the next change (2 s after a
 *                        refused attempt)
 *   window.inimJobs      {id: last status}; window.inimLastJob
 */
(() => {
  'use strict';

  const TOKEN = new URLSearchParams(location.search).get('token') || '';
  const IMAGE_TIMEOUT_MS = 60000;
  const HISTORY_MAX = 200;
  const $ = (id) => document.getElementById(id);
  const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

  window.inimLatency = [];
  window.inimServerMs = [];
  window.inimPainted = {revision: -1, level: -1};
  window.inimDiagram = {revision: -1};
  window.inimSync = {revision: -1, busy: false, pending: false};
  window.inimJobs = {};
  window.inimLastJob = null;

  // ---------------------------------------------------------------- HTTP

  // Every request carries the token header (the cookie alone is not relied on).
  function request(path, method = 'GET', body, timeoutMs = 0) {
    const headers = {'X-Inim-Token': TOKEN};
    const init = {method, headers, cache: 'no-store', credentials: 'same-origin'};
    if (body !== undefined) {
      headers['Content-Type'] = 'application/json';
      init.body = JSON.stringify(body);
    }
    if (timeoutMs > 0 && window.AbortSignal && AbortSignal.timeout) init.signal = AbortSignal.timeout(timeoutMs);
    return fetch(path, init);
  }

  async function requestJson(path, method = 'GET', body) {
    const res = await request(path, method, body, 30000);
    let data = null;
    try { data = await res.json(); } catch (e) { data = null; }
    return {status: res.status, ok: res.ok, data};
  }

  const errorText = (r) => (r.data && r.data.error) || `HTTP ${r.status}`;

  // An image answer with its headers; null when stale (409), which the page drops silently.
  async function fetchImage(path) {
    const res = await request(path, 'GET', undefined, IMAGE_TIMEOUT_MS);
    if (res.status === 409) return null;
    if (!res.ok) {
      let msg = `HTTP ${res.status}`;
      try { msg = (await res.json()).error || msg; } catch (e) { /* not JSON */ }
      throw new Error(`${path.split('?')[0]}: ${msg}`);
    }
    const h = (k) => res.headers.get(k);
    let counts = null;
    try { counts = JSON.parse(h('X-Inim-Counts') || 'null'); } catch (e) { counts = null; }
    return {
      blob: await res.blob(),
      revision: Number(h('X-Inim-Revision')),
      level: Number(h('X-Inim-Level')),
      serverMs: Number(h('X-Inim-Server-Ms')),
      counts,
    };
  }

  // Decodes off screen, then swaps the element's source (no blank frame), freeing the old blob;
  // false, showing nothing, when `wanted` says after the decode that a newer image won.
  async function showBlob(img, blob, wanted = () => true) {
    const url = URL.createObjectURL(blob);
    const probe = new Image();
    probe.src = url;
    try { await probe.decode(); } catch (e) { URL.revokeObjectURL(url); throw new Error('undecodable image'); }
    if (!wanted()) {
      URL.revokeObjectURL(url);
      return false;
    }
    const old = img.dataset.url;
    img.src = url;
    img.dataset.url = url;
    if (old) URL.revokeObjectURL(old);
    return true;
  }

  // Level 0 goes to a canvas, decoded in the page (createImageBitmap) with the PNG's values as
  // they are: an <img> from a blob URL took a round trip through the browser process per frame,
  // 7-10 ms of each input's latency on two busy cores and the worst of its spikes.
  async function drawBlob(canvas, blob, wanted = () => true) {
    let bitmap;
    try {
      bitmap = await createImageBitmap(blob, {colorSpaceConversion: 'none', premultiplyAlpha: 'none'});
    } catch (e) {
      throw new Error('undecodable image');
    }
    try {
      if (!wanted()) return false;
      if (canvas.width !== bitmap.width || canvas.height !== bitmap.height) {
        canvas.width = bitmap.width;
        canvas.height = bitmap.height;
      }
      canvas.getContext('2d').drawImage(bitmap, 0, 0);
      return true;
    } finally {
      bitmap.close();
    }
  }

  // ---------------------------------------------------------------- the live channel

  // State changes go over one WebSocket (/api/live) while it is open: the server answers each
  // with the new state and pushes that revision's level 0 once it is ready, two fetches fewer per
  // change on a main thread busy with the drag. Without it (refused, closed) changes go over HTTP.
  const live = {ws: null, open: false, waiting: [], failedAt: -Infinity};
  window.inimLive = {open: false, httpChanges: 0, close: () => live.ws && live.ws.close()};

  function openLive() {
    if (live.ws || !window.WebSocket || performance.now() - live.failedAt < 2000) return;
    const scheme = location.protocol === 'https:' ? 'wss:' : 'ws:';
    const ws = new WebSocket(`${scheme}//${location.host}/api/live?token=${encodeURIComponent(TOKEN)}`);
    ws.binaryType = 'arraybuffer';
    live.ws = ws;
    ws.onopen = () => { live.open = window.inimLive.open = true; };
    ws.onmessage = (ev) => onLiveMessage(ev.data);
    ws.onclose = () => {
      if (!live.open) live.failedAt = performance.now();  // refused: not again for 2 s
      live.ws = null;
      live.open = window.inimLive.open = false;
      const waiting = live.waiting;
      live.waiting = [];
      waiting.forEach((w) => w.fallback());
    };
  }

  // A state patch over the live channel, answered as requestJson answers (with `pushed`: its
  // level 0 will come by itself). A patch whose answer a closing channel took is sent again over
  // HTTP: a patch sets values, so applying it twice is applying it once.
  function livePut(patch) {
    return new Promise((resolve, reject) => {
      live.waiting.push({resolve, fallback: () => requestJson('/api/state', 'PUT', patch).then(resolve, reject)});
      live.ws.send(JSON.stringify(patch));
    });
  }

  function onLiveMessage(data) {
    if (typeof data === 'string') {
      let m;
      try { m = JSON.parse(data); } catch (e) { m = {error: 'an unreadable answer on the live channel', status: 500}; }
      const w = live.waiting.shift();
      if (w) w.resolve(m.state ? {status: 200, ok: true, data: m.state, pushed: true} : {status: m.status || 500, ok: false, data: m});
      return;
    }
    const a = liveImage(data);
    if (a.error) showError(new Error(`level 0: ${a.error}`));
    else showLevel0Image(a).catch(showError);
  }

  // A binary frame: the header's length (4 bytes, big-endian), the header (JSON), the PNG.
  function liveImage(buf) {
    const n = new DataView(buf).getUint32(0);
    const h = JSON.parse(new TextDecoder().decode(new Uint8Array(buf, 4, n)));
    return {blob: new Blob([new Uint8Array(buf, 4 + n)], {type: 'image/png'}), revision: Number(h.revision),
            level: 0, serverMs: Number(h.server_ms), counts: h.counts || null, error: h.error};
  }

  // ---------------------------------------------------------------- status line

  function setStatus(text, kind = '') {
    const s = $('status');
    s.textContent = text;
    s.className = 'status' + (kind ? ' ' + kind : '');
  }
  const showError = (e) => setStatus(e instanceof Error ? e.message : String(e), 'error');

  // ---------------------------------------------------------------- the state model

  const vec3 = (v) => (Array.isArray(v) ? [0, 1, 2].map((i) => Number(v[i])) : [Number(v), Number(v), Number(v)]);
  const isObject = (v) => v !== null && typeof v === 'object' && !Array.isArray(v);

  // The keys the page controls, scale always per axis.
  function normalise(s) {
    const p = s.placement || {};
    return {
      placement: {scale: vec3(p.scale ?? 1), rotate_deg: vec3(p.rotate_deg ?? 0), translate_mm: vec3(p.translate_mm ?? 0)},
      vcp_mm: Number(s.vcp_mm),
      layout: s.layout,
      viewing_distance_mm: Number(s.viewing_distance_mm),
      display: s.display,
    };
  }
  const copyState = (s) => JSON.parse(JSON.stringify(s));
  const sameState = (a, b) => JSON.stringify(a) === JSON.stringify(b);

  function mergePatch(a, b) {
    const out = {...a};
    for (const [k, v] of Object.entries(b)) out[k] = isObject(v) && isObject(out[k]) ? mergePatch(out[k], v) : v;
    return out;
  }

  let model = null;     // what the controls show (the user's wish)
  let defaults = null;  // /api/info defaults, for Reset
  let info = null;

  // ---------------------------------------------------------------- controls

  function niceStep(x) {
    const p = Math.pow(10, Math.floor(Math.log10(x)));
    const m = x / p;
    return Number(((m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p).toPrecision(1));
  }
  const decimalsOf = (step) => Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  const formatNum = (v) => String(Number(Number(v).toPrecision(12)));

  function vecSpec(id, label, unit, spanKey, key, i) {
    return {
      id, label, unit, spanKey,
      get: (m) => m.placement[key][i],
      set: (m, v) => {
        m.placement[key][i] = v;
        return {placement: {[key]: m.placement[key].slice()}};
      },
    };
  }

  function scalarSpec(id, label, unit, key) {
    return {
      id, label, unit, spanKey: key,
      get: (m) => m[key],
      set: (m, v) => { m[key] = v; return {[key]: v}; },
    };
  }

  // The scale slider is logarithmic: its value is log10(scale); the scale is sent uniform.
  const SCALE_SPEC = {
    id: 'scale', label: 'scale', unit: '×', spanKey: 'scale', log: true,
    get: (m) => m.placement.scale[0],
    set: (m, v) => { m.placement.scale = [v, v, v]; return {placement: {scale: v}}; },
  };

  const PLACEMENT_SPECS = [
    vecSpec('tx', 'translate x', 'mm', 'translate_mm', 'translate_mm', 0),
    vecSpec('ty', 'translate y', 'mm', 'translate_mm', 'translate_mm', 1),
    vecSpec('tz', 'translate z', 'mm', 'translate_mm', 'translate_mm', 2),
    vecSpec('rx', 'rotate x', 'deg', 'rotate_deg', 'rotate_deg', 0),
    vecSpec('ry', 'rotate y', 'deg', 'rotate_deg', 'rotate_deg', 1),
    vecSpec('rz', 'rotate z', 'deg', 'rotate_deg', 'rotate_deg', 2),
    SCALE_SPEC,
  ];
  const VCP_SPEC = scalarSpec('vcp', 'D_VCP', 'mm', 'vcp_mm');
  const VD_SPEC = scalarSpec('vd', 'view dist.', 'mm', 'viewing_distance_mm');
  const ALL_SPECS = [...PLACEMENT_SPECS, VCP_SPEC, VD_SPEC];

  const FALLBACK_SPANS = {
    translate_mm: [-100, 100], rotate_deg: [-180, 180], scale: [0.01, 100], vcp_mm: [-50, 300],
    viewing_distance_mm: [100, 2000],
  };

  function setSpan(spec, span) {
    const [lo, hi] = Array.isArray(span) && span.length === 2 ? span.map(Number) : FALLBACK_SPANS[spec.spanKey];
    const range = $(spec.id + '-range');
    if (spec.log) {
      range.min = Math.log10(lo);
      range.max = Math.log10(hi);
      range.step = 0.001;
    } else {
      spec.step = niceStep((hi - lo) / 1000);
      range.min = lo;
      range.max = hi;
      range.step = spec.step;
    }
  }

  function makeSlider(spec, container) {
    const row = document.createElement('div');
    row.className = 'slider';
    row.id = spec.id + '-row';
    const label = document.createElement('label');
    label.className = 'label';
    label.htmlFor = spec.id + '-num';
    label.textContent = `${spec.label} (${spec.unit})`;
    const range = document.createElement('input');
    range.type = 'range';
    range.id = spec.id + '-range';
    range.setAttribute('aria-label', spec.label);
    const num = document.createElement('input');
    num.type = 'number';
    num.id = spec.id + '-num';
    num.step = 'any';
    row.append(label, range, num);
    container.append(row);

    range.addEventListener('input', () => onControl(spec, fromRange(spec, range.value), 'range'));
    range.addEventListener('change', markCommit);
    num.addEventListener('input', () => {
      const v = Number(num.value);
      if (num.value.trim() !== '' && Number.isFinite(v)) onControl(spec, v, 'num');
    });
    num.addEventListener('change', () => {
      if (num.value.trim() === '' || !Number.isFinite(Number(num.value))) num.value = formatNum(spec.get(model));
      markCommit();
    });
  }

  // A range position as the value sent: rounded to the step, so the number shown is the one sent.
  function fromRange(spec, raw) {
    const x = Number(raw);
    if (spec.log) return Number(Math.pow(10, x).toPrecision(4));
    return Number(x.toFixed(decimalsOf(spec.step)));
  }
  const toRange = (spec, v) => (spec.log ? Math.log10(Math.max(v, 1e-12)) : v);

  function showSpec(spec, skip) {
    const v = spec.get(model);
    if (skip !== 'range') $(spec.id + '-range').value = toRange(spec, v);
    if (skip !== 'num') $(spec.id + '-num').value = formatNum(v);
  }

  function setControls() {
    for (const spec of ALL_SPECS) showSpec(spec);
    $('layout').value = model.layout;
    ensureDisplayOption(model.display);
    $('display').value = model.display;
    showLayoutHint();
    showScaleNote();
  }

  function showLayoutHint() {
    $('vd-row').classList.toggle('disabled', model.layout !== 'toed-in');
    $('vd-row').title = model.layout === 'toed-in' ? '' : 'used by the toed-in layout (and the level-2 camera)';
  }

  function showScaleNote() {
    const s = model.placement.scale;
    const uniform = s[0] === s[1] && s[1] === s[2];
    $('scale-note').hidden = uniform;
    $('scale-note').textContent = uniform ? '' : `per-axis scale ${s.map(formatNum).join(', ')}; the slider makes it uniform`;
  }

  function ensureDisplayOption(path) {
    const sel = $('display');
    if ([...sel.options].some((o) => o.value === path)) return;
    sel.append(new Option(path.split('/').pop(), path));
  }

  function onControl(spec, value, source) {
    const t0 = performance.now();
    const patch = spec.set(model, value);
    showSpec(spec, source);
    if (spec === SCALE_SPEC) showScaleNote();
    change(patch, t0);
  }

  function buildControls(spans) {
    for (const spec of PLACEMENT_SPECS) makeSlider(spec, $('sliders-placement'));
    makeSlider(VCP_SPEC, $('sliders-synthesis'));
    makeSlider(VD_SPEC, $('sliders-distance'));
    applySpans(spans);
    $('layout').addEventListener('change', () => {
      const t0 = performance.now();
      model.layout = $('layout').value;
      showLayoutHint();
      change({layout: model.layout}, t0);
      markCommit();
    });
    $('display').addEventListener('change', () => {
      const t0 = performance.now();
      model.display = $('display').value;
      change({display: model.display}, t0);
      markCommit();
      displayChanged = true;
    });
  }

  function applySpans(spans) {
    for (const spec of ALL_SPECS) setSpan(spec, (spans || {})[spec.spanKey]);
    if (model) for (const spec of ALL_SPECS) showSpec(spec, 'num');
  }

  // ---------------------------------------------------------------- sending changes

  // One change at a time (over the live channel, or a PUT); changes made meanwhile merge into one
  // pending patch, so dragging never queues stale states. Each revision's level 0 comes beside
  // (pushed, or fetched: putAndShow), and is painted unless a newer one was painted first.
  const sync = {pending: null, busy: false, flushQueued: false, revision: -1};
  const inputs = [];                 // [{seq, t0}] not yet painted
  const revisionInputs = new Map();  // revision -> last input seq it includes
  let inputSeq = 0;
  let commitWanted = false;
  let displayChanged = false;
  let idleWaiters = [];

  function publishSync() {
    window.inimSync = {revision: sync.revision, busy: sync.busy, pending: sync.pending !== null};
  }

  function change(patch, t0) {
    openLive();  // (again, when it closed)
    inputs.push({seq: ++inputSeq, t0});
    sync.pending = mergePatch(sync.pending || {}, patch);
    publishSync();
    scheduleFlush();
  }

  // Right after the input's handler (no frame's wait): a PUT under way merges what follows.
  function scheduleFlush() {
    if (sync.flushQueued) return;
    sync.flushQueued = true;
    queueMicrotask(flush);
  }

  async function flush() {
    sync.flushQueued = false;
    if (sync.busy || !sync.pending) return;
    const patch = sync.pending;
    const upTo = inputSeq;
    sync.pending = null;
    sync.busy = true;
    publishSync();
    try {
      await putAndShow(patch, upTo);
    } catch (e) {
      showError(e);
    } finally {
      sync.busy = false;
      publishSync();
      if (sync.pending) scheduleFlush();  // the changes made meanwhile, merged
      else onIdle();
    }
  }

  async function putAndShow(patch, upTo) {
    const r = live.open ? await livePut(patch) : await requestJson('/api/state', 'PUT', patch);
    if (r.status === 400) {
      // Coalescing may have merged valid changes with the refused one: keep those.
      const message = Object.keys(patch).length > 1 ? await putKeyByKey(patch) : errorText(r);
      await rejected(message, upTo);
      if (sync.revision !== shown.level0) await showLevel0(sync.revision);
      return;
    }
    if (!r.ok) throw new Error(`PUT /api/state: ${errorText(r)}`);
    sync.revision = Number(r.data.revision);
    revisionInputs.set(sync.revision, upTo);
    if ($('status').classList.contains('error')) setStatus('ok', 'ok');
    // Not awaited: the next change goes out while this one renders. The server finishes a level 0
    // it has started and serves it, so dragging shows frames and each input waits for at most
    // the render under way plus its own. Over the live channel it comes by itself.
    if (r.pushed) return;
    window.inimLive.httpChanges++;
    showLevel0(sync.revision).catch(showError);
  }

  // Sends the keys of a refused patch one at a time; the first refusal's text (null: none).
  async function putKeyByKey(patch) {
    let message = null;
    for (const [k, v] of Object.entries(patch)) {
      const r = await requestJson('/api/state', 'PUT', {[k]: v});
      if (r.status === 400) message = message || errorText(r);
      else if (!r.ok) throw new Error(`PUT /api/state: ${errorText(r)}`);
    }
    return message;
  }

  // A 400 changed nothing: show why, and put the controls back to the server's state.
  async function rejected(message, upTo) {
    if (message) setStatus(message, 'error');
    while (inputs.length && inputs[0].seq <= upTo) inputs.shift();
    sync.pending = null;
    commitWanted = false;
    const r = await requestJson('/api/state');
    if (!r.ok) throw new Error(`GET /api/state: ${errorText(r)}`);
    model = normalise(r.data);
    sync.revision = Number(r.data.revision);
    setControls();
    commitHistory();  // what the server did take (a no-op when it took nothing)
  }

  function onIdle() {
    publishSync();
    if (commitWanted) {
      commitWanted = false;
      commitHistory();
    }
    const rev = sync.revision;
    refreshDiagram(rev);
    progressive(rev).catch(showError);
    if (displayChanged) {
      displayChanged = false;
      loadInfo().catch(showError);
    }
    const waiters = idleWaiters;
    idleWaiters = [];
    waiters.forEach((w) => w());
  }

  const isIdle = () => !sync.busy && !sync.pending && !sync.flushQueued;
  const whenIdle = () => (isIdle() ? Promise.resolve() : new Promise((r) => idleWaiters.push(r)));

  window.inimSettled = () => sync.revision >= 0 && isIdle() && window.inimPainted.revision === sync.revision;

  // ---------------------------------------------------------------- previews

  const shown = {level0: -1, level1: -1, level2: -1, diagram: -1};

  async function showLevel0(rev) {
    const a = await fetchImage(`/api/preview?level=0&revision=${rev}`);
    if (a) await showLevel0Image(a);
  }

  async function showLevel0Image(a) {
    if (a.revision <= shown.level0) return;
    if (!(await drawBlob($('preview0'), a.blob, () => a.revision > shown.level0))) return;
    shown.level0 = a.revision;
    if (shown.level1 !== a.revision) $('preview1').hidden = true;
    $('preview2').classList.toggle('stale', shown.level2 !== a.revision);
    $('diagram').classList.toggle('stale', shown.diagram !== a.revision);
    showMeta(a);
    refreshDiagram(a.revision);
    requestAnimationFrame(() => painted(a));
  }

  // Runs in the frame that shows the image: the end of each input's latency.
  function painted(a) {
    const t1 = performance.now();
    const upTo = revisionInputs.get(a.revision);
    if (upTo !== undefined) {
      while (inputs.length && inputs[0].seq <= upTo) window.inimLatency.push(t1 - inputs.shift().t0);
      for (const r of revisionInputs.keys()) if (r <= a.revision) revisionInputs.delete(r);
    }
    if (Number.isFinite(a.serverMs)) window.inimServerMs.push(a.serverMs);
    if (a.revision >= window.inimPainted.revision) window.inimPainted = {revision: a.revision, level: 0};
    showLatency();
  }

  function showMeta(a) {
    $('preview-level').textContent = `level ${a.level}`;
    $('preview-meta').textContent =
        `revision ${a.revision} · server ${Number.isFinite(a.serverMs) ? a.serverMs.toFixed(1) : '?'} ms`;
    if (a.level === 0) showCounts(a.counts);
  }

  // Level 0's counts: one per lenslet, the numbers a person compares.
  function showCounts(c) {
    $('counts').textContent = c
      ? `lenslets: on plane ${c.on_plane} · real ${c.real} · virtual ${c.virtual} · no hit ${c.missed}`
      : '';
  }

  function median(xs) {
    if (!xs.length) return NaN;
    const s = [...xs].sort((a, b) => a - b);
    return s[Math.floor((s.length - 1) / 2)];
  }

  function showLatency() {
    const l = window.inimLatency;
    if (!l.length) return;
    $('latency-readout').textContent =
        `input → paint: last ${l[l.length - 1].toFixed(0)} ms, median ${median(l).toFixed(0)} ms (${l.length})`;
  }

  // Levels 1 and 2 once the user has stopped; dropped when the state moves on.
  let progressiveRev = -1;  // the revision levels 1 and 2 are being fetched for

  async function progressive(rev) {
    if (rev < 0 || shown.level2 === rev || progressiveRev === rev) return;
    progressiveRev = rev;
    try {
      await fetchLevels12(rev);
    } finally {
      if (progressiveRev === rev) progressiveRev = -1;
    }
  }

  async function fetchLevels12(rev) {
    const current = () => rev === sync.revision && isIdle();
    if (shown.level1 !== rev) {
      const a1 = await fetchImage(`/api/preview?level=1&revision=${rev}`);
      if (!a1 || !current() || shown.level0 !== rev) return;
      await showBlob($('preview1'), a1.blob);
      shown.level1 = rev;
      $('preview1').hidden = false;
      showMeta(a1);
      window.inimPainted = {revision: rev, level: 1};
    }
    const a2 = await fetchImage(`/api/preview?level=2&revision=${rev}`);
    if (!a2 || !current()) return;
    await showBlob($('preview2'), a2.blob);
    shown.level2 = rev;
    $('preview2').classList.remove('stale');
    $('preview2-meta').textContent = `revision ${rev} · server ${a2.serverMs.toFixed(0)} ms`;
    window.inimPainted = {revision: rev, level: 2};
  }

  // The diagram follows every revision; one request at a time, always for the newest. While the
  // controls move, a load starts at most every DIAGRAM_DRAG_MS: decoding and drawing the 900-px
  // diagram on every frame took the cores the lenslet preview needs (on 2 cores the drag's
  // input-to-paint p95 was 120-160 ms with it, 75-90 ms without).
  const DIAGRAM_DRAG_MS = 400;
  const diagramLoad = {busy: false, wanted: -1, startedAt: -Infinity, timer: null};

  function refreshDiagram(rev) {
    diagramLoad.wanted = Math.max(diagramLoad.wanted, rev);
    if (diagramLoad.busy || shown.diagram >= diagramLoad.wanted) return;
    const wait = isIdle() ? 0 : diagramLoad.startedAt + DIAGRAM_DRAG_MS - performance.now();
    clearTimeout(diagramLoad.timer);
    diagramLoad.timer = null;
    if (wait > 0) {
      diagramLoad.timer = setTimeout(() => refreshDiagram(diagramLoad.wanted), wait);
      return;
    }
    const target = diagramLoad.wanted;
    diagramLoad.busy = true;
    diagramLoad.startedAt = performance.now();
    loadDiagram(target)
      .catch(showError)
      .finally(() => {
        diagramLoad.busy = false;
        if (diagramLoad.wanted > target) refreshDiagram(diagramLoad.wanted);
      });
  }

  async function loadDiagram(rev) {
    const a = await fetchImage(`/api/diagram?revision=${rev}`);
    if (!a || a.revision < shown.diagram) return;
    await showBlob($('diagram'), a.blob);
    shown.diagram = a.revision;
    $('diagram').classList.toggle('stale', a.revision !== sync.revision);
    $('diagram-meta').textContent = `revision ${a.revision}`;
    window.inimDiagram = {revision: a.revision};
  }

  // ---------------------------------------------------------------- undo, redo, reset

  const undoStack = {list: [], at: -1};  // committed states; `at` is the one shown

  function markCommit() { commitWanted = true; if (isIdle()) onIdle(); }

  function commitHistory() {
    const s = copyState(model);
    if (undoStack.at >= 0 && sameState(undoStack.list[undoStack.at], s)) return;
    undoStack.list.length = undoStack.at + 1;
    undoStack.list.push(s);
    if (undoStack.list.length > HISTORY_MAX) undoStack.list.shift();
    undoStack.at = undoStack.list.length - 1;
    showHistoryButtons();
  }

  function showHistoryButtons() {
    $('undo').disabled = undoStack.at <= 0;
    $('redo').disabled = undoStack.at >= undoStack.list.length - 1;
  }

  // Sends the whole state (undo, redo, reset): every key the page controls.
  function applyWhole(s) {
    const t0 = performance.now();
    model = copyState(s);
    setControls();
    change(copyState(model), t0);
  }

  function moveInHistory(step) {
    const i = undoStack.at + step;
    if (i < 0 || i >= undoStack.list.length) return;
    undoStack.at = i;
    applyWhole(undoStack.list[i]);
    showHistoryButtons();
  }

  function reset() {
    applyWhole(defaults);
    markCommit();
  }

  function onKey(e) {
    if (!(e.ctrlKey || e.metaKey) || e.altKey) return;
    const k = e.key.toLowerCase();
    if (k !== 'z' && k !== 'y') return;
    const t = e.target;
    if (t instanceof HTMLInputElement && (t.type === 'text' || t.type === 'number')) return;  // the field's own undo
    e.preventDefault();
    moveInHistory(k === 'y' || e.shiftKey ? 1 : -1);
  }

  // ---------------------------------------------------------------- jobs

  function jobName() { return $('run-name').value.trim(); }

  async function startJob(path, body, label) {
    await whenIdle();  // the job takes the server's state: send the last change first
    const r = await requestJson(path, 'POST', body);
    if (r.status !== 202) {
      setStatus(`${label}: ${errorText(r)}`, 'error');
      return null;
    }
    setStatus(`${label}: job ${r.data.job} started`);
    return pollJob(r.data.job, label);
  }

  async function pollJob(id, label) {
    for (let n = 0; ; ++n) {
      const r = await requestJson(`/api/jobs/${id}`);
      if (!r.ok) {
        setStatus(`${label}: job ${id}: ${errorText(r)}`, 'error');
        return null;
      }
      showJob(r.data, label);
      if (r.data.state === 'done' || r.data.state === 'failed') return r.data;
      await sleep(n < 50 ? 200 : 1000);  // slower after 10 s
    }
  }

  function showJob(j, label) {
    window.inimJobs[j.id] = j;
    window.inimLastJob = j;
    const pct = Math.round(100 * (Number(j.progress) || 0));
    const text = `#${j.id} ${label}: ${j.state}${j.stage ? ' · ' + j.stage : ''} · ${pct} %`;
    $('job-state').textContent = text;
    $('job-progress').value = Number(j.progress) || 0;
    let li = $(`job-${j.id}`);
    if (!li) {
      li = document.createElement('li');
      li.id = `job-${j.id}`;
      $('jobs').prepend(li);
    }
    li.textContent = text + (j.error ? ` · ${j.error}` : '');
    li.className = j.state;
    if (j.state === 'done') jobDone(j, label);
    if (j.state === 'failed') setStatus(`${label} failed: ${j.error || 'unknown error'}`, 'error');
  }

  function jobDone(j, label) {
    for (const f of j.files || []) {
      const li = document.createElement('li');
      li.textContent = f;
      li.title = `${info && info.out_dir ? info.out_dir + '/' : ''}${f}`;
      $('written-files').prepend(li);
    }
    setStatus(`${label}: wrote ${(j.files || []).join(', ')}`, 'ok');
  }

  function write(what, label) {
    startJob('/api/write', {what, name: jobName()}, label).catch(showError);
  }

  async function predict() {
    const name = $('predict-name').value.trim();
    const body = {angle_deg: Number($('predict-angle').value), width: Math.round(Number($('predict-width').value)), name};
    const j = await startJob('/api/predict', body, 'predict view');
    if (!j || j.state !== 'done') return;
    await Promise.all([showFile($('predict-view'), `${name}.png`), showFile($('predict-ref'), `${name}_reference.png`)]);
    $('predict-panel').hidden = false;
    $('predict-meta').textContent = `${body.angle_deg} deg · ${body.width} px · job ${j.id}`;
    showMetrics(j.metrics);
  }

  async function showFile(img, name) {
    const res = await request(`/api/file?name=${encodeURIComponent(name)}`, 'GET', undefined, 30000);
    if (!res.ok) throw new Error(`${name}: HTTP ${res.status}`);
    await showBlob(img, await res.blob());
  }

  // Numbers of the metrics (nested objects flattened to a.b), four significant digits.
  function showMetrics(metrics) {
    const table = $('predict-metrics');
    table.textContent = '';
    const rows = [];
    const walk = (o, prefix) => {
      for (const [k, v] of Object.entries(o || {})) {
        if (isObject(v)) walk(v, prefix + k + '.');
        else rows.push([prefix + k, typeof v === 'number' ? Number(v.toPrecision(4)) : JSON.stringify(v)]);
      }
    };
    walk(metrics, '');
    for (const [k, v] of rows) table.insertRow().append(cell(k), cell(String(v)));
  }

  function cell(text) {
    const td = document.createElement('td');
    td.textContent = text;
    return td;
  }

  // ---------------------------------------------------------------- info

  async function loadInfo() {
    const r = await requestJson('/api/info');
    if (!r.ok) throw new Error(`GET /api/info: ${errorText(r)}`);
    info = r.data;
    showInfo();
    return info;
  }

  function showInfo() {
    const f = info.field || {};
    const d = info.display || {};
    $('field-info').textContent = `${f.kind || 'field'}: ${f.path || '(default scene)'}`;
    $('field-info').title = f.path || '';
    const lenslets = Array.isArray(d.lenslets) ? d.lenslets.join(' × ') : '?';
    $('display-info').textContent =
        `${d.name || ''} · ${lenslets} lenslets · pitch ${d.pitch_mm} mm · gap ${d.gap_mm} mm`;
    $('out-dir').textContent = info.out_dir || '';
    const sel = $('display');
    const chosen = sel.value;
    sel.textContent = '';
    for (const x of info.displays || []) sel.append(new Option(x.name || x.path, x.path));
    if (chosen) { ensureDisplayOption(chosen); sel.value = chosen; }
    applySpans(info.sliders);
  }

  // ---------------------------------------------------------------- start

  function wire() {
    $('undo').addEventListener('click', () => moveInHistory(-1));
    $('redo').addEventListener('click', () => moveInHistory(1));
    $('reset').addEventListener('click', reset);
    $('write-run').addEventListener('click', () => write('run', 'run file'));
    $('write-eia').addEventListener('click', () => write('eia', 'EIA'));
    $('write-sdf').addEventListener('click', () => write('sdf', 'SDF'));
    $('predict').addEventListener('click', () => predict().catch(showError));
    document.addEventListener('keydown', onKey);
  }

  async function start() {
    wire();
    const [ri, rs] = await Promise.all([requestJson('/api/info'), requestJson('/api/state')]);
    if (ri.status === 403 || rs.status === 403) throw new Error('no access: open the URL inim place printed (with its token)');
    if (!ri.ok) throw new Error(`GET /api/info: ${errorText(ri)}`);
    if (!rs.ok) throw new Error(`GET /api/state: ${errorText(rs)}`);
    openLive();
    info = ri.data;
    model = normalise(rs.data);
    defaults = normalise(info.defaults || rs.data);
    buildControls(info.sliders);
    showInfo();
    setControls();
    commitHistory();
    sync.revision = Number(rs.data.revision);
    sync.busy = true;
    publishSync();
    try {
      await showLevel0(sync.revision);
      setStatus('ready');
    } finally {
      sync.busy = false;
      if (sync.pending) scheduleFlush();
      else onIdle();
    }
  }

  start().catch(showError);
})();
