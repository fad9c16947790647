// The results page in a real browser (ctest report_page; also by hand on the whole page):
//   node tests/report/test_page.cjs PAGE.html SCREENSHOT.png
// Debian's chromium, headless, driven by puppeteer-core (experiments/report/node_modules, or
// REPORT_MODULES). Fails unless the page loads from file:// without a console error or a
// failed request, every figure's images decode, and keys switch the compared image and the
// error view, and zooming one pane zooms the other. Keeps a screenshot of the first comparison.
"use strict";
const path = require("path");

const modules = process.env.REPORT_MODULES ||
    path.join(__dirname, "..", "..", "experiments", "report", "node_modules");
const puppeteer = require(path.join(modules, "puppeteer-core"));

function fail(message) {
  console.error(`FAIL: ${message}`);
  process.exitCode = 1;
}

async function main() {
  const [page_file, screenshot] = process.argv.slice(2);
  if (!page_file || !screenshot) throw new Error("usage: test_page.cjs PAGE.html SCREENSHOT.png");
  const browser = await puppeteer.launch({
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    headless: true,
    args: ["--no-sandbox", "--allow-file-access-from-files=false"],
  });
  try {
    const page = await browser.newPage();
    await page.setViewport({ width: 1400, height: 1000 });
    const problems = [];
    page.on("console", (m) => { if (m.type() === "error") problems.push(`console: ${m.text()}`); });
    page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
    page.on("requestfailed", (r) => problems.push(`request failed: ${r.url()}`));
    await page.goto("file://" + path.resolve(page_file), { waitUntil: "load" });

    const viewers = await page.$$eval(".viewer", (v) => v.length);
    if (viewers === 0) fail("the page has no image comparison");
    await page.evaluate(() => ReportViewer.loadAll());
    await page.waitForFunction(
        (n) => ReportViewer.status.registered + ReportViewer.status.errors.length >= n &&
               [...ReportViewer.viewers.values()].every((v) => v.pixels.length > 0) ||
               ReportViewer.status.errors.length > 0,
        { timeout: 120000 }, viewers);
    const status = await page.evaluate(() => ({
      registered: ReportViewer.status.registered,
      decoded: ReportViewer.status.decoded,
      errors: ReportViewer.status.errors,
      images: [...ReportViewer.viewers.values()].reduce((n, v) => n + v.data.images.length, 0),
    }));
    console.log(`${viewers} comparisons, ${status.registered} registered, ` +
                `${status.decoded} of ${status.images} images decoded`);
    if (status.registered !== viewers) fail(`${status.registered} of ${viewers} figures loaded`);
    if (status.decoded !== status.images || status.images === 0)
      fail(`${status.decoded} of ${status.images} images decoded`);
    for (const e of status.errors) fail(e);

    // Every canvas drew something other than black.
    const blank = await page.evaluate(() => [...document.querySelectorAll(".viewer canvas")]
        .filter((c) => !c.getContext("2d").getImageData(0, 0, c.width, c.height).data
            .some((value, i) => i % 4 !== 3 && value > 0)).length);
    if (blank) fail(`${blank} canvases are black`);

    // Keys: → steps to the next image, a digit chooses one, e shows the error view.
    const first = await page.$(".viewer");
    await first.focus();
    const current = () => page.evaluate(() => document.querySelector(".viewer").dataset.current);
    const caption = () => page.evaluate(
        () => document.querySelectorAll(".viewer .caption")[0].textContent);
    const before = await caption();
    await page.keyboard.press("ArrowRight");
    const after = await caption();
    if (after === before) fail(`→ did not switch the image (still "${after}")`);
    await page.keyboard.press("1");
    if ((await current()) !== "0") fail(`key 1 chose image ${await current()}, not 0`);
    await page.keyboard.press("e");
    const right = await page.evaluate(
        () => document.querySelectorAll(".viewer .caption")[1].textContent);
    if (!right.startsWith("relative error")) fail(`e did not show the error view ("${right}")`);
    await page.keyboard.press("ArrowRight");

    // Zoom in the left pane: the right pane follows (synchronised zoom and pan).
    const frame = await page.$(".viewer .frame");
    const box = await frame.boundingBox();
    await page.mouse.move(box.x + box.width / 3, box.y + box.height / 3);
    for (let i = 0; i < 4; ++i) await page.mouse.wheel({ deltaY: -240 });
    await new Promise((resolve) => setTimeout(resolve, 300));
    const transforms = await page.evaluate(() => [...document.querySelector(".viewer")
        .querySelectorAll("canvas")].map((c) => c.style.transform));
    if (!/matrix\(/.test(transforms[0]) || transforms[0].startsWith("matrix(1, 0, 0, 1, 0, 0)"))
      fail(`the wheel did not zoom the left pane ("${transforms[0]}")`);
    if (transforms[0] !== transforms[1])
      fail(`the panes' zooms differ: "${transforms[0]}" and "${transforms[1]}"`);

    // A cell of the cross-paper matrix (when the page has one) shows its technique's image in
    // its scene's comparison: the caption names the cell's column.
    const cells = await page.$$("table.matrix a[data-image]");
    for (const cell of cells.slice(-2)) {
      const { figure, image, column } = await cell.evaluate((a) => ({
        figure: a.dataset.figure, image: a.dataset.image,
        column: a.closest("table").rows[0].cells[a.closest("td").cellIndex].textContent }));
      await cell.click();
      const shown = await page.evaluate((id) => {
        const root = document.querySelector(`.viewer[data-figure="${id}"]`);
        return { current: root.dataset.current, caption: root.querySelector(".caption").textContent };
      }, figure);
      if (shown.current !== image) fail(`the ${column} cell showed image ${shown.current}, not ${image}`);
      if (!shown.caption.includes(`${column}, `)) fail(`the ${column} cell showed "${shown.caption}"`);
    }
    await first.screenshot({ path: screenshot });
    for (const p of problems) fail(p);
    if (!process.exitCode) console.log(`ok; screenshot ${screenshot}`);
  } finally {
    await browser.close();
  }
}

main().catch((e) => { fail(e.stack || String(e)); });
