// Loads the lab page in headless Chromium, runs every panel's check and prints `name fingerprint`
// lines (compared with the native build's by scripts/browser.sh), the costs as a table on
// stderr and in <out>/costs.json, and a screenshot of each panel, live (the cloth while
// dragged), in <out>/<panel>.png.
// A page error fails it. Usage: node web/check.mjs <url> <out>
import { writeFileSync } from "node:fs";
import { chromium } from "playwright-core";

const [url, out] = process.argv.slice(2);
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  // This machine's network is closed: no background fetches, no component updates.
  args: [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
  ],
});
const failures = [];
try {
  const page = await browser.newPage({ viewport: { width: 1360, height: 1700 } });
  page.on("pageerror", (error) => failures.push(`page error: ${error.message}`));
  page.on("console", (message) => {
    if (message.type() === "error") failures.push(`console error: ${message.text()}`);
  });
  await page.goto(`${url}?check`);
  await page.waitForFunction(() => window.labCheck, null, { timeout: 120_000 });
  const report = await page.evaluate(() => window.labCheck);
  failures.push(...report.errors);
  for (const r of report.results) console.log(`${r.panel} ${r.fingerprint}`);
  for (const r of report.results) {
    console.error(
      `${r.panel.padEnd(10)} ${r.usPerStep.toFixed(1).padStart(8)} µs/step ` +
        `${r.stepsPerFrame.toFixed(2).padStart(6)} steps/frame ${r.msPerFrame.toFixed(3).padStart(7)} ms/frame`,
    );
  }
  writeFileSync(`${out}/costs.json`, JSON.stringify(report.results, null, 2) + "\n");
  // The live page, a few seconds in, one screenshot a panel.
  await page.goto(url);
  await page.waitForTimeout(8000);
  for (const id of ["spring", "pendulum", "gray_scott", "dam_break", "mpm"]) {
    await page.locator(`#${id}`).screenshot({ path: `${out}/${id}.png` });
  }
  // Drag the implicit cloth's free corner, hanging at about (1, −1) on screen (web/page.js
  // maps [−0.15, 1.55] × [−1.3, 0.45] m onto each half's 300 × 300 pixels), up and in.
  const box = await page.locator("#cloth canvas").boundingBox();
  const scale = box.width / 640;
  const pixel = (x, y) => [
    box.x + scale * (325 + ((x + 0.15) / 1.7) * 300),
    box.y + scale * (10 + ((0.45 - y) / 1.75) * 300),
  ];
  await page.mouse.move(...pixel(1.0, -1.0));
  await page.mouse.down();
  await page.mouse.move(...pixel(0.75, -0.45), { steps: 30 });
  await page.waitForTimeout(300);
  await page.locator("#cloth").screenshot({ path: `${out}/cloth.png` });
  await page.mouse.up();
  const stopped = await page.evaluate(() => window.labErrors);
  failures.push(...stopped);
} finally {
  await browser.close();
}
if (failures.length > 0) {
  console.error(failures.join("\n"));
  process.exit(1);
}
