// The web viewer end to end in headless Chromium (Debian's /usr/bin/chromium, driven over CDP by
// playwright-core from web/node_modules; never a downloaded browser). Run by tests/it/web.rs:
//
//   node tests/web_e2e.mjs http://127.0.0.1:PORT OUT_DIR
//
// Loads the page, creates a paper-phantom session in it, waits for frames, starts a recording,
// drags the needle into the tissue with the mouse, checks that the inserted depth grows and the
// tissue drawing and both force plots (uPlot: series named in their legends, its CSS applied)
// change, stops the recording and plays it back; then creates a bevel-tip session and flips its
// bevel with the "Flip bevel" button. Saves view-before.png, bevel-flipped.png, view-after.png,
// plots.png, page.png and playback.png in OUT_DIR and prints a JSON summary.
import { mkdtempSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { CHROMIUM_ARGS, chromium, executablePath, fail, scriptArgs } from "./browser.mjs";

const [base, outDir] = scriptArgs("web_e2e.mjs");
const userDataDir = mkdtempSync(join(tmpdir(), "needlesim-chromium-"));

const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath,
  headless: true,
  viewport: { width: 1240, height: 860 },
  args: CHROMIUM_ARGS,
});
const errors = [];
const page = context.pages()[0] ?? (await context.newPage());
try {
  page.on("pageerror", (e) => errors.push(`pageerror: ${e.message}`));
  page.on("console", (m) => {
    if (m.type() === "error") errors.push(`console: ${m.text()}`);
  });
  await page.goto(`${base}/`, { waitUntil: "load" });
  await page.waitForSelector("body[data-ready='1']", { timeout: 20000 });

  // Create a session from the paper-phantom example, in the page.
  await page.selectOption("#example-select", "paper-phantom");
  await page.click("#create");
  await page.waitForFunction(() => Number(document.body.dataset.frames) >= 10, null, { timeout: 20000 });
  const session = await page.evaluate(() => document.body.dataset.session);
  const depth0 = await page.evaluate(() => Number(document.body.dataset.depthM));
  const view = page.locator("#view");
  await page.waitForTimeout(300);
  const before = await view.screenshot({ path: join(outDir, "view-before.png") });
  // The force plots (uPlot, its CSS bundled into dist/app.css): both charts name their series.
  const plots = await page.evaluate(() =>
    ["plot-time", "plot-depth"].map((id) => {
      const el = document.getElementById(id);
      const over = el.querySelector(".u-over");
      return {
        id,
        canvases: el.querySelectorAll("canvas").length,
        series: [...el.querySelectorAll(".u-legend .u-label")].map((l) => l.textContent),
        cssLoaded: over !== null && getComputedStyle(over).position === "absolute",
      };
    }),
  );
  for (const p of plots) {
    if (p.canvases < 1) fail(`#${p.id} holds no chart canvas`);
    if (!p.cssLoaded) fail(`#${p.id}: uPlot's CSS is not applied (dist/app.css)`);
    const want = ["axial (N)", "lateral (N)", "torque (mN·m)"];
    if (JSON.stringify(p.series) !== JSON.stringify(want)) fail(`#${p.id} legend ${JSON.stringify(p.series)}, not ${JSON.stringify(want)}`);
  }
  const plotTime = page.locator("#plot-time");
  const plotDepth = page.locator("#plot-depth");
  const [timeBefore, depthBefore] = [await plotTime.screenshot(), await plotDepth.screenshot()];

  await page.click("#rec-start");
  await page.waitForFunction(() => /recording to/.test(document.getElementById("status").textContent), null, { timeout: 10000 });

  // Drag the needle down (into the tissue) along its axis, in small steps, as a hand would.
  await view.scrollIntoViewIfNeeded();
  const box = await view.boundingBox();
  const x = box.x + box.width / 2;
  const y = box.y + box.height * 0.2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  const steps = 40;
  const travel = box.height * 0.12;
  for (let i = 1; i <= steps; i++) {
    await page.mouse.move(x, y + (travel * i) / steps);
    await page.waitForTimeout(40);
    // Regression (the CI run of issue 15's stop): the layout shifts mid-drag (here a 40 px row
    // added to the header, as when the session list refills and the header wraps); the drag
    // must still follow the mouse's travel, not the canvas's new place on the page.
    if (i === steps / 2) {
      await page.evaluate(() => {
        const row = document.createElement("div");
        row.id = "layout-shift";
        row.style.cssText = "flex-basis: 100%; height: 40px";
        document.querySelector("header").appendChild(row);
      });
    }
  }
  await page.mouse.up();
  await page.evaluate(() => document.getElementById("layout-shift")?.remove());
  await page.waitForFunction((d0) => Number(document.body.dataset.depthM) > d0 + 0.01, depth0, { timeout: 15000 });
  await page.waitForTimeout(800);
  const depth1 = await page.evaluate(() => Number(document.body.dataset.depthM));
  const poses = await page.evaluate(() => Number(document.body.dataset.poses || 0));
  const frames = await page.evaluate(() => Number(document.body.dataset.frames));
  const after = await view.screenshot({ path: join(outDir, "view-after.png") });
  await page.screenshot({ path: join(outDir, "page.png") });
  if (before.equals(after)) fail("the tissue view did not change as the needle advanced");
  await page.locator("#side").screenshot({ path: join(outDir, "plots.png") });
  if (timeBefore.equals(await plotTime.screenshot())) fail("the force–time plot did not change as the needle advanced");
  if (depthBefore.equals(await plotDepth.screenshot())) fail("the force–depth plot did not change as the needle advanced");

  // Stop the recording and play it back from the MCAP file, parsed in the page.
  await page.click("#rec-stop");
  await page.waitForFunction(() => /recorded/.test(document.getElementById("status").textContent), null, { timeout: 10000 });
  const recording = await page.evaluate(() => document.getElementById("rec-select").value);
  if (!recording.startsWith(`${session}-`)) fail(`the page selected the recording ${recording}, not the new one of ${session}`);
  await page.click("#rec-load");
  await page.waitForFunction(() => document.body.dataset.state === "playback", null, { timeout: 20000 });
  const playbackFrames = await page.evaluate(() => Number(document.body.dataset.playbackFrames));
  const last = playbackFrames - 1;
  await page.locator("#slider").fill(String(last));
  await page.waitForTimeout(200);
  const playbackDepth = await page.evaluate(() => Number(document.body.dataset.depthM));
  await page.screenshot({ path: join(outDir, "playback.png") });
  if (!(playbackFrames > 10)) fail(`the recording played back ${playbackFrames} frames`);
  if (!(playbackDepth > depth0 + 0.005)) fail(`the played-back depth at the end is ${playbackDepth} m`);

  // Issue 8: a bevel-tip session; the "Flip bevel" button turns the needle about its axis.
  await page.selectOption("#example-select", "bevel-tip");
  await page.click("#create");
  await page.waitForFunction(() => document.body.dataset.bevelSide === "1", null, { timeout: 20000 });
  await page.click("#flip-bevel");
  await page.waitForFunction(() => document.body.dataset.bevelSide === "-1", null, { timeout: 10000 });
  await view.screenshot({ path: join(outDir, "bevel-flipped.png") });
  if (errors.length) fail(`errors in the page: ${errors.join("; ")}`);

  const summary = { session, frames, poses, depth0, depth1, playbackFrames, playbackDepth, bevelFlipped: true, plotsChanged: true };
  writeFileSync(join(outDir, "summary.json"), JSON.stringify(summary, null, 2));
  console.log(JSON.stringify(summary));
} catch (e) {
  console.error(`web e2e failed: ${e.message}`);
  const state = await page
    .evaluate(() => ({ status: document.getElementById("status")?.textContent, data: { ...document.body.dataset } }))
    .catch(() => null);
  console.error(`page state: ${JSON.stringify(state)}`);
  await page.screenshot({ path: join(outDir, "failure.png") }).catch(() => {});
  if (errors.length) console.error(errors.join("\n"));
  process.exitCode = 1;
} finally {
  await context.close();
  rmSync(userDataDir, { recursive: true, force: true });
}
