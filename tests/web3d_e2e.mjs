// The web viewer's 3D view end to end in headless Chromium (Debian's /usr/bin/chromium over CDP
// by playwright-core; WebGL through its software renderer, SwiftShader). Run by tests/it/web.rs:
//
//   node tests/web3d_e2e.mjs http://127.0.0.1:PORT OUT_DIR
//
// Creates a cube-phantom-3d session in the page, waits for its surface and frames, checks the
// tissue is drawn (a share of the canvas is not background), drives the needle in with the mouse
// (Ctrl-drag up: insert along the needle), checks the inserted depth grows and the picture
// changes, then turns the section plane on and checks the picture changes again; the drive is
// recorded (with the surface's displacements), downloaded and played back in the page: the
// recording's own surface, its first and last frames drawn differently, the depth at the end.
// Saves view3-before.png, view3-after.png, view3-section.png, page3.png, playback3-first.png and
// playback3-last.png in OUT_DIR and writes summary3.json.
import { mkdtempSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { CHROMIUM_ARGS, WEBGL_ARGS, chromium, executablePath, fail, scriptArgs } from "./browser.mjs";

const [base, outDir] = scriptArgs("web3d_e2e.mjs");
const userDataDir = mkdtempSync(join(tmpdir(), "needlesim-chromium-"));

const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath,
  headless: true,
  viewport: { width: 1240, height: 860 },
  args: [...CHROMIUM_ARGS, ...WEBGL_ARGS],
});
const errors = [];
const page = context.pages()[0] ?? (await context.newPage());

/** The share of the 3D canvas's pixels that are not the white background. */
const drawnShare = () =>
  page.evaluate(() => {
    const src = document.getElementById("view3");
    const c = document.createElement("canvas");
    c.width = src.width;
    c.height = src.height;
    const ctx = c.getContext("2d");
    ctx.drawImage(src, 0, 0);
    const px = ctx.getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < px.length; i += 4) if (px[i] < 245 || px[i + 1] < 245 || px[i + 2] < 245) n++;
    return n / (px.length / 4);
  });

/** Waits until the 3D view has drawn `more` more times (so a change has reached the canvas). */
async function draws(more) {
  const now = await page.evaluate(() => Number(document.body.dataset.view3Draws ?? 0));
  await drawnSince(now + more - 1);
}

const drawCount = () => page.evaluate(() => Number(document.body.dataset.view3Draws ?? 0));

/** Waits until the 3D view has drawn more than `count` times in all. */
async function drawnSince(count) {
  await page.waitForFunction((n) => Number(document.body.dataset.view3Draws ?? 0) > n, count, { timeout: 60000 });
}

try {
  page.on("pageerror", (e) => errors.push(`pageerror: ${e.message}`));
  page.on("console", (m) => {
    if (m.type() === "error") errors.push(`console: ${m.text()}`);
  });
  await page.goto(`${base}/`, { waitUntil: "load" });
  await page.waitForSelector("body[data-ready='1']", { timeout: 20000 });

  await page.selectOption("#example-select", "cube-phantom-3d");
  await page.click("#create");
  await page.waitForFunction(() => document.body.dataset.dim === "3" && Number(document.body.dataset.frames) >= 10, null, {
    timeout: 60000,
  });
  await draws(3);
  const view = page.locator("#view3");
  if (!(await view.isVisible())) fail("the 3D view is not shown for a 3D session");
  if (await page.locator("#view").isVisible()) fail("the 2D view is still shown for a 3D session");
  const share0 = await drawnShare();
  const before = await view.screenshot({ path: join(outDir, "view3-before.png") });
  const depth0 = await page.evaluate(() => Number(document.body.dataset.depthM));

  // Record the drive (the page asks for the displacement field).
  await page.click("#rec-start");
  await page.waitForFunction(() => document.getElementById("rec-select").value !== "", null, { timeout: 20000 });
  await page.waitForTimeout(300);

  // Drive: Ctrl-drag upwards 300 px = 30 mm along the needle (the tip starts 5 mm above the top).
  const box = await view.boundingBox();
  const x = box.x + box.width / 2, y = box.y + box.height * 0.8;
  await page.keyboard.down("Control");
  await page.mouse.move(x, y);
  await page.mouse.down();
  const steps = 30;
  for (let i = 1; i <= steps; i++) {
    await page.mouse.move(x, y - (300 * i) / steps);
    await page.waitForTimeout(40);
  }
  await page.mouse.up();
  await page.keyboard.up("Control");
  await page.waitForFunction((d0) => Number(document.body.dataset.depthM) > d0 + 0.015, depth0, { timeout: 20000 });
  await page.waitForTimeout(300);
  await draws(3);
  const depth1 = await page.evaluate(() => Number(document.body.dataset.depthM));
  const after = await view.screenshot({ path: join(outDir, "view3-after.png") });

  // The section plane cuts the tissue open.
  await page.check("#section-on");
  await draws(3);
  const section = await view.screenshot({ path: join(outDir, "view3-section.png") });
  await page.screenshot({ path: join(outDir, "page3.png") });

  // Stop, download and play the recording back: its first and last frames.
  await page.waitForTimeout(500);
  await page.click("#rec-stop");
  await page.waitForTimeout(1500);
  await page.click("#rec-load");
  await page.waitForFunction(() => document.body.dataset.state === "playback", null, { timeout: 30000 });
  const playbackFrames = await page.evaluate(() => Number(document.body.dataset.playbackFrames));
  const playbackFields = await page.evaluate(() => Number(document.body.dataset.playbackFields));
  const playbackDim = await page.evaluate(() => Number(document.body.dataset.dim));
  // (Frame 1: the slider starts at 0, and setting the value it has draws nothing new.)
  let drawn = await drawCount();
  await page.locator("#slider").fill("1");
  await drawnSince(drawn);
  const playbackDepth0 = await page.evaluate(() => Number(document.body.dataset.depthM));
  const first = await view.screenshot({ path: join(outDir, "playback3-first.png") });
  drawn = await drawCount();
  await page.locator("#slider").fill(String(playbackFrames - 1));
  await drawnSince(drawn);
  const playbackDepth1 = await page.evaluate(() => Number(document.body.dataset.depthM));
  const last = await view.screenshot({ path: join(outDir, "playback3-last.png") });

  const summary = {
    playbackFrames,
    playbackFields,
    playbackDim,
    playbackDepth0,
    playbackDepth1,
    playbackChanged: !first.equals(last),
    frames: await page.evaluate(() => Number(document.body.dataset.frames)),
    poses: await page.evaluate(() => Number(document.body.dataset.poses ?? 0)),
    drawnShare: share0,
    depth0,
    depth1,
    changedByInsertion: !before.equals(after),
    changedBySection: !after.equals(section),
    errors,
  };
  writeFileSync(join(outDir, "summary3.json"), JSON.stringify(summary, null, 2));
  console.log(JSON.stringify(summary));
  if (errors.length) fail(`the page reported errors: ${errors.join("; ")}`);
} catch (e) {
  console.error(`page errors: ${errors.join("; ") || "none"}`);
  await page.screenshot({ path: join(outDir, "page3-failed.png") }).catch(() => {});
  throw e;
} finally {
  await context.close();
  rmSync(userDataDir, { recursive: true, force: true });
}
