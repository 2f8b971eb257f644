// report.html's script (inlined by strata_report): reads the JSON data block and builds, per scene,
// uPlot charts of error vs frame and vs cumulative GPU time (whole image, and disoccluded pixels
// where any run has them) and stacked bars of the median per-pass GPU cost.
// When every chart has drawn it sets <body data-plots="N" data-plot-rects="[[x,y,w,h],...]">
// (the plot areas in CSS pixels, page coordinates) and appends " [ready]" to the title.
// It logs nothing on success.
(function () {
  "use strict";

  const data = JSON.parse(document.getElementById("data").textContent);
  const RUN_COLORS = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                      "#17becf", "#e377c2", "#bcbd22", "#8c564b", "#7f7f7f"];
  const PASS_COLORS = ["#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                       "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"];
  const METRICS = [["relmse", "RelMSE"], ["mape", "MAPE"], ["flip", "FLIP"]];
  const X_AXES = [
    {key: "frame", label: "frame", title: "vs frame", of: (f) => f.frame, incrs: [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000]},
    {key: "cumulative_ms", label: "cumulative GPU ms", title: "vs cumulative GPU time", of: (f) => f.cumulative_ms},
  ];
  const GROUPS = [
    {key: "whole", heading: "Error", of: (f) => f.whole},
    {key: "masked", heading: "Disoccluded pixels: error", of: (f) => (f.has_masked ? f.masked : null)},
  ];
  const PLOT_WIDTH = 430, PLOT_HEIGHT = 240;

  const charts = [];
  let expected = 0;
  let drawn = 0;
  let building = true;

  const isNum = (v) => typeof v === "number" && Number.isFinite(v);

  function fmt(v) {
    if (!isNum(v)) return "–";
    if (v === 0) return "0";
    const a = Math.abs(v);
    if (a >= 1e5 || a < 1e-3) return v.toExponential(2);
    return String(Number(v.toPrecision(4)));
  }

  function el(tag, cls, text) {
    const e = document.createElement(tag);
    if (cls) e.className = cls;
    if (text !== undefined) e.textContent = text;
    return e;
  }

  function runLabel(run) {
    if (run.equal_time_pt) return "pt " + run.spp + " spp (equal time to " + (run.matched_method || "?") + ")";
    return run.method + " " + run.spp + " spp";
  }

  // uPlot wants one shared x array: the sorted union of the runs' x values, with null where a run
  // has no point (spanGaps joins its line across them).
  function alignedData(runs, xOf, yOf) {
    const xs = new Set();
    for (const run of runs) {
      for (const f of run.frames) {
        if (isNum(xOf(f)) && isNum(yOf(f))) xs.add(xOf(f));
      }
    }
    const x = Array.from(xs).sort((a, b) => a - b);
    const index = new Map(x.map((v, i) => [v, i]));
    const columns = runs.map((run) => {
      const column = new Array(x.length).fill(null);
      for (const f of run.frames) {
        if (isNum(xOf(f)) && isNum(yOf(f))) column[index.get(xOf(f))] = yOf(f);
      }
      return column;
    });
    return [x].concat(columns);
  }

  function markReadyIfDone() {
    if (building || drawn < expected) return;
    const rects = charts.map((u) => {
      const r = u.over.getBoundingClientRect();
      return [Math.round(r.left + window.scrollX), Math.round(r.top + window.scrollY),
              Math.round(r.width), Math.round(r.height)];
    });
    document.body.dataset.plotRects = JSON.stringify(rects);
    document.body.dataset.plots = String(drawn);
    document.title = document.title + " [ready]";
  }

  function onFirstDraw(u) {
    if (u.strataDrawn) return;
    u.strataDrawn = true;
    drawn += 1;
    markReadyIfDone();
  }

  function errorPlot(host, runs, axis, group, metric, scene) {
    const yOf = (f) => {
      const e = group.of(f);
      return e ? e[metric[0]] : null;
    };
    const aligned = alignedData(runs, axis.of, yOf);
    if (aligned[0].length === 0) return;
    const ys = aligned.slice(1).flat().filter(isNum);
    const logY = ys.length > 0 && ys.every((v) => v > 0);
    const name = metric[1] + (group.key === "masked" ? " (disoccluded)" : "");
    const opts = {
      title: scene + ": " + name + " " + axis.title,
      width: PLOT_WIDTH,
      height: PLOT_HEIGHT,
      scales: {x: {time: false}, y: logY ? {distr: 3, log: 10} : {}},
      axes: [
        Object.assign({label: axis.label, values: (u, splits) => splits.map((v) => (v == null ? "" : fmt(v)))},
                      axis.incrs ? {incrs: axis.incrs} : {}),
        {label: name + (logY ? " (log)" : ""), size: 62, values: (u, splits) => splits.map((v) => (v == null ? "" : fmt(v)))},
      ],
      series: [{label: axis.label, value: (u, v) => fmt(v)}].concat(runs.map((run) => ({
        label: runLabel(run),
        stroke: run.color,
        width: 2,
        spanGaps: true,
        points: {size: 5, fill: run.color},
        value: (u, v) => fmt(v),
      }))),
      legend: {show: true},
      hooks: {draw: [onFirstDraw]},
    };
    const box = el("div", "plot");
    host.appendChild(box);
    expected += 1;
    charts.push(new uPlot(opts, aligned, box));
  }

  function median(values) {
    if (values.length === 0) return 0;
    const v = values.slice().sort((a, b) => a - b);
    const n = v.length;
    return n % 2 === 1 ? v[(n - 1) / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  }

  // Stacked horizontal bars, one per run: the median over frames of each pass's GPU ms (a pass
  // missing from a frame counts as 0 ms there).
  function passStacks(host, runs) {
    const passes = [];
    for (const run of runs) {
      for (const f of run.frames) {
        for (const p of Object.keys(f.pass_ms || {})) if (!passes.includes(p)) passes.push(p);
      }
    }
    if (passes.length === 0) {
      host.appendChild(el("p", "empty", "No per-pass timings."));
      return;
    }
    const color = (i) => PASS_COLORS[i % PASS_COLORS.length];
    const medians = runs.map((run) => passes.map((p) => median(run.frames.map((f) => {
      const v = (f.pass_ms || {})[p];
      return isNum(v) ? v : 0;
    }))));
    const totals = medians.map((m) => m.reduce((a, b) => a + b, 0));
    const maxTotal = Math.max(...totals) || 1;

    const legend = el("div", "pass-legend");
    passes.forEach((p, i) => {
      const item = el("span", "pass-key");
      const swatch = el("span", "swatch");
      swatch.style.background = color(i);
      item.appendChild(swatch);
      item.appendChild(document.createTextNode(p));
      legend.appendChild(item);
    });
    host.appendChild(legend);

    const bars = el("div", "pass-bars");
    runs.forEach((run, r) => {
      const row = el("div", "pass-row");
      row.appendChild(el("span", "pass-label", runLabel(run)));
      const track = el("span", "pass-track");
      passes.forEach((p, i) => {
        if (!(medians[r][i] > 0)) return;
        const seg = el("span", "pass-seg");
        seg.style.width = (100 * medians[r][i] / maxTotal) + "%";
        seg.style.background = color(i);
        seg.title = p + ": " + fmt(medians[r][i]) + " ms";
        track.appendChild(seg);
      });
      row.appendChild(track);
      row.appendChild(el("span", "pass-total", fmt(totals[r]) + " ms"));
      bars.appendChild(row);
    });
    host.appendChild(bars);

    const details = el("details", "pass-table");
    details.appendChild(el("summary", null, "Median ms by pass"));
    const table = el("table");
    const head = el("tr");
    head.appendChild(el("th", null, "pass"));
    for (const run of runs) head.appendChild(el("th", null, runLabel(run)));
    table.appendChild(head);
    passes.forEach((p, i) => {
      const tr = el("tr");
      tr.appendChild(el("td", null, p));
      medians.forEach((m) => tr.appendChild(el("td", "num", fmt(m[i]))));
      table.appendChild(tr);
    });
    details.appendChild(table);
    host.appendChild(details);
  }

  function buildScene(section) {
    const scene = section.dataset.scene;
    const runs = data.runs.filter((r) => r.scene === scene);
    const plotsHost = section.querySelector(".plots-host");
    const passesHost = section.querySelector(".passes-host");
    if (runs.length === 0) {
      plotsHost.appendChild(el("p", "empty", "No runs."));
      return;
    }
    const anyMasked = runs.some((r) => r.frames.some((f) => f.has_masked));
    for (const group of GROUPS) {
      if (group.key === "masked" && !anyMasked) continue;
      for (const axis of X_AXES) {
        plotsHost.appendChild(el("h3", null, group.heading + " " + axis.title));
        const row = el("div", "plots");
        plotsHost.appendChild(row);
        for (const metric of METRICS) errorPlot(row, runs, axis, group, metric, scene);
      }
    }
    passStacks(passesHost, runs);
  }

  // One colour per method (equal-time pt keyed by the method it matches), the same in every scene.
  const colorKeys = [];
  for (const run of data.runs) {
    const key = run.method + (run.equal_time_pt ? " = " + run.matched_method : "");
    if (!colorKeys.includes(key)) colorKeys.push(key);
    run.color = RUN_COLORS[colorKeys.indexOf(key) % RUN_COLORS.length];
  }
  document.querySelectorAll("section.scene").forEach(buildScene);
  building = false;
  markReadyIfDone();
})();
