// The BVH explorer (book/src/explorer.md): bvhkit compiled to wasm by
// scripts/build-explorer (crate book/explorer), drawn on a canvas. Plain JS,
// no framework. The wasm exports plain functions; results stay in Rust-owned
// buffers read through typed-array views (made anew after every call, since
// a call may grow the memory). With `?selftest` in the URL the page runs a
// fixed scenario and writes key=value lines into <pre id="selftest">, which
// scripts/test-book-in-browser compares with `cargo run --bin selftest`.
"use strict";
(function () {
  // Errors are counted for the self-test (console.error, uncaught, rejected).
  let errors = 0;
  const consoleError = console.error.bind(console);
  console.error = (...a) => { errors++; consoleError(...a); };
  window.addEventListener("error", () => errors++);
  window.addEventListener("unhandledrejection", () => errors++);

  const wasmUrl = new URL("bvhkit_explorer.wasm", document.currentScript.src);
  const $ = (id) => document.getElementById(id);
  const canvas = $("bvh-canvas");
  if (!canvas) return; // a page without the explorer (print.html, say)
  const ctx = canvas.getContext("2d");
  const SCALE = canvas.width / 100; // the world is 100 x 70 units
  let X = null; // the wasm exports
  let labels = {};
  let boxes = []; // [minx, miny, maxx, maxy]
  let tree = null; // {nodes, depth, info, outline, indices}
  let view = "tree"; // what the canvas shows beyond the tree: "pairs" or "region"
  let pairs = null; // {a: Set, b: Set, dx, dy}
  let walk = null; // {region, steps: [[kind, id, hit]], at}
  let drag = null;

  const mem = () => X.memory.buffer;
  const text = (ptr, len) => new TextDecoder().decode(new Uint8Array(mem(), ptr >>> 0, len));
  const error = () => text(X.err_ptr(), X.err_len());
  const status = (s) => { $("bvh-status").textContent = s; };

  function fillSelect(id, names, first) {
    const sel = $(id);
    sel.innerHTML = "";
    if (first) sel.add(new Option(first, "-1"));
    names.forEach((n, i) => sel.add(new Option(n, String(i))));
  }

  function selectByName(id, name) {
    const sel = $(id);
    const o = [...sel.options].find((o) => o.text === name);
    if (!o) throw new Error(`no ${name} in ${id}`);
    sel.value = o.value;
  }

  // Boxes go to Rust through the input buffer; a generated scene comes back through it.
  function writeBoxes() {
    const n = boxes.length;
    const v = new Float32Array(mem(), X.input(n) >>> 0, 4 * n);
    boxes.forEach((b, i) => v.set(b, 4 * i));
  }

  function generate(kind) {
    const n = X.scene(kind, +$("bvh-n").value, +$("bvh-seed").value);
    const v = new Float32Array(mem(), X.input(n) >>> 0, 4 * n);
    boxes = [];
    for (let i = 0; i < n; i++) boxes.push([...v.subarray(4 * i, 4 * i + 4)]);
    rebuild();
  }

  function load() {
    const rows = $("bvh-text").value.split("\n").map((l) => l.trim()).filter((l) => l && !l.startsWith("#"));
    const parsed = rows.map((l) => l.split(/[\s,]+/).map(Number));
    const bad = parsed.findIndex((b) => b.length !== 4 || b.some((x) => !Number.isFinite(x)));
    if (bad >= 0) return status(`line ${bad + 1}: want four numbers: minx miny maxx maxy`);
    boxes = parsed;
    rebuild();
  }

  function rebuild() {
    writeBoxes();
    const n = X.build(+$("bvh-builder").value, +$("bvh-partition").value, +$("bvh-axis").value,
      +$("bvh-leaf").value, +$("bvh-volume").value);
    pairs = null;
    walk = null;
    view = "tree";
    if (n < 0) {
      tree = null;
      status("build failed: " + error());
      return draw();
    }
    const info = [...new Int32Array(mem(), X.info_ptr() >>> 0, 6 * n)];
    const outline = [...new Float32Array(mem(), X.outline_ptr() >>> 0, X.outline_len())];
    const indices = [...new Uint32Array(mem(), X.indices_ptr() >>> 0, boxes.length)];
    let depth = 0;
    for (let k = 0; k < n; k++) depth = Math.max(depth, info[6 * k]);
    tree = { nodes: n, depth, info, outline, indices };
    const slider = $("bvh-depth");
    slider.max = String(depth);
    slider.value = String(depth);
    status(`${boxes.length} boxes: ${n} nodes, ${leafCount()} leaves, depth ${depth}`);
    draw();
  }

  const leafCount = () => tree.info.filter((_, i) => i % 6 === 1).reduce((a, b) => a + b, 0);

  function setDepth(d) {
    if (!tree) return;
    $("bvh-depth").value = String(Math.max(0, Math.min(tree.depth, d)));
    const shown = tree.info.filter((x, i) => i % 6 === 0 && x <= +$("bvh-depth").value).length;
    status(`build, level by level: depth <= ${$("bvh-depth").value} of ${tree.depth}, ${shown} of ${tree.nodes} nodes`);
    draw();
  }

  function runPairs() {
    if (!tree) return;
    const dx = +$("bvh-dx").value, dy = +$("bvh-dy").value;
    const n = X.query(dx, dy, +$("bvh-descent").value);
    if (n < 0) return status("query failed: " + error());
    const p = new Uint32Array(mem(), X.pairs_ptr() >>> 0, 2 * n);
    pairs = { a: new Set(), b: new Set(), dx, dy, n, nv: X.counter(0), np: X.counter(1) };
    for (let i = 0; i < n; i++) { pairs.a.add(p[2 * i]); pairs.b.add(p[2 * i + 1]); }
    view = "pairs";
    status(`A against B = A moved by (${dx}, ${dy}), descent ${$("bvh-descent").selectedOptions[0].text}:\n` +
      `${n} overlapping pairs; Nv = ${pairs.nv} volume tests, Np = ${pairs.np} box tests` +
      (X.check() === 1 ? " (checked against brute force)" : " (DIFFERS FROM BRUTE FORCE)"));
    draw();
  }

  function runRegion(r) {
    if (!tree) return;
    const n = X.region(r[0], r[1], r[2], r[3]);
    if (n < 0) return status("region query failed: " + error());
    const s = new Int32Array(mem(), X.steps_ptr() >>> 0, 3 * n);
    const steps = [];
    for (let i = 0; i < n; i++) steps.push([s[3 * i], s[3 * i + 1], s[3 * i + 2]]);
    walk = { region: r, steps, at: 0, ok: X.check() === 1 };
    view = "region";
    stepRegion(0);
  }

  // Replays the walk up to step `at` and tallies what it did so far.
  function stepRegion(delta) {
    if (!walk) return;
    walk.at = Math.max(0, Math.min(walk.steps.length, walk.at + delta));
    let nv = 0, np = 0, hits = 0;
    for (const [kind, , hit] of walk.steps.slice(0, walk.at)) {
      if (kind === 0) nv++; else { np++; hits += hit; }
    }
    Object.assign(walk, { nv, np, hits });
    const last = walk.steps[walk.at - 1];
    const what = !last ? "nothing tested yet" : last[0] === 0
      ? `node ${last[1]}'s volume ${last[2] ? "overlaps: open it" : "misses: skip its subtree"}`
      : `box ${last[1]} ${last[2] ? "overlaps: a hit" : "misses"}`;
    status(`region query, step ${walk.at} of ${walk.steps.length}: ${what}\n` +
      `Nv = ${nv} volume tests, Np = ${np} box tests, ${hits} hits` +
      (walk.at === walk.steps.length ? (walk.ok ? " (the library's query finds the same, with the same Nv)" : " (DIFFERS FROM THE LIBRARY)") : ""));
    draw();
  }

  // ---- drawing ----
  const px = (x) => x * SCALE;
  const colour = (d, a) => `hsla(${(d * 47) % 360}, 70%, 40%, ${a})`;

  function rect(b, fill, stroke, width, dx = 0, dy = 0) {
    const [x, y, w, h] = [px(b[0] + dx), px(b[1] + dy), px(b[2] - b[0]), px(b[3] - b[1])];
    if (fill) { ctx.fillStyle = fill; ctx.fillRect(x, y, w, h); }
    if (stroke) { ctx.strokeStyle = stroke; ctx.lineWidth = width; ctx.strokeRect(x, y, w, h); }
  }

  function outline(k, stroke, width, dash) {
    const [start, len] = [tree.info[6 * k + 4], tree.info[6 * k + 5]];
    if (len < 2) return;
    ctx.beginPath();
    for (let i = 0; i < len; i++) {
      const [x, y] = [tree.outline[2 * (start + i)], tree.outline[2 * (start + i) + 1]];
      i ? ctx.lineTo(px(x), px(y)) : ctx.moveTo(px(x), px(y));
    }
    ctx.closePath();
    ctx.setLineDash(dash || []);
    ctx.strokeStyle = stroke;
    ctx.lineWidth = width;
    ctx.stroke();
    ctx.setLineDash([]);
  }

  function draw() {
    ctx.fillStyle = "#fff";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    const hitBox = new Set(), missBox = new Set();
    if (view === "region" && walk) {
      for (const [kind, id, hit] of walk.steps.slice(0, walk.at)) if (kind === 1) (hit ? hitBox : missBox).add(id);
    }
    boxes.forEach((b, i) => {
      let fill = "rgba(90, 90, 90, 0.18)";
      if (view === "pairs" && pairs && pairs.a.has(i)) fill = "rgba(220, 40, 40, 0.45)";
      if (hitBox.has(i)) fill = "rgba(30, 160, 60, 0.6)";
      if (missBox.has(i)) fill = "rgba(220, 120, 0, 0.45)";
      rect(b, fill, "#333", 1);
    });
    if (view === "pairs" && pairs) {
      boxes.forEach((b, i) => rect(b, null, pairs.b.has(i) ? "#c22" : "rgba(40, 80, 200, 0.6)", 1, pairs.dx, pairs.dy));
    }
    if (tree && view !== "region") {
      const d = +$("bvh-depth").value;
      for (let k = 0; k < tree.nodes; k++) {
        const nd = tree.info[6 * k];
        if (nd <= d) outline(k, colour(nd, nd === d ? 0.95 : 0.4), nd === d ? 2 : 1, tree.info[6 * k + 1] ? [4, 3] : null);
      }
    }
    if (view === "region" && walk) {
      const tested = new Map();
      for (const [kind, id, hit] of walk.steps.slice(0, walk.at)) if (kind === 0) tested.set(id, hit);
      tested.forEach((hit, k) => outline(k, hit ? "rgba(30, 140, 60, 0.8)" : "rgba(210, 40, 40, 0.8)", 1.5));
      const last = walk.steps[walk.at - 1];
      if (last && last[0] === 0) outline(last[1], "#000", 3);
      if (last && last[0] === 1) rect(boxes[last[1]], null, "#000", 3);
      ctx.setLineDash([6, 4]);
      rect(walk.region, "rgba(40, 90, 220, 0.08)", "#2a5ad8", 2);
      ctx.setLineDash([]);
    }
    if (drag && drag.to) rect(norm(drag.from, drag.to), null, "#000", 1);
  }

  // ---- input ----
  const norm = (a, b) => [Math.min(a[0], b[0]), Math.min(a[1], b[1]), Math.max(a[0], b[0]), Math.max(a[1], b[1])];
  function at(e) {
    const r = canvas.getBoundingClientRect();
    return [((e.clientX - r.left) * canvas.width) / r.width / SCALE, ((e.clientY - r.top) * canvas.height) / r.height / SCALE];
  }
  canvas.addEventListener("pointerdown", (e) => {
    drag = { from: at(e) };
    if (e.isTrusted) canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener("pointermove", (e) => { if (drag) { drag.to = at(e); draw(); } });
  canvas.addEventListener("pointerup", (e) => {
    if (!drag) return;
    const b = norm(drag.from, at(e));
    drag = null;
    if (b[2] - b[0] < 0.2 && b[3] - b[1] < 0.2) return draw();
    if ($("bvh-drag").value === "region") runRegion(b);
    else { boxes.push(b); rebuild(); }
  });

  function wire() {
    $("bvh-random").onclick = () => generate(0);
    $("bvh-row").onclick = () => generate(1);
    $("bvh-clusters").onclick = () => generate(2);
    $("bvh-clear").onclick = () => { boxes = []; rebuild(); };
    $("bvh-load").onclick = load;
    $("bvh-show").onclick = () => { $("bvh-text").value = boxes.map((b) => b.map((x) => +x.toFixed(3)).join(" ")).join("\n"); };
    for (const id of ["bvh-builder", "bvh-partition", "bvh-axis", "bvh-leaf", "bvh-volume"]) $(id).onchange = rebuild;
    $("bvh-depth").oninput = () => { view = "tree"; setDepth(+$("bvh-depth").value); };
    $("bvh-back").onclick = () => { view = "tree"; setDepth(+$("bvh-depth").value - 1); };
    $("bvh-step").onclick = () => { view = "tree"; setDepth(+$("bvh-depth").value + 1); };
    $("bvh-query").onclick = runPairs;
    $("bvh-walk-back").onclick = () => stepRegion(-1);
    $("bvh-walk-step").onclick = () => stepRegion(1);
    $("bvh-walk-end").onclick = () => stepRegion(Infinity);
    $("bvh-builder").addEventListener("change", () => {
      const topDown = +$("bvh-builder").value < labels.builders.length - 2; // PLOC and insertion have no split choices
      $("bvh-partition").disabled = $("bvh-axis").disabled = !topDown;
    });
  }

  // The self-test: the scenario of book/explorer/src/lib.rs (SELFTEST), through the page's own controls.
  function selftest() {
    $("bvh-n").value = "60";
    $("bvh-seed").value = "7";
    selectByName("bvh-builder", "sah");
    $("bvh-partition").value = $("bvh-axis").value = "-1";
    $("bvh-leaf").value = "2";
    selectByName("bvh-volume", "18-dop");
    $("bvh-clusters").click();
    $("bvh-dx").value = "1.5";
    $("bvh-dy").value = "1";
    selectByName("bvh-descent", "larger");
    $("bvh-query").click();
    const result = { boxes: boxes.length, nodes: tree.nodes, depth: tree.depth, pairs: pairs.n, nv: pairs.nv, np: pairs.np };
    runRegion([20, 15, 55, 40]);
    while (walk.at < walk.steps.length) $("bvh-walk-step").click();
    Object.assign(result, { region_steps: walk.at, region_hits: walk.hits, region_nv: walk.nv });
    result.rust_check = X.check() === 1 && walk.ok ? "ok" : "FAILED";
    result.ui = uiCheck();
    // Whether the canvas shows anything: pixels off the white background.
    const px = ctx.getImageData(0, 0, canvas.width, canvas.height).data;
    let ink = 0;
    for (let i = 0; i < px.length; i += 4) if (px[i] < 250 || px[i + 1] < 250 || px[i + 2] < 250) ink++;
    result.canvas = ink > 0.01 * canvas.width * canvas.height ? "drawn" : "blank";
    result.errors = errors;
    const pre = document.createElement("pre");
    pre.id = "selftest";
    pre.textContent = Object.entries(result).map(([k, v]) => `${k}=${v}`).join("\n") + "\n";
    canvas.parentNode.appendChild(pre);
  }

  // The controls the scenario above does not touch: levels, typed-in boxes, dragging.
  function uiCheck() {
    const fail = [];
    const expect = (what, ok) => { if (!ok) fail.push(what); };
    const d = tree.depth;
    $("bvh-back").click(); $("bvh-back").click(); $("bvh-step").click();
    expect("levels", +$("bvh-depth").value === d - 1 && view === "tree");
    $("bvh-text").value = "10 10 20 15\n12 12 30 20\n# a comment\n50 50 60 55";
    $("bvh-load").click();
    expect("load", boxes.length === 3 && tree && tree.info[2] === 3);
    const dragOn = (a, b) => {
      const r = canvas.getBoundingClientRect();
      const client = (p) => ({ clientX: r.left + (p[0] * SCALE * r.width) / canvas.width, clientY: r.top + (p[1] * SCALE * r.height) / canvas.height, bubbles: true });
      canvas.dispatchEvent(new PointerEvent("pointerdown", client(a)));
      canvas.dispatchEvent(new PointerEvent("pointermove", client(b)));
      canvas.dispatchEvent(new PointerEvent("pointerup", client(b)));
    };
    dragOn([30, 30], [40, 38]);
    expect("drag adds a box", boxes.length === 4 && tree.info[2] === 4 && Math.abs(boxes[3][2] - 40) < 0.01);
    $("bvh-drag").value = "region";
    dragOn([5, 5], [35, 35]);
    $("bvh-walk-end").click();
    expect("drag sets the region", view === "region" && walk.ok && walk.hits === 3);
    $("bvh-drag").value = "add";
    return fail.length ? "FAILED:" + fail.join(",") : "ok";
  }

  async function start() {
    let module;
    try {
      const resp = await fetch(wasmUrl);
      if (!resp.ok) throw new Error(`${wasmUrl}: HTTP ${resp.status}`);
      module = await WebAssembly.instantiate(await resp.arrayBuffer(), {});
    } catch (e) {
      status("The explorer's wasm is missing: run scripts/build-explorer, then mdbook serve book.\n" + e);
      console.error("explorer: could not load the wasm:", e);
      if (location.search.includes("selftest")) canvas.parentNode.insertAdjacentHTML("beforeend", `<pre id="selftest">load=FAILED\nerrors=${errors}\n</pre>`);
      return;
    }
    X = module.instance.exports;
    for (const line of text(X.labels_ptr(), X.labels_len()).split("\n")) {
      const [key, list] = line.split(":");
      if (list) labels[key] = list.split(",");
    }
    fillSelect("bvh-builder", labels.builders);
    fillSelect("bvh-partition", labels.partitions, "(the preset's)");
    fillSelect("bvh-axis", labels.axes, "(the preset's)");
    fillSelect("bvh-volume", labels.volumes);
    fillSelect("bvh-descent", labels.descents);
    selectByName("bvh-descent", "larger");
    wire();
    if (location.search.includes("selftest")) {
      try { selftest(); } catch (e) { console.error("selftest:", e); canvas.parentNode.insertAdjacentHTML("beforeend", `<pre id="selftest">selftest=FAILED ${e}\nerrors=${errors}\n</pre>`); }
    } else generate(0);
  }
  start();
})();
