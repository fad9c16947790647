// The results page's image comparison (make report; experiments/harness/report.py writes the
// page and the data). Each figure's images are float RGB (half floats, gzip, base64) in a
// script of their own, data/<figure>.js, loaded when the figure scrolls into view, so that the
// page works from file:// with no server: it calls ReportViewer.register(id, data).
//
// Two panes per figure: the image chosen (keys 1-9, or ←/→ to step through them) and the
// reference, or with `e` the chosen image's relative error against the reference in false
// colour. Zoom (wheel) and pan (drag) move both panes together (panzoom); exposure (slider,
// +/-) applies to the float values live.
/* global panzoom, d3 */
"use strict";

const ReportViewer = (() => {
  const viewers = new Map();  // figure id -> Viewer
  const status = { registered: 0, decoded: 0, errors: [] };

  // IEEE half -> float.
  function halfToFloat(h) {
    const sign = h & 0x8000 ? -1 : 1;
    const exponent = (h >> 10) & 0x1f;
    const fraction = h & 0x3ff;
    if (exponent === 0) return sign * 2 ** -14 * (fraction / 1024);
    if (exponent === 31) return fraction ? NaN : sign * Infinity;
    return sign * 2 ** (exponent - 15) * (1 + fraction / 1024);
  }

  async function decode(base64) {
    const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("gzip"));
    const raw = new Uint16Array(await new Response(stream).arrayBuffer());
    const out = new Float32Array(raw.length);
    for (let i = 0; i < raw.length; ++i) out[i] = halfToFloat(raw[i]);
    return out;
  }

  function srgb(v) {
    if (!(v > 0)) return 0;
    const c = v <= 0.0031308 ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055;
    return Math.min(255, Math.round(255 * c));
  }

  // The error view's colour map, inferno, sampled once (not a colour string per pixel).
  let inferno = null;
  function infernoTable() {
    inferno = inferno || Array.from({ length: 256 }, (_, i) => d3.rgb(d3.interpolateInferno(i / 255)));
    return inferno;
  }

  function luminance(p, i) {
    return 0.2126 * p[i] + 0.7152 * p[i + 1] + 0.0722 * p[i + 2];
  }

  class Viewer {
    constructor(root, data) {
      this.root = root;
      this.data = data;
      this.pixels = [];
      this.current = data.images.findIndex((im) => im.key !== "reference");
      if (this.current < 0) this.current = 0;
      this.exposure = 0;
      this.errorView = false;
      this.build();
    }

    build() {
      const { width, height } = this.data;
      this.root.innerHTML = "";
      this.root.tabIndex = 0;
      const bar = document.createElement("div");
      bar.className = "bar";
      this.buttons = this.data.images.map((image, i) => {
        const b = document.createElement("button");
        b.textContent = `${i + 1} ${image.label}`;
        b.addEventListener("click", () => this.show(i));
        bar.appendChild(b);
        return b;
      });
      const exposure = document.createElement("label");
      exposure.innerHTML = 'exposure <input type="range" min="-8" max="8" step="0.25" value="0">';
      this.slider = exposure.querySelector("input");
      this.slider.addEventListener("input", () => this.setExposure(+this.slider.value));
      const error = document.createElement("button");
      error.textContent = "e: relative error";
      error.addEventListener("click", () => this.toggleError());
      this.errorButton = error;
      bar.append(exposure, error);
      const panes = document.createElement("div");
      panes.className = "panes";
      this.canvases = [0, 1].map(() => {
        const pane = document.createElement("div");
        pane.className = "pane";
        const caption = document.createElement("div");
        caption.className = "caption";
        const frame = document.createElement("div");
        frame.className = "frame";
        const canvas = document.createElement("canvas");
        canvas.width = width;
        canvas.height = height;
        frame.appendChild(canvas);
        pane.append(caption, frame);
        panes.appendChild(pane);
        return { canvas, caption, frame };
      });
      const legend = document.createElement("div");
      legend.className = "legend";
      this.legend = legend;
      this.root.append(bar, panes, legend);
      // One zoom for both panes: each follows the other's transform.
      this.zooms = this.canvases.map((c) =>
        panzoom(c.canvas, { maxZoom: 64, minZoom: 0.5, smoothScroll: false, zoomDoubleClickSpeed: 1 }));
      this.zooms.forEach((zoom, i) => {
        const other = this.zooms[1 - i];
        zoom.on("transform", () => {
          if (this.syncing) return;
          this.syncing = true;
          const t = zoom.getTransform();
          other.zoomAbs(0, 0, t.scale);
          other.moveTo(t.x, t.y);
          this.syncing = false;
        });
      });
      this.root.addEventListener("keydown", (event) => this.key(event));
    }

    async decodeAll() {
      this.pixels = await Promise.all(this.data.images.map((image) => decode(image.data)));
      for (const [i, p] of this.pixels.entries()) {
        const expected = this.data.width * this.data.height * 3;
        if (p.length !== expected)
          throw new Error(`${this.data.id}: image ${i} has ${p.length} values, not ${expected}`);
      }
      status.decoded += this.pixels.length;
      this.draw();
    }

    key(event) {
      const n = this.data.images.length;
      if (event.key >= "1" && event.key <= "9" && +event.key <= n) this.show(+event.key - 1);
      else if (event.key === "ArrowRight") this.show((this.current + 1) % n);
      else if (event.key === "ArrowLeft") this.show((this.current + n - 1) % n);
      else if (event.key === "e") this.toggleError();
      else if (event.key === "+" || event.key === "=") this.setExposure(this.exposure + 0.5);
      else if (event.key === "-") this.setExposure(this.exposure - 0.5);
      else return;
      event.preventDefault();
    }

    show(i) {
      this.current = i;
      this.root.dataset.current = String(i);
      this.draw();
    }

    setExposure(stops) {
      this.exposure = Math.max(-8, Math.min(8, stops));
      this.slider.value = String(this.exposure);
      this.draw();
    }

    toggleError() {
      this.errorView = !this.errorView;
      this.draw();
    }

    tonemap(canvas, p) {
      const ctx = canvas.getContext("2d");
      const image = ctx.createImageData(this.data.width, this.data.height);
      const scale = 2 ** this.exposure;
      for (let i = 0, j = 0; i < p.length; i += 3, j += 4) {
        image.data[j] = srgb(p[i] * scale);
        image.data[j + 1] = srgb(p[i + 1] * scale);
        image.data[j + 2] = srgb(p[i + 2] * scale);
        image.data[j + 3] = 255;
      }
      ctx.putImageData(image, 0, 0);
    }

    // |L − L_ref| / L_ref per pixel, on a log scale from 10⁻³ to 10 (inferno); the reference's
    // mean luminance / 100 keeps black reference pixels from dividing by zero.
    errorMap(canvas, p, ref) {
      const ctx = canvas.getContext("2d");
      const image = ctx.createImageData(this.data.width, this.data.height);
      let mean = 0;
      for (let i = 0; i < ref.length; i += 3) mean += luminance(ref, i);
      const floor = Math.max(mean / (ref.length / 3) / 100, 1e-8);
      const colours = infernoTable();
      for (let i = 0, j = 0; i < p.length; i += 3, j += 4) {
        const r = luminance(ref, i);
        const rel = Math.abs(luminance(p, i) - r) / Math.max(r, floor);
        const t = Math.min(1, Math.max(0, (Math.log10(Math.max(rel, 1e-3)) + 3) / 4));
        const c = colours[Math.round(255 * t)];
        image.data[j] = c.r;
        image.data[j + 1] = c.g;
        image.data[j + 2] = c.b;
        image.data[j + 3] = 255;
      }
      ctx.putImageData(image, 0, 0);
    }

    draw() {
      if (!this.pixels.length) return;
      const images = this.data.images;
      const reference = images.findIndex((im) => im.key === "reference");
      const [left, right] = this.canvases;
      this.tonemap(left.canvas, this.pixels[this.current]);
      left.caption.textContent = `${this.current + 1} ${images[this.current].label}`;
      if (this.errorView && reference >= 0) {
        this.errorMap(right.canvas, this.pixels[this.current], this.pixels[reference]);
        right.caption.textContent = `relative error of ${images[this.current].label}`;
        this.legend.textContent = "relative error |L − L_ref| / L_ref: black 10⁻³ … yellow 10";
      } else {
        this.tonemap(right.canvas, this.pixels[Math.max(reference, 0)]);
        right.caption.textContent = images[Math.max(reference, 0)].label;
        this.legend.textContent = `exposure ${this.exposure >= 0 ? "+" : ""}${this.exposure} stops`;
      }
      this.buttons.forEach((b, i) => b.classList.toggle("on", i === this.current));
      this.errorButton.classList.toggle("on", this.errorView);
    }
  }

  function register(id, data) {
    status.registered += 1;
    const root = document.querySelector(`.viewer[data-figure="${id}"]`);
    if (!root) {
      status.errors.push(`${id}: no viewer element`);
      return;
    }
    const viewer = new Viewer(root, { id, ...data });
    viewers.set(id, viewer);
    if (wanted.has(id)) {
      viewer.show(wanted.get(id));
      wanted.delete(id);
    }
    viewer.decodeAll().catch((e) => status.errors.push(`${id}: ${e.message}`));
  }

  // Adds the figure's data script once (a <script> element: no fetch, so file:// works).
  function load(root) {
    if (root.dataset.loading) return;
    root.dataset.loading = "1";
    const script = document.createElement("script");
    script.src = root.dataset.src;
    script.onerror = () => status.errors.push(`${root.dataset.figure}: ${root.dataset.src} missing`);
    document.head.appendChild(script);
  }

  // A link to one image of a figure (a cell of the cross-paper matrix: data-figure, data-image):
  // its viewer shows that image, at once or when its data has loaded.
  const wanted = new Map();
  function showImage(id, index) {
    const viewer = viewers.get(id);
    if (viewer) {
      viewer.show(index);
      return;
    }
    wanted.set(id, index);
    const root = document.querySelector(`.viewer[data-figure="${id}"]`);
    if (root) load(root);
  }

  function loadAll() {
    document.querySelectorAll(".viewer").forEach(load);
  }

  function start() {
    document.addEventListener("click", (event) => {
      const link = event.target.closest("a[data-image]");
      if (link) showImage(link.dataset.figure, Number(link.dataset.image));
    });
    const observer = new IntersectionObserver((entries) => {
      for (const entry of entries) if (entry.isIntersecting) load(entry.target);
    }, { rootMargin: "400px" });
    document.querySelectorAll(".viewer").forEach((v) => observer.observe(v));
  }

  return { register, loadAll, start, status, viewers, showImage };
})();

document.addEventListener("DOMContentLoaded", ReportViewer.start);
