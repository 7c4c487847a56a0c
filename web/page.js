// The lab page: six panels, each a WebAssembly model from odyn (web/src) drawn on a canvas.
// Every display frame hands each panel the frame's duration; the panel's fixed-timestep
// accumulator (odyn::FixedTimestep, in Rust) turns it into whole steps. `?check` runs each
// panel's fixed check instead and publishes the fingerprints and costs as `window.labCheck`
// (scripts/browser.sh compares them with the native build's).
import init, { SpringLab, PendulumLab, ClothLab, GrayScottLab, DamBreakLab, MpmLab } from "./pkg/lab.js";

const errors = [];
window.labErrors = errors;
addEventListener("error", (event) => errors.push(String(event.message)));
addEventListener("unhandledrejection", (event) => errors.push(String(event.reason)));

await init();
const checking = new URLSearchParams(location.search).has("check");

/// A panel: its section, canvas, model, drawing, and what its frames cost.
class Panel {
  constructor(id, lab, draw) {
    this.id = id;
    this.root = document.getElementById(id);
    this.canvas = this.root.querySelector("canvas");
    this.context = this.canvas.getContext("2d");
    this.lab = lab;
    this.draw = draw;
    this.window = { ms: 0, steps: 0, frames: 0, since: performance.now() };
    this.shown = "";
    this.failed = false;
    // A panel scrolled out of view pauses: its accumulator gets no time.
    this.visible = true;
    new IntersectionObserver(([entry]) => (this.visible = entry.isIntersecting)).observe(this.root);
  }

  control(name) {
    return this.root.querySelector(`[name="${name}"]`);
  }

  // One display frame of `seconds`.
  tick(seconds) {
    if (this.failed || !this.visible) return;
    try {
      const started = performance.now();
      const steps = this.lab.frame(seconds);
      this.window.ms += performance.now() - started;
      this.window.steps += steps;
      this.window.frames += 1;
      this.draw(this);
      this.status();
    } catch (error) {
      this.fail(error);
    }
  }

  // Method, dt, steps a frame and their cost, averaged over the last second.
  status() {
    const now = performance.now();
    const w = this.window;
    if (now - w.since > 1000 && w.frames > 0) {
      const perStep = w.steps > 0 ? (1000 * w.ms) / w.steps : 0;
      this.shown =
        `${(w.steps / w.frames).toFixed(1)} steps/frame · ${perStep.toFixed(1)} µs/step · ` +
        `${(w.ms / w.frames).toFixed(2)} ms/frame`;
      this.window = { ms: 0, steps: 0, frames: 0, since: now };
    }
    this.root.querySelector(".status").textContent =
      `${this.lab.method()} · dt ${format(this.lab.dt())} · t ${this.lab.t().toFixed(2)} · ${this.shown}`;
  }

  fail(error) {
    this.failed = true;
    errors.push(`${this.id}: ${error}`);
    const status = this.root.querySelector(".status");
    status.textContent = `stopped: ${error}`;
    status.classList.add("error");
  }

  restart(how) {
    try {
      how();
      this.failed = false;
      this.root.querySelector(".status").classList.remove("error");
      this.reset?.();
    } catch (error) {
      this.fail(error);
    }
  }
}

function format(x) {
  return x >= 0.01 ? x.toPrecision(3) : x.toExponential(2);
}

/// Maps a world box onto a canvas rectangle, y up.
function view(box, rect) {
  const [x0, x1, y0, y1] = box;
  const [left, top, width, height] = rect;
  return {
    x: (x) => left + ((x - x0) / (x1 - x0)) * width,
    y: (y) => top + ((y1 - y) / (y1 - y0)) * height,
    back: (px, py) => [x0 + ((px - left) / width) * (x1 - x0), y1 - ((py - top) / height) * (y1 - y0)],
  };
}

function line(context, points, colour, width = 1.5, dash = []) {
  context.strokeStyle = colour;
  context.lineWidth = width;
  context.setLineDash(dash);
  context.beginPath();
  points.forEach(([x, y], i) => (i ? context.lineTo(x, y) : context.moveTo(x, y)));
  context.stroke();
  context.setLineDash([]);
}

function label(context, text, x, y, colour = "#4a5568") {
  context.fillStyle = colour;
  context.font = "12px system-ui, sans-serif";
  context.fillText(text, x, y);
}

// (a) The spring lab: the mass, x(t) against cos t, and E/E₀ on a log scale.
function springPanel() {
  const panel = new Panel("spring", new SpringLab(), drawSpring);
  const method = panel.control("method");
  SpringLab.methods().forEach((name, i) => method.add(new Option(SpringLab.labels()[i], name)));
  const dt = panel.control("dt");
  const restart = () =>
    panel.restart(() => panel.lab.restart(method.value, Number((10 ** Number(dt.value)).toPrecision(3))));
  panel.reset = () => {
    panel.history = [];
    panel.control("dt-value").textContent = `dt = ${format(panel.lab.dt())}`;
  };
  method.onchange = restart;
  dt.oninput = restart;
  panel.control("restart").onclick = restart;
  panel.reset();
  return panel;
}

function drawSpring(panel) {
  const { context: c, lab } = panel;
  const [t, x, e] = [lab.t(), lab.x(), lab.energy()];
  panel.history.push([t, x, e]);
  while (panel.history.length > 2 && panel.history[0][0] < t - 12) panel.history.shift();
  c.clearRect(0, 0, 640, 320);
  // The mass on its spring, |x| ≤ 3 shown.
  const slot = view([-3, 3, -1, 1], [20, 10, 200, 60]);
  const mass = slot.x(Math.max(-3, Math.min(3, x)));
  const coils = Array.from({ length: 25 }, (_, i) => [
    20 + (i / 24) * (mass - 30),
    40 + (i % 2 ? -8 : 8) * (i > 0 && i < 24),
  ]);
  line(c, [[20, 15], [20, 65]], "#1d2430", 3);
  line(c, coils, "#6b7280");
  c.fillStyle = "#2b6cb0";
  c.fillRect(mass - 10, 28, 20, 24);
  // x(t) against the exact cos t over the last 12 s.
  const plot = view([t - 12, t, -2, 2], [240, 10, 390, 140]);
  line(c, [[240, plot.y(0)], [630, plot.y(0)]], "#e3e6eb", 1);
  const exact = Array.from({ length: 121 }, (_, i) => t - 12 + i / 10);
  line(c, exact.map((s) => [plot.x(s), plot.y(SpringLab.exact(s))]), "#9aa3af", 1.5, [5, 4]);
  line(c, panel.history.map(([s, x]) => [plot.x(s), plot.y(Math.max(-2, Math.min(2, x)))]), "#2b6cb0", 2);
  label(c, "x(t) — exact cos t dashed", 250, 24);
  // E/E₀ over the last 12 s, log scale 1/10 … 10.
  const energy = view([t - 12, t, -1, 1], [240, 170, 390, 140]);
  line(c, [[240, energy.y(0)], [630, energy.y(0)]], "#e3e6eb", 1);
  const log = (e) => Math.max(-1, Math.min(1, Math.log10(e / 0.5)));
  line(c, panel.history.map(([s, , e]) => [energy.x(s), energy.y(log(e))]), "#c05621", 2);
  label(c, "E/E₀ (log scale, 0.1 … 10)", 250, 184);
  label(c, `E/E₀ = ${(e / 0.5).toPrecision(6)}`, 20, 110, "#c05621");
  label(c, `x = ${x.toPrecision(4)}, cos t = ${SpringLab.exact(t).toPrecision(4)}`, 20, 130);
  const theory = lab.explicit_euler_growth();
  panel.root.querySelector(".note").textContent =
    lab.method() === "Explicit Euler"
      ? `Explicit Euler multiplies the energy by 1 + ω²dt² = ${theory.toFixed(7)} every step ` +
        `(ω = 1); measured (E/E₀)^(1/n) = ${lab.growth_per_step().toFixed(7)} after ${lab.steps()} steps.`
      : `${lab.method()}: E/E₀ = ${(e / 0.5).toPrecision(8)} after ${lab.steps()} steps.`;
}

// (b) Two double pendulums a micro-radian apart.
function pendulumPanel() {
  const panel = new Panel("pendulum", new PendulumLab(), drawPendulum);
  panel.reset = () => (panel.trails = [[], []]);
  panel.control("restart").onclick = () => panel.restart(() => panel.lab.restart());
  panel.reset();
  return panel;
}

function drawPendulum(panel) {
  const { context: c, lab } = panel;
  const bobs = lab.bobs();
  c.clearRect(0, 0, 640, 320);
  const v = view([-2.2, 2.2, -2.2, 2.2], [170, 10, 300, 300]);
  const colours = ["#2b6cb0", "#c05621"];
  [0, 1].forEach((k) => {
    const [x1, y1, x2, y2] = bobs.slice(4 * k, 4 * k + 4);
    const trail = panel.trails[k];
    trail.push([v.x(x2), v.y(y2)]);
    if (trail.length > 240) trail.shift();
    line(c, trail, colours[k] + "66", 1);
    line(c, [[v.x(0), v.y(0)], [v.x(x1), v.y(y1)], [v.x(x2), v.y(y2)]], colours[k], 2.5);
    for (const [x, y] of [[x1, y1], [x2, y2]]) {
      c.fillStyle = colours[k];
      c.beginPath();
      c.arc(v.x(x), v.y(y), 7, 0, 2 * Math.PI);
      c.fill();
    }
  });
  label(c, `lower bobs ${lab.separation().toExponential(2)} m apart`, 10, 20);
  label(c, `energy drift ${lab.energy_drift().toExponential(1)}`, 10, 38);
  panel.root.querySelector(".note").textContent =
    "Same model, same RK4 step; the second starts with θ₂ larger by 10⁻⁶ rad. " +
    "Each keeps its energy to ~10⁻⁹ while the two part: chaos, not error.";
}

// (c) The cloth twice, draggable with the mouse or a finger.
function clothPanel() {
  const panel = new Panel("cloth", new ClothLab(), drawCloth);
  const halves = [0, 1].map((k) => view([-0.15, 1.55, -1.3, 0.45], [10 + 315 * k, 10, 300, 300]));
  panel.halves = halves;
  const world = (event) => {
    const box = panel.canvas.getBoundingClientRect();
    const px = ((event.clientX - box.left) / box.width) * 640;
    const py = ((event.clientY - box.top) / box.height) * 320;
    return halves[px < 320 ? 0 : 1].back(px, py);
  };
  panel.canvas.onpointerdown = (event) => {
    const [x, y] = world(event);
    if (panel.lab.grab(x, y, 0.08)) panel.canvas.setPointerCapture(event.pointerId);
  };
  panel.canvas.onpointermove = (event) => panel.lab.drag(...world(event));
  panel.canvas.onpointerup = () => panel.lab.release();
  panel.links = panel.lab.links();
  const solve = panel.control("solve");
  ClothLab.solves().forEach((name, i) => solve.add(new Option(ClothLab.solve_labels()[i], name)));
  solve.onchange = () => panel.restart(() => panel.lab.set_solve(solve.value));
  panel.control("restart").onclick = () => panel.restart(() => panel.lab.restart());
  // The check runs once for each solve; the page's choice is restored after it.
  panel.variants = [["cloth", "baraff_witkin"], ["cloth_qn", "quasi_newton"]];
  panel.select = (name) => panel.lab.set_solve(name ?? solve.value);
  return panel;
}

function drawCloth(panel) {
  const { context: c, lab } = panel;
  const points = lab.points();
  const count = points.length / 4;
  c.clearRect(0, 0, 640, 320);
  ["XPBD", "implicit Euler"].forEach((name, k) => {
    const v = panel.halves[k];
    const at = (i) => [v.x(points[2 * (count * k + i)]), v.y(points[2 * (count * k + i) + 1])];
    c.strokeStyle = k ? "#c05621" : "#2b6cb0";
    c.lineWidth = 1;
    c.beginPath();
    for (let s = 0; s < panel.links.length; s += 2) {
      const [a, b] = [at(panel.links[s]), at(panel.links[s + 1])];
      c.moveTo(...a);
      c.lineTo(...b);
    }
    c.stroke();
    label(c, name, 20 + 315 * k, 24);
  });
  panel.root.querySelector(".note").textContent =
    `${lab.side()}² particles, springs of k = 10⁴ N/m. Implicit Euler has taken ` +
    `${lab.factorizations()} sparse Cholesky factorizations (one a step solved the ` +
    "Baraff–Witkin way, one a run by the quasi-Newton solve).";
}

// (d) Gray–Scott with its named patterns.
function grayScottPanel() {
  const panel = new Panel("gray_scott", new GrayScottLab(), drawGrayScott);
  const pattern = panel.control("pattern");
  GrayScottLab.patterns().forEach((name, i) => pattern.add(new Option(name, String(i))));
  const restart = () => panel.restart(() => panel.lab.restart(Number(pattern.value)));
  pattern.onchange = restart;
  panel.control("restart").onclick = restart;
  const side = panel.lab.side();
  panel.image = new OffscreenCanvas(side, side);
  return panel;
}

function drawGrayScott(panel) {
  const { context: c, lab, image } = panel;
  const side = lab.side();
  const pixels = new ImageData(new Uint8ClampedArray(lab.pixels()), side, side);
  image.getContext("2d").putImageData(pixels, 0, 0);
  c.imageSmoothingEnabled = false;
  c.drawImage(image, 0, 0, 256, 256);
  panel.root.querySelector(".note").textContent =
    `${side}² cells of Pearson's size, v shown; ${lab.speed()} time units a second of real time.`;
}

// (e) The SPH dam break.
function damBreakPanel() {
  const panel = new Panel("dam_break", new DamBreakLab(), drawDamBreak);
  panel.control("restart").onclick = () => panel.restart(() => panel.lab.restart());
  return panel;
}

function drawDamBreak(panel) {
  const { context: c, lab } = panel;
  const [width, height] = lab.domain();
  const v = view([0, width, 0, height], [20, 20, 600, 600 * (height / width)]);
  c.clearRect(0, 0, 640, 280);
  line(c, [[v.x(0), v.y(height)], [v.x(0), v.y(0)], [v.x(width), v.y(0)], [v.x(width), v.y(height)]], "#1d2430", 2);
  const particles = lab.particles();
  const speeds = lab.speeds();
  for (let i = 0; i < speeds.length; i++) {
    const s = Math.min(1, speeds[i] / 2.5);
    c.fillStyle = `rgb(${Math.round(40 + 200 * s)}, ${Math.round(110 + 60 * s)}, ${Math.round(220 - 150 * s)})`;
    c.beginPath();
    c.arc(v.x(particles[2 * i]), v.y(particles[2 * i + 1]), 3.2, 0, 2 * Math.PI);
    c.fill();
  }
  panel.root.querySelector(".note").textContent =
    `${speeds.length} fluid particles; shown at ${lab.speed()} × real time; ` +
    `front at ${lab.front().toFixed(3)} m.`;
}

// (f) Jelly, water and snow by MLS-MPM.
function mpmPanel() {
  const panel = new Panel("mpm", new MpmLab(), drawMpm);
  panel.reset = () => (panel.kinds = panel.lab.materials());
  panel.control("restart").onclick = () => panel.restart(() => panel.lab.restart());
  panel.reset();
  return panel;
}

function drawMpm(panel) {
  const { context: c, lab } = panel;
  const v = view([0, 1, 0, 1], [10, 10, 300, 300]);
  c.clearRect(0, 0, 640, 320);
  const wall = 3 / 64;
  line(c, [[v.x(wall), v.y(1 - wall)], [v.x(wall), v.y(wall)], [v.x(1 - wall), v.y(wall)], [v.x(1 - wall), v.y(1 - wall)]], "#1d2430", 2);
  const colours = ["#2b6cb0", "#dd6b20", "#8d99ae"];
  const names = ["water", "jelly", "snow"];
  const points = lab.particles();
  for (let k = 0; k < 3; k++) {
    c.fillStyle = colours[k];
    for (let i = 0; i < panel.kinds.length; i++) {
      if (panel.kinds[i] === k) c.fillRect(v.x(points[2 * i]) - 1, v.y(points[2 * i + 1]) - 1, 2.2, 2.2);
    }
    label(c, names[k], 330, 30 + 20 * k, colours[k]);
  }
  label(c, `energy left ${(100 * lab.energy_left()).toFixed(1)} % of the start's`, 330, 110);
  panel.root.querySelector(".note").textContent =
    `${panel.kinds.length} particles on a 64² grid, shown at ${lab.speed()} × real time: water ` +
    "(weakly compressible), jelly (fixed-corotated) and Stomakhin's snow, one MLS-MPM step for all.";
}

const panels = [];
for (const make of [springPanel, pendulumPanel, clothPanel, grayScottPanel, damBreakPanel, mpmPanel]) {
  try {
    panels.push(make());
  } catch (error) {
    errors.push(`${make.name}: ${error}`);
  }
}

if (checking) {
  runChecks();
} else {
  let last = performance.now();
  const frame = (now) => {
    const seconds = Math.max(0, (now - last) / 1000);
    last = now;
    for (const panel of panels) panel.tick(seconds);
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);
}

// Each panel's check, repeated for at least 300 ms to time it; then its fingerprint and the
// cost of one 60 Hz frame at its default step.
function runChecks() {
  const results = [];
  for (const panel of panels) {
    try {
      for (const [name, variant] of panel.variants ?? [[panel.id, null]]) {
        if (variant) panel.select(variant);
        let steps = 0;
        const started = performance.now();
        do steps += panel.lab.check();
        while (performance.now() - started < 300);
        const msPerStep = (performance.now() - started) / steps;
        const stepsPerFrame = ((1 / 60) * (panel.lab.speed?.() ?? 1)) / panel.lab.dt();
        results.push({
          panel: name,
          fingerprint: panel.lab.fingerprint(),
          steps,
          usPerStep: 1000 * msPerStep,
          stepsPerFrame,
          msPerFrame: msPerStep * stepsPerFrame,
        });
      }
      if (panel.variants) panel.select(null);
      panel.reset?.();
      panel.draw(panel);
      panel.status();
    } catch (error) {
      panel.fail(error);
    }
  }
  const report = { results, errors };
  const pre = document.getElementById("check");
  pre.textContent = JSON.stringify(report, null, 2);
  pre.hidden = false;
  window.labCheck = report;
}
