// The live viewer (/view): opens a session over /view/ws, draws its frames, and turns keys, mouse
// and the panel into FrameInputs (strata.v1, proto JSON). Protocol: server/http/viewer_stream.h.
// For tests and tools the page reports its state on window.strataViewer and document.body.dataset.
(function () {
  'use strict';
  const $ = (id) => document.getElementById(id);
  const params = new URLSearchParams(location.search);
  const canvas = $('frame'), ctx2d = canvas.getContext('2d');
  const v = {
    state: 'connecting', frames: 0, dropped: 0, coalesced: 0, lastFrame: null, error: '', closeCode: 0, closeReason: '',
    session: null, hello: null, selected: null, lastPick: null, latencies: [], frameTimes: [], fps: 0, frameHash: 0,
    camera: null, cameraSent: null, transforms: {}, lods: {}, overlay: null, overlayFrames: 0,
  };
  window.strataViewer = v;
  let ws = null, sequence = 0, lastFrameInput = 0, running = true;
  const sentAt = new Map();
  let cameraDirty = false, overlayDirty = false, pendingOptions = {}, pendingTransforms = {}, pendingLods = {};
  const ackDelayMs = Number(params.get('ack_delay_ms') || 0);  // emulates a slow viewer (tests)

  function report() {
    const d = document.body.dataset;
    d.state = v.state; d.frames = v.frames; d.dropped = v.dropped; d.error = v.error;
    d.closeCode = v.closeCode; d.closeReason = v.closeReason; d.session = v.session ? v.session.name : '';
  }
  function status(text) { $('status').textContent = text; }
  function showMessage(text, isError) {
    const m = $('message');
    m.textContent = text;
    m.className = isError ? 'error' : '';
    m.style.display = text ? 'block' : 'none';
  }
  function send(obj) { if (ws && ws.readyState === WebSocket.OPEN) ws.send(JSON.stringify(obj)); }

  // ---- camera: position plus yaw (about +Y) and pitch; the camera looks down its local -Z -------
  const cam = { pos: [0, 0, 5], yaw: 0, pitch: 0, fov: 0.8, aperture: 0, focus: 1, shutter: 0, speed: 1 };
  function quatMul(a, b) {  // [w, x, y, z]
    return [a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
            a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]];
  }
  function rotate(q, p) {
    const r = quatMul(quatMul(q, [0, p[0], p[1], p[2]]), [q[0], -q[1], -q[2], -q[3]]);
    return [r[1], r[2], r[3]];
  }
  function orientation() {
    const qy = [Math.cos(cam.yaw / 2), 0, Math.sin(cam.yaw / 2), 0], qx = [Math.cos(cam.pitch / 2), Math.sin(cam.pitch / 2), 0, 0];
    return quatMul(qy, qx);
  }
  function setCamera(c) {
    const q = [c.orientation.w, c.orientation.x, c.orientation.y, c.orientation.z];
    const f = rotate(q, [0, 0, -1]);
    cam.pos = [c.position.x, c.position.y, c.position.z];
    cam.pitch = Math.asin(Math.max(-1, Math.min(1, f[1])));
    cam.yaw = Math.atan2(-f[0], -f[2]);
    cam.fov = c.vertical_fov; cam.aperture = c.aperture; cam.focus = c.focus_distance; cam.shutter = c.shutter;
    cam.speed = Math.max(0.2, 0.5 * Math.hypot(cam.pos[0], cam.pos[1], cam.pos[2]));
    $('speed').value = cam.speed.toFixed(2);
  }
  function cameraMessage() {
    const q = orientation();
    return { position: { x: cam.pos[0], y: cam.pos[1], z: cam.pos[2] }, orientation: { w: q[0], x: q[1], y: q[2], z: q[3] },
             vertical_fov: cam.fov, aperture: cam.aperture, focus_distance: cam.focus, shutter: cam.shutter };
  }
  function ray(u, w) {  // u right, w down, both in [0, 1]
    const h = Math.tan(cam.fov / 2), aspect = canvas.width / canvas.height;
    const d = [(2 * u - 1) * h * aspect, (1 - 2 * w) * h, -1], n = Math.hypot(d[0], d[1], d[2]);
    return rotate(orientation(), [d[0] / n, d[1] / n, d[2] / n]);
  }

  // ---- keys: WASD/QE fly, shift faster, [ ] the selected instance's LoD level ---------------------
  const held = new Set();
  const flyKeys = new Set(['KeyW', 'KeyA', 'KeyS', 'KeyD', 'KeyQ', 'KeyE']);
  canvas.addEventListener('keydown', (e) => {
    if (flyKeys.has(e.code)) { held.add(e.code); e.preventDefault(); }
    if (e.code === 'ShiftLeft' || e.code === 'ShiftRight') held.add('Shift');
    if ((e.code === 'BracketLeft' || e.code === 'BracketRight') && v.selected !== null) {
      const inst = v.session.instances[v.selected];
      const level = Math.max(0, Math.min(inst.lod_levels - 1, (v.lods[v.selected] ?? inst.lod) + (e.code === 'BracketRight' ? 1 : -1)));
      v.lods[v.selected] = level;
      pendingLods[v.selected] = level;
      updateSelection();
      e.preventDefault();
    }
  });
  canvas.addEventListener('keyup', (e) => { held.delete(e.code); if (e.key === 'Shift') held.delete('Shift'); });
  canvas.addEventListener('blur', () => held.clear());
  let lastTick = performance.now();
  function fly(now) {
    const dt = Math.min(0.1, (now - lastTick) / 1000);
    lastTick = now;
    if (!held.size || !v.session) return;
    const q = orientation(), fwd = rotate(q, [0, 0, -1]), right = rotate(q, [1, 0, 0]);
    const step = cam.speed * dt * (held.has('Shift') ? 4 : 1);
    const move = (dir, s) => { for (let k = 0; k < 3; ++k) cam.pos[k] += dir[k] * s; };
    if (held.has('KeyW')) move(fwd, step);
    if (held.has('KeyS')) move(fwd, -step);
    if (held.has('KeyD')) move(right, step);
    if (held.has('KeyA')) move(right, -step);
    if (held.has('KeyE')) move([0, 1, 0], step);
    if (held.has('KeyQ')) move([0, 1, 0], -step);
    if (held.has('KeyW') || held.has('KeyS') || held.has('KeyA') || held.has('KeyD') || held.has('KeyQ') || held.has('KeyE')) cameraDirty = true;
  }

  // ---- mouse: press picks; on an instance, drag moves it in the plane facing the camera; elsewhere,
  // drag turns the camera ------------------------------------------------------------------------
  let drag = null;
  function imageFraction(e) {
    const r = canvas.getBoundingClientRect();
    return [Math.max(0, Math.min(1, (e.clientX - r.left) / r.width)), Math.max(0, Math.min(1, (e.clientY - r.top) / r.height))];
  }
  canvas.addEventListener('mousedown', (e) => {
    canvas.focus();
    if (!v.session || e.button !== 0) return;
    const [u, w] = imageFraction(e);
    drag = { mode: 'pending', start: [e.clientX, e.clientY], at: [u, w], yaw: cam.yaw, pitch: cam.pitch };
    send({ type: 'pick', x: u, y: w });
    e.preventDefault();
  });
  window.addEventListener('mousemove', (e) => {
    if (!drag) return;
    drag.last = [e.clientX, e.clientY];
    drag.at = imageFraction(e);
    applyDrag();
  });
  window.addEventListener('mouseup', () => { drag = null; });
  function applyDrag() {
    if (!drag || !drag.last) return;
    if (drag.mode === 'look') {
      const r = canvas.getBoundingClientRect(), k = cam.fov / r.height;
      cam.yaw = drag.yaw - (drag.last[0] - drag.start[0]) * k;
      cam.pitch = Math.max(-1.55, Math.min(1.55, drag.pitch - (drag.last[1] - drag.start[1]) * k));
      cameraDirty = true;
    } else if (drag.mode === 'object') {
      // The plane through the grabbed point, facing the camera: the grabbed point stays under the cursor.
      const d = ray(drag.at[0], drag.at[1]), n = rotate(orientation(), [0, 0, -1]);
      const denom = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
      if (Math.abs(denom) < 1e-6) return;
      const t = ((drag.point[0] - cam.pos[0]) * n[0] + (drag.point[1] - cam.pos[1]) * n[1] + (drag.point[2] - cam.pos[2]) * n[2]) / denom;
      const p = [cam.pos[0] + d[0] * t, cam.pos[1] + d[1] * t, cam.pos[2] + d[2] * t];
      const tr = drag.transform, id = drag.instance;
      const moved = { instance_id: id, translation: { x: tr.translation.x + p[0] - drag.point[0], y: tr.translation.y + p[1] - drag.point[1],
                      z: tr.translation.z + p[2] - drag.point[2] }, rotation: tr.rotation, scale: tr.scale };
      v.transforms[id] = moved;
      pendingTransforms[id] = moved;
    }
  }
  function onPick(m) {
    v.lastPick = m;
    if (m.instance === null) {
      v.selected = null;
      if (drag && drag.mode === 'pending') { drag.mode = 'look'; applyDrag(); }
    } else {
      v.selected = m.instance;
      if (drag && drag.mode === 'pending') {
        drag.mode = 'object';
        drag.instance = m.instance;
        drag.point = [m.point.x, m.point.y, m.point.z];
        drag.transform = m.transform;
        applyDrag();
      }
    }
    updateSelection();
  }
  function updateSelection() {
    if (v.selected === null || !v.session) { $('selection').textContent = 'none (click an object)'; return; }
    const inst = v.session.instances[v.selected];
    $('selection').textContent = `#${v.selected} ${inst.name || ''}  LoD ${v.lods[v.selected] ?? inst.lod} of 0..${inst.lod_levels - 1}`;
  }

  // ---- inputs: latest wins on the server; the page keeps at most two unanswered ----------------
  function sendInput(force) {
    if (!v.session || v.state !== 'streaming') return;
    const outstanding = sequence - lastFrameInput;
    const dirty = cameraDirty || overlayDirty || Object.keys(pendingOptions).length || Object.keys(pendingTransforms).length || Object.keys(pendingLods).length;
    if (!(dirty && outstanding < 2) && !(force && outstanding === 0)) return;
    const input = { sequence: ++sequence };
    overlayDirty = false;  // the overlay message went first; this input renders a frame with it
    if (cameraDirty) { input.camera = cameraMessage(); v.cameraSent = input.camera; cameraDirty = false; }
    if (Object.keys(pendingOptions).length) { input.options = pendingOptions; pendingOptions = {}; }
    const ts = Object.values(pendingTransforms);
    if (ts.length) { input.transforms = ts; pendingTransforms = {}; }
    const ls = Object.entries(pendingLods).map(([id, level]) => ({ instance_id: Number(id), level }));
    if (ls.length) { input.lod_changes = ls; pendingLods = {}; }
    sentAt.set(input.sequence, performance.now());
    send({ type: 'input', input });
  }
  function tick(now) {
    fly(now);
    sendInput(running);
    requestAnimationFrame(tick);
  }

  // ---- frames ----------------------------------------------------------------------------------
  function percentile(values, p) {
    if (!values.length) return 0;
    const s = values.slice().sort((a, b) => a - b);
    return s[Math.min(s.length - 1, Math.floor(p * s.length))];
  }
  async function onFrame(buffer) {
    const n = new DataView(buffer).getUint32(0, true);
    const h = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, n)));
    const jpeg = new Uint8Array(buffer, 4 + n, h.jpeg_bytes);
    const bitmap = await createImageBitmap(new Blob([jpeg], { type: 'image/jpeg' }));
    const overlay = h.overlay && $('overlay').checked
      ? await createImageBitmap(new Blob([new Uint8Array(buffer, 4 + n + h.jpeg_bytes, h.overlay.bytes)], { type: 'image/png' }))
      : null;
    if (canvas.width !== h.width || canvas.height !== h.height || !fitted) {
      canvas.width = h.width; canvas.height = h.height;
      canvas.classList.toggle('small', h.width < 512);
      fit();
      fitted = true;
    }
    ctx2d.drawImage(bitmap, 0, 0);
    bitmap.close();
    if (overlay) {  // the domain map over the frame (server/http/viewer_overlay.h)
      ctx2d.globalAlpha = 0.6;
      ctx2d.drawImage(overlay, 0, 0);
      ctx2d.globalAlpha = 1;
      overlay.close();
      v.overlayFrames += 1;
    }
    v.overlay = h.overlay || null;
    const now = performance.now();
    v.frames += 1;
    v.lastFrame = h;
    v.dropped = h.dropped_total;
    v.coalesced += h.coalesced;
    v.camera = h.camera;
    if (h.session) { v.session.session = h.session; showDecisions(h.session); }
    lastFrameInput = Math.max(lastFrameInput, h.input_sequence);
    if (sentAt.has(h.input_sequence)) v.latencies.push(now - sentAt.get(h.input_sequence));
    for (const k of sentAt.keys()) if (k <= h.input_sequence) sentAt.delete(k);
    if (v.latencies.length > 200) v.latencies.shift();
    v.frameTimes.push(now);
    while (v.frameTimes.length && now - v.frameTimes[0] > 2000) v.frameTimes.shift();
    v.fps = v.frameTimes.length > 1 ? (v.frameTimes.length - 1) * 1000 / (now - v.frameTimes[0]) : 0;
    let hash = 0;
    for (let i = 0; i < jpeg.length; ++i) hash = (hash * 31 + jpeg[i]) >>> 0;
    v.frameHash = hash;  // tells frames apart (tests)
    hud(h);
    plot(h, now);
    report();
    const ack = () => { send({ type: 'ack', frame: h.frame }); sendInput(running); };
    if (ackDelayMs > 0) setTimeout(ack, ackDelayMs); else ack();
  }
  function hud(h) {
    const passes = Object.entries(h.pass_ms).sort((a, b) => b[1] - a[1]).slice(0, 6)
      .map(([p, ms]) => `  ${p.padEnd(18)} ${ms.toFixed(1).padStart(7)} ms`).join('\n');
    $('hud').textContent =
      `${v.session.session.method} ${h.width}x${h.height}  frame ${h.frame}  ${v.fps.toFixed(1)} fps\n` +
      `GPU ${h.gpu_ms.toFixed(1)} ms  render ${h.render_ms.toFixed(1)} ms  queued ${h.queued_ms.toFixed(1)} ms\n` +
      `JPEG ${h.encode_ms.toFixed(2)} ms  ${(h.jpeg_bytes / 1024).toFixed(1)} KiB\n` +
      `input-to-frame p50 ${percentile(v.latencies, 0.5).toFixed(0)} ms  p95 ${percentile(v.latencies, 0.95).toFixed(0)} ms\n` +
      `dropped ${h.dropped_total}  coalesced ${v.coalesced}` + (h.history_reset ? `\nreset: ${h.history_reset_reason}` : '') +
      (h.overlay ? `\ndomains ${h.overlay.summary.active_domains_mean.toFixed(2)}/px  disoccluded ${(100 * h.overlay.summary.disoccluded_share).toFixed(1)}%` +
                   `  covered ${(100 * h.overlay.summary.covered_share_of_disoccluded).toFixed(0)}% of them` : '') +
      `\n${passes}`;
  }
  let chart = null, fitted = false;
  const series = [[], [], []];
  function plot(h, now) {
    series[0].push(now / 1000); series[1].push(h.render_ms); series[2].push(v.latencies.length ? v.latencies[v.latencies.length - 1] : null);
    if (series[0].length > 300) series.forEach((s) => s.shift());
    if (!chart && typeof uPlot !== 'undefined') {
      chart = new uPlot({ width: 270, height: 140, legend: { show: true }, scales: { x: { time: false } }, axes: [{ show: false }, { size: 50, values: (u, vals) => vals.map((x) => x.toFixed(0)) }],
                          series: [{}, { label: 'render ms', stroke: '#1e88e5' }, { label: 'latency ms', stroke: '#e53935' }] }, series, $('chart'));
    } else if (chart) {
      chart.setData(series);
    }
  }

  // ---- the panel -------------------------------------------------------------------------------
  function isRestir() { return v.session && v.session.session.method.startsWith('restir'); }
  function buildPanel() {
    const h = v.hello;
    const sceneSel = $('scene'), methodSel = $('method');
    sceneSel.innerHTML = ''; methodSel.innerHTML = '';
    for (const s of h.scenes) sceneSel.add(new Option(s.name, s.name));
    for (const m of h.methods) methodSel.add(new Option(m, m));
    sceneSel.value = params.get('scene') || (h.scenes.some((s) => s.name === 'carousel') ? 'carousel' : h.scenes[0].name);
    methodSel.value = params.get('method') || h.default_method;
    $('width').value = params.get('width') || 256;
    $('height').value = params.get('height') || 256;
  }
  function buildOptions() {
    const box = $('options');
    box.innerHTML = '';
    const effective = v.session.session.options;
    for (const o of v.hello.options) {
      if (o.restir_only && !isRestir()) continue;
      if (o.field === 'spp' && isRestir()) continue;  // the restir-* methods take one sample per pixel
      const label = document.createElement('label');
      label.textContent = o.label;
      const input = document.createElement('input');
      input.dataset.field = o.field;
      const value = document.createElement('span');
      value.className = 'value';
      if (o.kind === 'bool') {
        input.type = 'checkbox';
        input.checked = Boolean(effective[o.field]);
        input.addEventListener('change', () => { pendingOptions[o.field] = input.checked; });
      } else {
        input.type = 'range'; input.min = o.min; input.max = o.max; input.step = o.step;
        input.value = effective[o.field];
        value.textContent = input.value;
        input.addEventListener('input', () => { value.textContent = input.value; });
        input.addEventListener('change', () => { pendingOptions[o.field] = Number(input.value); });
      }
      label.append(input, value);
      box.append(label);
    }
  }
  function showDecisions(s) {
    const box = $('decisions');
    box.innerHTML = '';
    for (const d of s.decisions || []) {
      const div = document.createElement('div');
      div.innerHTML = '<b></b> = <span></span> <i></i>';
      div.children[0].textContent = d.name; div.children[1].textContent = d.value; div.children[2].textContent = d.reason ? `(${d.reason})` : '';
      box.append(div);
    }
  }
  function createSession() {
    const request = { scene: { builtin: $('scene').value }, method: $('method').value,
                      resolution: { width: Number($('width').value), height: Number($('height').value) } };
    const scene = v.hello.scenes.find((s) => s.name === $('scene').value);
    if (scene && scene.kind !== 'BUILTIN') request.scene = { path: scene.name };
    v.state = 'creating'; report();
    send({ type: 'create', request });
  }

  // ---- the socket ------------------------------------------------------------------------------
  function connect() {
    const token = sessionStorage.getItem('strata_token');
    ws = new WebSocket((location.protocol === 'https:' ? 'wss://' : 'ws://') + location.host + '/view/ws');
    ws.binaryType = 'arraybuffer';
    v.state = 'connecting'; report();
    ws.onopen = () => { send(token ? { type: 'hello', token } : { type: 'hello' }); status('connected'); };
    ws.onmessage = (e) => {
      if (typeof e.data !== 'string') { onFrame(e.data); return; }
      const m = JSON.parse(e.data);
      if (m.type === 'hello') {
        v.hello = m; v.state = 'ready'; report();
        status(`connected to ${m.device}`);
        $('token-form').style.display = 'none';
        buildPanel();
        if (params.get('session')) send({ type: 'attach', session: params.get('session') });
        else if (params.get('autostart') !== '0') createSession();
      } else if (m.type === 'session') {
        v.session = m; v.state = 'streaming'; v.selected = null; v.transforms = {}; v.lods = {};
        sequence = 0; lastFrameInput = 0; sentAt.clear();
        setCamera(m.camera);
        buildOptions(); showDecisions(m.session); updateSelection(); showMessage('');
        $('overlay-box').style.display = v.hello.domain_map_methods.includes(m.session.method) ? 'block' : 'none';
        $('overlay').checked = false;
        status(`${m.session.name}: ${m.session.scene}, ${m.session.method}`);
        report();
        sendInput(true);
      } else if (m.type === 'pick') {
        onPick(m);
      } else if (m.type === 'error') {
        v.error = m.message; report();
        showMessage(m.message, true);
      }
    };
    ws.onclose = (e) => {
      v.closeCode = e.code; v.closeReason = e.reason; v.state = 'closed'; report();
      status(`closed (${e.code})`);
      if (e.code === 4401) {  // the daemon wants a token: ask once, then keep it for this tab
        sessionStorage.removeItem('strata_token');
        $('token-form').style.display = 'block';
        showMessage('This stratad needs its access token (--auth-token-file).', false);
      } else if (!v.error) {
        showMessage(`The connection closed (${e.code}${e.reason ? ': ' + e.reason : ''}).`, e.code !== 1000);
      }
    };
  }
  $('token-form').addEventListener('submit', (e) => {
    e.preventDefault();
    sessionStorage.setItem('strata_token', $('token').value);
    v.error = ''; showMessage('');
    connect();
  });
  $('start').addEventListener('click', () => { v.error = ''; showMessage(''); createSession(); });
  $('run').addEventListener('change', () => { running = $('run').checked; });
  $('overlay').addEventListener('change', () => {
    send({ type: 'overlay', domain_map: $('overlay').checked });
    overlayDirty = true;
  });
  $('speed').addEventListener('change', () => { cam.speed = Math.max(0.001, Number($('speed').value)); });
  function fit() {
    const stage = $('stage').getBoundingClientRect();
    const k = Math.min(stage.width / canvas.width, stage.height / canvas.height);
    canvas.style.width = Math.floor(canvas.width * k) + 'px';
    canvas.style.height = Math.floor(canvas.height * k) + 'px';
  }
  window.addEventListener('resize', fit);
  v.pick = (u, w) => send({ type: 'pick', x: u, y: w });
  setInterval(() => send({ type: 'ping' }), 15000);  // the server closes sockets silent for a minute
  report();
  connect();
  requestAnimationFrame(tick);
})();
