// The validator's browser view: draws the scene that render_html.py puts in the page
// (validator/render_scene.py says what a scene holds) on a canvas, with zoom and pan,
// layers on and off, the tree's growth in the order the planner printed it, and the
// coordinates under the pointer. Everything the planner wrote is shown as text
// (textContent), never as markup. window.rrtView tells tests what was drawn.
"use strict";
(function () {
  const TAU = 2 * Math.PI;
  const LAYERS = ["grid", "obstacles", "tree", "footprints", "answer", "marks", "failure"];
  const LAYER_NAMES = {grid: "grid", obstacles: "obstacles", tree: "tree", footprints: "footprints",
                       answer: "answer", marks: "start and goal", failure: "failure"};
  const CHUNK = 20000;          // polylines a path holds before it is stroked
  const SLOW_DRAW_MS = 40;      // a draw slower than this: pan and zoom move a snapshot first
  const MARGIN = {left: 64, right: 50, top: 22, bottom: 36, gap: 26};
  const stats = {ready: false, draws: 0, firstDrawMs: null, lastDrawMs: null, edgesDrawn: 0,
                 view: 0, error: null};
  window.rrtView = stats;

  // ----- the scene's data ----------------------------------------------------------------
  function bytesOf(b64) {
    const text = atob(b64);
    const out = new Uint8Array(text.length);
    for (let i = 0; i < text.length; i++) out[i] = text.charCodeAt(i);
    return out;
  }

  async function inflate(bytes) {
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate"));
    return new Uint8Array(await new Response(stream).arrayBuffer());
  }

  // Replaces each {"$": type, "b64": ...} in the scene by its typed array (in place).
  async function decode(node) {
    const waits = [];
    (function walk(value, parent, key) {
      if (Array.isArray(value)) { value.forEach((v, i) => walk(v, value, i)); return; }
      if (!value || typeof value !== "object") return;
      if (value.$) {
        const bytes = bytesOf(value.b64);
        if (value.$ === "f32") parent[key] = new Float32Array(bytes.buffer);
        else if (value.$ === "u32") parent[key] = new Uint32Array(bytes.buffer);
        else waits.push(inflate(bytes).then(out => { parent[key] = out; }));
        return;
      }
      for (const k of Object.keys(value)) walk(value[k], value, k);
    })(node, null, null);
    await Promise.all(waits);
  }

  // ----- page -------------------------------------------------------------------------------
  function element(tag, attributes, text) {
    const node = document.createElement(tag);
    Object.assign(node, attributes || {});
    if (text !== undefined) node.textContent = text;
    return node;
  }

  function buildPage(scene) {
    document.body.replaceChildren();
    const header = element("header");
    header.append(element("div", {id: "verdict", className: scene.valid ? "valid" : "invalid"},
                          scene.verdict),
                  element("div", {id: "heading"}, scene.heading));
    if (scene.counts) header.append(element("div", {id: "counts"}, scene.counts));
    header.append(element("div", {id: "what"}));
    if (scene.failure) {
      const f = scene.failure;
      const at = f.line !== null ? `, line ${f.line}` : "";
      header.append(element("div", {id: "failure"},
        `First failure (check ${f.check}${at}): ${f.message}` + (f.detail ? `\n${f.detail}` : "")));
    }
    const notes = scene.notes.concat(scene.warnings.map(w => "Warning: " + w));
    if (notes.length) {
      header.append(element("div", {id: "notes", className: scene.answer ? "plain" : ""},
                            notes.join("\n")));
    }
    const nav = element("nav");
    const main = element("main");
    const canvas = element("canvas");
    main.append(canvas);
    const footer = element("footer");
    document.body.append(header, nav, main, footer);
    return {nav, main, canvas, footer};
  }

  // ----- numbers on the axes ----------------------------------------------------------------
  function niceStep(raw) {
    const power = Math.pow(10, Math.floor(Math.log10(raw)));
    for (const m of [1, 2, 5, 10]) if (m * power >= raw * (1 - 1e-9)) return m * power;
    return 10 * power;
  }

  // The nice step below ``step`` (5 -> 2 -> 1 -> 0.5 times a power of ten).
  function smallerStep(step) {
    const power = Math.pow(10, Math.floor(Math.log10(step) + 1e-9));
    const mantissa = Math.round(step / power);
    return mantissa === 5 ? 2 * power : mantissa === 2 ? power : power / 2;
  }

  function angleLabel(value, denominator) {
    let k = Math.round(value / (Math.PI / denominator));
    if (k === 0) return "0";
    let d = denominator;
    while (d > 1 && k % 2 === 0) { k /= 2; d /= 2; }
    const sign = k < 0 ? "-" : "";
    const n = Math.abs(k);
    return `${sign}${n === 1 ? "" : n}π${d === 1 ? "" : "/" + d}`;
  }

  // [value, label] of the ticks across [low, high] at about ``gap`` pixels apart.
  function ticks(low, high, scale, angle, gap) {
    const out = [];
    if (angle) {
      let denominator = 1;
      while (denominator < 64 && (Math.PI / (2 * denominator)) * scale >= gap) denominator *= 2;
      const step = Math.PI / denominator;
      if (step * scale >= gap * 0.5) {
        for (let k = Math.ceil(low / step - 1e-9); k <= Math.floor(high / step + 1e-9); k++) {
          out.push([k * step, angleLabel(k * step, denominator)]);
        }
        return out;
      }
    }
    let step = niceStep(gap / scale);
    const count = s => Math.floor(high / s + 1e-9) - Math.ceil(low / s - 1e-9) + 1;
    while (count(step) < 3 && smallerStep(step) * scale >= 14) step = smallerStep(step);
    const digits = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
    for (let k = Math.ceil(low / step - 1e-9); k <= Math.floor(high / step + 1e-9); k++) {
      out.push([k * step, (k * step).toFixed(Math.min(digits, 12)).replace(/^-0$/, "0")]);
    }
    return out;
  }

  // ----- plots: where they sit, how they map data to pixels ---------------------------------
  // Plots stacked in the canvas; a plot at one scale for both axes hugs its box.
  function layoutPlots(view, width, height) {
    const plots = view.plots;
    const inner = height - MARGIN.top - MARGIN.bottom - MARGIN.gap * (plots.length - 1);
    const each = inner / plots.length;
    plots.forEach((p, k) => {
      const rect = {x: MARGIN.left, y: MARGIN.top + k * (each + MARGIN.gap),
                    w: Math.max(10, width - MARGIN.left - MARGIN.right), h: Math.max(10, each)};
      if (p.equal) {
        const [x0, y0, x1, y1] = p.box;
        const s = Math.min(rect.w / (x1 - x0), rect.h / (y1 - y0));
        const w = s * (x1 - x0), h = s * (y1 - y0);
        rect.x += (rect.w - w) / 2; rect.w = w; rect.h = h;
      }
      p.rect = rect;
    });
  }

  function fit(p) {
    const [x0, y0, x1, y1] = p.box;
    const r = p.rect;
    let sx = r.w / (x1 - x0), sy = r.h / (y1 - y0);
    if (p.equal) sx = sy = Math.min(sx, sy);
    p.t = {sx, sy, tx: r.x + (r.w - sx * (x1 - x0)) / 2 - sx * x0,
           ty: r.y + (r.h + sy * (y1 - y0)) / 2 + sy * y0};
  }

  function toData(p, px, py) {
    return [(px - p.t.tx) / p.t.sx, (p.t.ty - py) / p.t.sy];
  }

  function plotAt(view, px, py) {
    return view.plots.find(p => px >= p.rect.x && px <= p.rect.x + p.rect.w &&
                                py >= p.rect.y - 4 && py <= p.rect.y + p.rect.h + 4);
  }

  // ----- drawing ------------------------------------------------------------------------------
  function drawAxes(ctx, p, last) {
    const r = p.rect, t = p.t;
    ctx.save();
    ctx.strokeStyle = "#000"; ctx.lineWidth = 1;
    ctx.strokeRect(r.x + 0.5, r.y + 0.5, r.w, r.h);
    ctx.fillStyle = "#111"; ctx.font = "12px system-ui, sans-serif";
    const [xl, yt] = toData(p, r.x, r.y), [xr, yb] = toData(p, r.x + r.w, r.y + r.h);
    ctx.textAlign = "center"; ctx.textBaseline = "top";
    ctx.beginPath();
    let lastLabel = 0;  // how far the last label on x reaches past the plot's right edge
    for (const [v, label] of ticks(xl, xr, t.sx, p.x.angle, 80)) {
      const x = Math.round(t.tx + t.sx * v) + 0.5;
      ctx.moveTo(x, r.y + r.h); ctx.lineTo(x, r.y + r.h + 5);
      if (last) ctx.fillText(label, x, r.y + r.h + 7);
      lastLabel = Math.max(0, 2 * (x + ctx.measureText(label).width / 2 - r.x - r.w));
    }
    ctx.textAlign = "right"; ctx.textBaseline = "middle";
    for (const [v, label] of ticks(yb, yt, t.sy, p.y.angle, Math.min(50, r.h / 3))) {
      const y = Math.round(t.ty - t.sy * v) + 0.5;
      ctx.moveTo(r.x, y); ctx.lineTo(r.x - 5, y);
      ctx.fillText(label, r.x - 7, y);
    }
    ctx.stroke();
    ctx.font = "bold 12px system-ui, sans-serif"; ctx.textAlign = "left";
    ctx.textBaseline = "bottom";
    ctx.fillText(p.y.name, r.x + 2, r.y - 3);
    if (last) {
      ctx.textBaseline = "top";
      ctx.fillText(p.x.name, r.x + r.w + 4 + lastLabel / 2, r.y + r.h + 7);
    }
    ctx.restore();
  }

  // Strokes the first ``count`` polylines of a ``lines`` item, once per turn it lists.
  function drawLines(ctx, p, item, count) {
    const pts = item.points, t = p.t, per = item.per, starts = item.starts;
    ctx.strokeStyle = item.colour; ctx.lineWidth = item.width;
    ctx.setLineDash(item.dash || []);
    ctx.lineJoin = "round"; ctx.lineCap = "round";
    for (const [kx, ky] of item.turns) {
      const ox = t.tx + t.sx * kx * TAU, oy = t.ty - t.sy * ky * TAU, sx = t.sx, sy = t.sy;
      ctx.beginPath();
      for (let i = 0; i < count; i++) {
        const a = per ? i * per : starts[i], b = per ? a + per : starts[i + 1];
        if (b - a < 1) continue;
        ctx.moveTo(ox + sx * pts[2 * a], oy - sy * pts[2 * a + 1]);
        if (b - a === 1) ctx.lineTo(ox + sx * pts[2 * a] + 0.01, oy - sy * pts[2 * a + 1]);
        for (let j = a + 1; j < b; j++) ctx.lineTo(ox + sx * pts[2 * j], oy - sy * pts[2 * j + 1]);
        if (i % CHUNK === CHUNK - 1) { ctx.stroke(); ctx.beginPath(); }
      }
      ctx.stroke();
    }
    ctx.setLineDash([]);
  }

  function polylineCount(item) {
    return item.per ? item.points.length / (2 * item.per) : item.starts.length - 1;
  }

  const MAX_CELLS = 16e6;  // a map with more cells is shown at a lower resolution
  function cellImage(item) {
    if (item.image) return item.image;
    const k = Math.max(1, Math.ceil(Math.sqrt(item.cols * item.rows / MAX_CELLS)));
    const w = Math.ceil(item.cols / k), h = Math.ceil(item.rows / k);
    const canvas = document.createElement("canvas");
    canvas.width = w; canvas.height = h;
    const c = canvas.getContext("2d"), image = c.createImageData(w, h);
    const rgb = [1, 3, 5].map(i => parseInt(item.colour.slice(i, i + 2), 16));
    const cells = item.cells, cols = item.cols, rows = item.rows;
    for (let row = 0; row < rows; row++) {
      const y = h - 1 - Math.floor(row / k);
      for (let col = 0; col < cols; col++) {
        if (!cells[row * cols + col]) continue;
        const o = 4 * (y * w + Math.floor(col / k));
        image.data[o] = rgb[0]; image.data[o + 1] = rgb[1]; image.data[o + 2] = rgb[2];
        image.data[o + 3] = Math.min(255, image.data[o + 3] + Math.ceil(255 / (k * k)));
      }
    }
    c.putImageData(image, 0, 0);
    item.image = canvas; item.reduced = k;
    return canvas;
  }

  function drawCells(ctx, p, item) {
    const image = cellImage(item), t = p.t, [x0, y0, x1, y1] = item.box;
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(image, t.tx + t.sx * x0, t.ty - t.sy * y1, t.sx * (x1 - x0), t.sy * (y1 - y0));
  }

  function drawGridLines(ctx, p, item) {
    const t = p.t;
    if (t.sx < 4 || t.sy < 4) return;  // cells too small on the screen for their lines
    const r = p.rect, [xl, yt] = toData(p, r.x, r.y), [xr, yb] = toData(p, r.x + r.w, r.y + r.h);
    ctx.strokeStyle = "#d1d1d1"; ctx.lineWidth = 1;
    ctx.beginPath();
    for (let i = Math.max(1, Math.ceil(xl)); i <= Math.min(item.cols - 1, xr); i++) {
      const x = Math.round(t.tx + t.sx * i) + 0.5;
      ctx.moveTo(x, t.ty); ctx.lineTo(x, t.ty - t.sy * item.rows);
    }
    for (let j = Math.max(1, Math.ceil(yb)); j <= Math.min(item.rows - 1, yt); j++) {
      const y = Math.round(t.ty - t.sy * j) + 0.5;
      ctx.moveTo(t.tx, y); ctx.lineTo(t.tx + t.sx * item.cols, y);
    }
    ctx.stroke();
  }

  function polygonPath(ctx, p, flat) {
    const t = p.t;
    ctx.moveTo(t.tx + t.sx * flat[0], t.ty - t.sy * flat[1]);
    for (let i = 2; i < flat.length; i += 2) {
      ctx.lineTo(t.tx + t.sx * flat[i], t.ty - t.sy * flat[i + 1]);
    }
    ctx.closePath();
  }

  function drawShapes(ctx, p, item) {
    const t = p.t;
    ctx.fillStyle = item.fill;
    ctx.beginPath();
    for (const [x0, y0, x1, y1] of item.rects) {
      ctx.rect(t.tx + t.sx * x0, t.ty - t.sy * y1, t.sx * (x1 - x0), t.sy * (y1 - y0));
    }
    for (const [cx, cy, radius] of item.discs) {
      ctx.moveTo(t.tx + t.sx * (cx + radius), t.ty - t.sy * cy);
      ctx.ellipse(t.tx + t.sx * cx, t.ty - t.sy * cy, t.sx * radius, t.sy * radius, 0, 0, TAU);
    }
    for (const flat of item.polygons) polygonPath(ctx, p, flat);
    ctx.fill();
  }

  function drawBodies(ctx, p, item) {
    const t = p.t;
    ctx.beginPath();
    for (const flat of item.polygons) polygonPath(ctx, p, flat);
    if (item.fill) { ctx.globalAlpha = 0.6; ctx.fillStyle = item.fill; ctx.fill(); }
    ctx.globalAlpha = 1;
    ctx.strokeStyle = item.colour; ctx.lineWidth = 1.2; ctx.setLineDash(item.dash || []);
    ctx.stroke(); ctx.setLineDash([]);
    ctx.beginPath();
    for (const [x0, y0, x1, y1] of item.fronts) {
      ctx.moveTo(t.tx + t.sx * x0, t.ty - t.sy * y0);
      ctx.lineTo(t.tx + t.sx * x1, t.ty - t.sy * y1);
    }
    ctx.strokeStyle = item.front; ctx.lineWidth = 2.2; ctx.stroke();
  }

  function halo(ctx, draw, width) {
    ctx.save();
    ctx.strokeStyle = "#fff"; ctx.lineWidth = width;
    draw(); ctx.stroke();
    ctx.restore();
  }

  function drawMark(ctx, p, item) {
    const t = p.t, x = t.tx + t.sx * item.at[0], y = t.ty - t.sy * item.at[1];
    ctx.lineCap = "round";
    if (item.kind === "dot") {
      ctx.beginPath(); ctx.arc(x, y, item.radius + (item.halo ? 2 : 0), 0, TAU);
      ctx.fillStyle = "#fff"; if (item.halo) ctx.fill();
      ctx.beginPath(); ctx.arc(x, y, item.radius, 0, TAU); ctx.fillStyle = item.colour; ctx.fill();
    } else if (item.kind === "circle") {
      const rx = t.sx * item.radius, ry = t.sy * item.radius, arm = item.cross;
      const path = () => {
        ctx.beginPath();
        if (item.outline !== false) ctx.ellipse(x, y, rx, ry, 0, 0, TAU);
        if (Math.min(rx, ry) < 4 && arm) {
          ctx.moveTo(x - arm, y); ctx.lineTo(x + arm, y);
          ctx.moveTo(x, y - arm); ctx.lineTo(x, y + arm);
        }
      };
      halo(ctx, path, 5);
      path(); ctx.strokeStyle = item.colour; ctx.lineWidth = 1.8; ctx.stroke();
    } else if (item.kind === "cross") {
      const s = item.size;
      const path = () => {
        ctx.beginPath();
        ctx.moveTo(x - s, y - s); ctx.lineTo(x + s, y + s);
        ctx.moveTo(x - s, y + s); ctx.lineTo(x + s, y - s);
        ctx.moveTo(x + 1.35 * s, y); ctx.arc(x, y, 1.35 * s, 0, TAU);
      };
      halo(ctx, path, 6);
      path(); ctx.strokeStyle = item.colour; ctx.lineWidth = 2.4; ctx.stroke();
    }
  }

  function drawRings(ctx, p, item) {
    const t = p.t;
    ctx.beginPath();
    for (const [x, y] of item.points) {
      const px = t.tx + t.sx * x, py = t.ty - t.sy * y;
      ctx.moveTo(px + item.radius, py); ctx.arc(px, py, item.radius, 0, TAU);
    }
    ctx.strokeStyle = item.colour; ctx.lineWidth = 1.8; ctx.stroke();
  }

  function drawItem(ctx, p, item, state) {
    switch (item.kind) {
      case "lines": {
        let count = polylineCount(item);
        if (item.growth) {
          count = Math.min(count, Math.ceil(state.grown / state.scene.tree.stride));
          state.edgesDrawn += count;
        }
        drawLines(ctx, p, item, count);
        break;
      }
      case "cells": drawCells(ctx, p, item); break;
      case "gridlines": drawGridLines(ctx, p, item); break;
      case "shapes": drawShapes(ctx, p, item); break;
      case "outline": {
        const [x0, y0, x1, y1] = item.box, t = p.t;
        ctx.strokeStyle = item.colour; ctx.lineWidth = 1.2;
        ctx.strokeRect(t.tx + t.sx * x0, t.ty - t.sy * y1, t.sx * (x1 - x0), t.sy * (y1 - y0));
        break;
      }
      case "bodies": drawBodies(ctx, p, item); break;
      case "rings": drawRings(ctx, p, item); break;
      default: drawMark(ctx, p, item);
    }
  }

  function drawPlot(ctx, p, state, last) {
    ctx.save();
    ctx.beginPath(); ctx.rect(p.rect.x, p.rect.y, p.rect.w, p.rect.h); ctx.clip();
    for (const id of LAYERS) {
      if (!state.shown[id]) continue;
      for (const layer of p.layers) {
        if (layer.id === id) for (const item of layer.items) drawItem(ctx, p, item, state);
      }
    }
    ctx.restore();
    drawAxes(ctx, p, last);
  }

  // ----- the view's state, interaction ------------------------------------------------------
  function start(scene) {
    const page = buildPage(scene);
    const ctx = page.canvas.getContext("2d");
    const present = new Set();
    scene.views.forEach(v => v.plots.forEach(p => p.layers.forEach(l => present.add(l.id))));
    const state = {scene, view: 0, grown: scene.tree.kept, shown: {}, edgesDrawn: 0,
                   snapshot: null, timer: null, pending: false, ctx, canvas: page.canvas};
    LAYERS.forEach(id => { state.shown[id] = true; });
    const pointer = element("span", {id: "pointer"}, "");
    buildTabs(page.nav, state);
    buildControls(page.footer, state, present, pointer);
    const resize = () => {
      const dpr = window.devicePixelRatio || 1;
      page.canvas.width = Math.round(page.main.clientWidth * dpr);
      page.canvas.height = Math.round(page.main.clientHeight * dpr);
      state.dpr = dpr;
      for (const view of scene.views) {
        layoutPlots(view, page.main.clientWidth, page.main.clientHeight);
        view.plots.forEach(fit);
        linkPlots(view, view.plots[0]);
      }
      draw(state);
    };
    window.addEventListener("resize", resize);
    interact(page.canvas, state, pointer);
    const asked = /^#view=(\d+)$/.exec(window.location.hash);
    selectView(state, asked ? Math.min(Number(asked[1]), scene.views.length - 1) : 0);
    resize();
  }

  function currentView(state) { return state.scene.views[state.view]; }

  function selectView(state, index) {
    state.view = index;
    stats.view = index;
    const view = currentView(state);
    document.getElementById("what").textContent = view.what || "";
    document.querySelectorAll("nav button").forEach((b, i) => {
      b.classList.toggle("on", i === index);
    });
    draw(state);
  }

  function buildTabs(nav, state) {
    if (state.scene.views.length < 2) { nav.remove(); return; }
    state.scene.views.forEach((view, i) => {
      const button = element("button", {type: "button"}, view.name);
      button.addEventListener("click", () => selectView(state, i));
      nav.append(button);
    });
  }

  // The colour a layer's check box shows: its first item's (the start's dot for the marks).
  function swatchColour(scene, id) {
    for (const v of scene.views) for (const p of v.plots) for (const l of p.layers) {
      if (l.id !== id || !l.items.length) continue;
      const item = l.items.find(i => i.kind === "dot" && i.halo) || l.items[0];
      return item.colour || item.fill || "#999";
    }
    return "#999";
  }

  function buildControls(footer, state, present, pointer) {
    const tree = state.scene.tree;
    if (tree.kept > 0) {
      const box = element("div", {id: "growth"});
      const slider = element("input", {type: "range", min: "0", max: String(tree.kept),
                                       step: "1", value: String(tree.kept), id: "grow"});
      const label = element("span", {id: "grown"});
      const say = () => {
        label.textContent = `tree: the first ${state.grown} of ${tree.kept} edges` +
          (tree.kept < tree.total ? ` (of ${tree.total} printed)` : "") +
          (tree.stride > 1 ? `, one in ${tree.stride} drawn` : "");
      };
      slider.addEventListener("input", () => {
        state.grown = Number(slider.value);
        say();
        draw(state);
      });
      say();
      box.append(element("span", {}, "growth"), slider, label);
      footer.append(box);
    }
    for (const id of LAYERS) {
      if (!present.has(id)) continue;
      const label = element("label");
      const check = element("input", {type: "checkbox", checked: true, id: "layer-" + id});
      check.addEventListener("change", () => { state.shown[id] = check.checked; draw(state); });
      const swatch = element("span", {className: "swatch"});
      swatch.style.background = swatchColour(state.scene, id);
      label.append(check, swatch, document.createTextNode(LAYER_NAMES[id]));
      footer.append(label);
    }
    const reset = element("button", {type: "button", id: "reset"}, "reset view");
    reset.addEventListener("click", () => { currentView(state).plots.forEach(fit); draw(state); });
    footer.append(reset, pointer);
  }

  // Plots of one link (the time strips) share their x mapping.
  function linkPlots(view, source) {
    if (!source.link) return;
    for (const p of view.plots) {
      if (p !== source && p.link === source.link) { p.t.sx = source.t.sx; p.t.tx = source.t.tx; }
    }
  }

  function draw(state) {
    if (state.pending) return;
    state.pending = true;
    requestAnimationFrame(() => { state.pending = false; drawNow(state); });
  }

  function drawNow(state) {
    const began = performance.now();
    const ctx = state.ctx, view = currentView(state);
    ctx.setTransform(state.dpr, 0, 0, state.dpr, 0, 0);
    ctx.fillStyle = "#fff";
    ctx.fillRect(0, 0, state.canvas.width, state.canvas.height);
    state.edgesDrawn = 0;
    view.plots.forEach((p, k) => drawPlot(ctx, p, state, k === view.plots.length - 1));
    const reduced = view.plots.flatMap(p => p.layers).flatMap(l => l.items)
      .filter(i => i.reduced > 1).map(i => i.reduced);
    if (reduced.length) {
      ctx.fillStyle = "#a00"; ctx.font = "12px system-ui, sans-serif"; ctx.textAlign = "right";
      ctx.fillText(`map drawn at 1/${reduced[0]} of its cells' resolution`,
                   state.canvas.width / state.dpr - MARGIN.right, 14);
    }
    state.snapshot = {image: null, view: state.view,
                      t: view.plots.map(p => Object.assign({}, p.t))};
    const ms = performance.now() - began;
    stats.draws += 1; stats.lastDrawMs = ms; stats.edgesDrawn = state.edgesDrawn;
    stats.plots = view.plots.map(p => [p.t.sx, p.t.sy, p.t.tx, p.t.ty]);
    if (stats.firstDrawMs === null) stats.firstDrawMs = performance.now();
    stats.ready = true;
  }

  // While the pointer drags or the wheel turns, a slow view moves a snapshot of itself;
  // the full drawing follows when the pointer rests.
  function moved(state) {
    const view = currentView(state);
    if (stats.lastDrawMs > SLOW_DRAW_MS && view.plots.length === 1 && state.snapshot &&
        state.snapshot.view === state.view) {
      const snap = state.snapshot;
      if (!snap.image) {
        snap.image = document.createElement("canvas");
        snap.image.width = state.canvas.width; snap.image.height = state.canvas.height;
        snap.image.getContext("2d").drawImage(state.canvas, 0, 0);
      }
      const p = view.plots[0], was = snap.t[0], ctx = state.ctx;
      const ax = p.t.sx / was.sx, ay = p.t.sy / was.sy;
      ctx.setTransform(1, 0, 0, 1, 0, 0);
      ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, state.canvas.width, state.canvas.height);
      const d = state.dpr;
      ctx.save(); ctx.beginPath();
      ctx.rect(p.rect.x * d, p.rect.y * d, p.rect.w * d, p.rect.h * d); ctx.clip();
      ctx.setTransform(ax, 0, 0, ay, (p.t.tx - ax * was.tx) * d, (p.t.ty - ay * was.ty) * d);
      ctx.drawImage(snap.image, 0, 0);
      ctx.restore();
      clearTimeout(state.timer);
      state.timer = setTimeout(() => draw(state), 150);
      return;
    }
    draw(state);
  }

  function interact(canvas, state, pointer) {
    let drag = null;
    const local = e => {
      const r = canvas.getBoundingClientRect();
      return [e.clientX - r.left, e.clientY - r.top];
    };
    canvas.addEventListener("wheel", e => {
      e.preventDefault();
      const [px, py] = local(e), view = currentView(state), p = plotAt(view, px, py);
      if (!p) return;
      const f = Math.pow(1.0015, -e.deltaY);
      p.t.tx = px - f * (px - p.t.tx); p.t.sx *= f;
      if (p.zoom === "xy") { p.t.ty = py - f * (py - p.t.ty); p.t.sy *= f; }
      linkPlots(view, p);
      moved(state);
    }, {passive: false});
    canvas.addEventListener("pointerdown", e => {
      const [px, py] = local(e), p = plotAt(currentView(state), px, py);
      if (!p) return;
      drag = {p, px, py}; canvas.setPointerCapture(e.pointerId); canvas.classList.add("dragging");
    });
    canvas.addEventListener("pointermove", e => {
      const [px, py] = local(e);
      if (drag) {
        const p = drag.p;
        p.t.tx += px - drag.px; if (p.zoom === "xy") p.t.ty += py - drag.py;
        drag.px = px; drag.py = py;
        linkPlots(currentView(state), p);
        moved(state);
      }
      sayPointer(state, pointer, px, py);
    });
    const end = () => { drag = null; canvas.classList.remove("dragging"); };
    canvas.addEventListener("pointerup", end);
    canvas.addEventListener("pointercancel", end);
    canvas.addEventListener("dblclick", () => {
      currentView(state).plots.forEach(fit);
      draw(state);
    });
    canvas.addEventListener("pointerleave", () => { pointer.textContent = ""; });
  }

  function sayPointer(state, pointer, px, py) {
    const p = plotAt(currentView(state), px, py);
    if (!p) { pointer.textContent = ""; return; }
    const [x, y] = toData(p, px, py);
    const digits = s => Math.max(0, Math.min(8, Math.ceil(-Math.log10(1 / s)) + 1));
    let text = `${p.x.name} ${x.toFixed(digits(p.t.sx))}, ${p.y.name} ${y.toFixed(digits(p.t.sy))}`;
    if (p.grid && x >= 0 && y >= 0 && x < p.grid[0] && y < p.grid[1]) {
      text += `  (cell ${Math.floor(x)}, ${Math.floor(y)})`;
    }
    pointer.textContent = text;
  }

  // ----- start --------------------------------------------------------------------------------
  function fail(error) {
    stats.error = String(error && error.stack || error);
    const box = element("div", {id: "problem"}, "The view could not be drawn: " + error);
    document.body.prepend(box);
    console.error(error);
  }

  async function main() {
    try {
      const scene = JSON.parse(document.getElementById("scene").textContent);
      await decode(scene);
      start(scene);
    } catch (error) {
      fail(error);
    }
  }
  main();
})();
