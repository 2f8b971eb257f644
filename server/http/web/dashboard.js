// The live dashboard: one card per session, built from /events (one server-sent event per
// rendered frame; with a token, sent as the viewer sends it). Charts keep the last MAX_POINTS frames and redraw at most once per animation
// frame. <body> carries data-events, data-sessions, data-charts and data-redraws so that a
// headless browser can tell that the charts drew and updated; the title gains " [live]" once
// every card has drawn.
(function () {
  'use strict';
  const MAX_POINTS = 300;
  const COLORS = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf', '#bcbd22', '#7f7f7f'];
  const sessions = new Map();
  const main = document.getElementById('sessions');
  const status = document.getElementById('status');
  let events = 0, redraws = 0, pending = false;

  function color(i, alpha) {
    const c = COLORS[i % COLORS.length];
    if (alpha === undefined) return c;
    const n = parseInt(c.slice(1), 16);
    return 'rgba(' + (n >> 16) + ',' + ((n >> 8) & 255) + ',' + (n & 255) + ',' + alpha + ')';
  }

  // A chart of named series over the frame index; `stacked` draws cumulative filled bands.
  function Chart(parent, title, unit, stacked) {
    this.parent = parent; this.title = title; this.unit = unit; this.stacked = stacked;
    this.keys = []; this.x = []; this.values = {}; this.plot = null;
    this.el = document.createElement('div');
    parent.appendChild(this.el);
  }
  Chart.prototype.add = function (x, named) {
    for (const k of Object.keys(named)) {
      if (!(k in this.values)) {
        this.values[k] = this.x.map(() => null);
        this.keys.push(k);
        this.keys.sort();
        if (this.plot) { this.plot.destroy(); this.plot = null; }
      }
    }
    this.x.push(x);
    for (const k of this.keys) this.values[k].push(k in named ? named[k] : null);
    if (this.x.length > MAX_POINTS) {
      this.x.shift();
      for (const k of this.keys) this.values[k].shift();
    }
  };
  Chart.prototype.data = function () {
    const cols = [this.x];
    let acc = this.x.map(() => 0);
    for (const k of this.keys) {
      if (this.stacked) {
        acc = acc.map((a, i) => a + (this.values[k][i] || 0));
        cols.push(acc.slice());
      } else {
        cols.push(this.values[k]);
      }
    }
    return cols;
  };
  Chart.prototype.draw = function () {
    if (this.keys.length === 0 || this.x.length === 0) return false;
    const data = this.data();
    if (!this.plot) {
      const series = [{ label: 'frame' }].concat(this.keys.map((k, i) => ({
        label: k, stroke: color(i), width: 1.5, spanGaps: true,
        fill: this.stacked ? color(i, 0.35) : undefined })));
      // Stacked bands: each filled down to the one below it.
      const bands = this.stacked ? this.keys.slice(1).map((k, i) => ({ series: [i + 2, i + 1] })) : [];
      this.plot = new uPlot({ title: this.title + ' (' + this.unit + ')', width: 380, height: 200, series: series, bands: bands,
        scales: { x: { time: false } }, legend: { show: true } }, data, this.el);
    } else {
      this.plot.setData(data);
    }
    return true;
  };

  function card(e) {
    let s = sessions.get(e.session);
    if (s) return s;
    const el = document.createElement('section');
    el.className = 'session';
    const h = document.createElement('h2');
    h.textContent = e.session;
    const meta = document.createElement('span');
    meta.className = 'meta';
    h.appendChild(meta);
    el.appendChild(h);
    const row = document.createElement('div');
    row.className = 'row';
    el.appendChild(row);
    const img = document.createElement('img');
    img.className = 'thumb';
    img.alt = 'latest frame of ' + e.session;
    row.appendChild(img);
    main.appendChild(el);
    s = { el: el, meta: meta, img: img, last_t: null, fps: [],
          charts: {
            gpu: new Chart(row, 'GPU time by pass, stacked', 'ms', true),
            fps: new Chart(row, 'Frames per second', 'fps', false),
            latency: new Chart(row, 'Server latency', 'ms', false),
            coverage: new Chart(row, 'Disocclusion coverage', 'ratio', false),
            domains: new Chart(row, 'Active domains by layer', 'domains', false),
            failures: new Chart(row, 'Shift failures by reason', 'per frame', false) } };
    sessions.set(e.session, s);
    return s;
  }

  function onEvent(e) {
    events++;
    const s = card(e);
    s.meta.textContent = e.scene + ' \u00b7 ' + e.method + ' \u00b7 ' + e.width + 'x' + e.height + ' \u00b7 frame ' + e.frame;
    if (e.thumbnail) s.img.src = e.thumbnail;
    // fps over the last 10 frames' arrival times.
    s.fps.push(e.t_ms);
    if (s.fps.length > 10) s.fps.shift();
    const span = s.fps.length > 1 ? (s.fps[s.fps.length - 1] - s.fps[0]) / 1000 : 0;
    const x = e.frame;
    s.charts.gpu.add(x, e.pass_ms);
    s.charts.fps.add(x, { fps: span > 0 ? (s.fps.length - 1) / span : null });
    s.charts.latency.add(x, { queued: e.queued_ms, total: e.latency_ms });
    const d = e.domains;
    s.charts.coverage.add(x, { covered: d.disoccluded > 0 ? d.covered / d.disoccluded : 0 });
    const layers = {};
    d.active_by_layer.forEach((n, i) => { layers['layer ' + i] = n; });
    if (d.active_by_layer.length === 0) layers['layer 0'] = 0;
    s.charts.domains.add(x, layers);
    const failures = Object.assign({}, e.shift_failures);
    if (Object.keys(failures).length === 0) failures.none = 0;
    s.charts.failures.add(x, failures);
    if (!pending) {
      pending = true;
      requestAnimationFrame(redraw);
    }
  }

  function redraw() {
    pending = false;
    let charts = 0;
    for (const s of sessions.values())
      for (const c of Object.values(s.charts)) if (c.draw()) charts++;
    redraws++;
    document.body.setAttribute('data-events', String(events));
    document.body.setAttribute('data-sessions', String(sessions.size));
    document.body.setAttribute('data-charts', String(charts));
    document.body.setAttribute('data-redraws', String(redraws));
    if (charts > 0 && charts === sessions.size * 6 && !document.title.endsWith('[live]')) document.title += ' [live]';
  }

  // The event stream, read with fetch so that it can carry the daemon's token: with
  // --auth-token-file /events answers 401 without it, and the page asks for it once (kept for the
  // tab under the viewer's key). Reconnects after 2 s as EventSource would.
  const form = document.getElementById('token-form');
  function parseEvents(text) {
    let cut;
    while ((cut = text.indexOf('\n\n')) >= 0) {
      const data = text.slice(0, cut).split('\n').filter((l) => l.startsWith('data: ')).map((l) => l.slice(6)).join('\n');
      text = text.slice(cut + 2);
      if (data) onEvent(JSON.parse(data));
    }
    return text;
  }
  async function stream() {
    for (;;) {
      const token = sessionStorage.getItem('strata_token');
      try {
        const r = await fetch('/events', { cache: 'no-store', headers: token ? { Authorization: 'Bearer ' + token } : {} });
        if (r.status === 401) {
          sessionStorage.removeItem('strata_token');
          status.textContent = 'this stratad needs its access token';
          form.style.display = 'inline';
          return;
        }
        if (r.ok && r.body) {
          status.textContent = 'live';
          const reader = r.body.pipeThrough(new TextDecoderStream()).getReader();
          let pendingText = '';
          for (;;) {
            const { value, done } = await reader.read();
            if (done) break;
            pendingText = parseEvents(pendingText + value);
          }
        }
      } catch (e) {
        // the daemon went away: try again below
      }
      status.textContent = 'reconnecting';
      await new Promise((resolve) => setTimeout(resolve, 2000));
    }
  }
  form.addEventListener('submit', (e) => {
    e.preventDefault();
    sessionStorage.setItem('strata_token', document.getElementById('token').value);
    form.style.display = 'none';
    status.textContent = 'connecting';
    stream();
  });
  stream();
})();
