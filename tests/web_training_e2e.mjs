// Training in the web viewer (issue 20), end to end in headless Chromium (Debian's
// /usr/bin/chromium over CDP by playwright-core from web/node_modules). Run by
// tests/it/training_live.rs:
//
//   node tests/web_training_e2e.mjs http://127.0.0.1:PORT OUT_DIR
//
// The trainee's page starts the biopsy-2d exercise ("Start exercise"), shows the live score, who
// is in control and the ultrasound slice; an observer's page (its link) shows the same; the
// trainee drags the needle in — the slice changes — and declares "Placed" — the score changes;
// the instructor's page (its link) takes control — the observer's page shows "instructor" — and
// hands it back. Saves slice-before.png, slice-after.png, training-observer.png (the observer's
// page with the instructor in control) and training-trainee.png in OUT_DIR, and summary-training.json.
import { createRequire } from "node:module";
import { mkdtempSync, rmSync, writeFileSync, mkdirSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";

const require = createRequire(new URL("../web/package.json", import.meta.url));
const { chromium } = require("playwright-core");

const [base, outDir] = process.argv.slice(2);
if (!base || !outDir) {
  console.error("usage: node tests/web_training_e2e.mjs BASE_URL OUT_DIR");
  process.exit(2);
}
mkdirSync(outDir, { recursive: true });
const executablePath = process.env.NEEDLESIM_CHROMIUM || "/usr/bin/chromium";
const userDataDir = mkdtempSync(join(tmpdir(), "needlesim-chromium-"));

function fail(msg) {
  throw new Error(msg);
}

const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath,
  headless: true,
  viewport: { width: 1240, height: 900 },
  args: [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--no-first-run",
    "--disable-quic",
    "--disable-sync",
  ],
});
const errors = [];
const watchErrors = (p, who) => {
  p.on("pageerror", (e) => errors.push(`${who} pageerror: ${e.message}`));
  p.on("console", (m) => {
    if (m.type() === "error") errors.push(`${who} console: ${m.text()}`);
  });
};
const data = (p, key) => p.evaluate((k) => document.body.dataset[k], key);
const trainee = context.pages()[0] ?? (await context.newPage());
let observer = null;
try {
  watchErrors(trainee, "trainee");
  await trainee.goto(`${base}/`, { waitUntil: "load" });
  await trainee.waitForSelector("body[data-ready='1']", { timeout: 20000 });
  await trainee.selectOption("#exercise-select", "biopsy-2d");
  await trainee.click("#create-exercise");
  await trainee.waitForFunction(() => document.body.dataset.exercise === "biopsy-2d", null, { timeout: 30000 });
  await trainee.waitForFunction(() => Number(document.body.dataset.frames) >= 10 && Number(document.body.dataset.ultrasoundFrames) >= 2, null, {
    timeout: 20000,
  });
  const links = await trainee.evaluate(() =>
    Object.fromEntries(["trainee", "instructor", "observer"].map((k) => [k, document.getElementById(`link-${k}`).href])),
  );
  if (!links.instructor.includes("instructor=")) fail(`the instructor's link carries no instructor token: ${links.instructor}`);
  const controller0 = await data(trainee, "controller");
  if (controller0 !== "trainee") fail(`in control at the start: ${controller0}`);
  const score0 = Number(await data(trainee, "score"));
  const slice = trainee.locator("#ultrasound");
  await trainee.waitForTimeout(300);
  const sliceBefore = await slice.screenshot({ path: join(outDir, "slice-before.png") });
  const tick0 = Number(await data(trainee, "ultrasoundTick"));

  // An observer follows the exercise through its link.
  observer = await context.newPage();
  watchErrors(observer, "observer");
  await observer.goto(links.observer, { waitUntil: "load" });
  await observer.waitForFunction(() => document.body.dataset.exercise === "biopsy-2d" && document.body.dataset.controller === "trainee", null, {
    timeout: 20000,
  });
  if (await observer.evaluate(() => !document.getElementById("ex-instructor").hidden)) fail("the observer's page shows the instructor's buttons");

  // The trainee drags the needle in along its axis.
  await trainee.bringToFront();
  const view = trainee.locator("#view");
  await view.scrollIntoViewIfNeeded();
  const depth0 = Number(await data(trainee, "depthM"));
  const box = await view.boundingBox();
  const x = box.x + box.width / 2;
  const y = box.y + box.height * 0.2;
  await trainee.mouse.move(x, y);
  await trainee.mouse.down();
  const steps = 60;
  const travel = box.height * 0.3;
  for (let i = 1; i <= steps; i++) {
    await trainee.mouse.move(x, y + (travel * i) / steps);
    await trainee.waitForTimeout(40);
  }
  await trainee.mouse.up();
  await trainee.waitForFunction((d0) => Number(document.body.dataset.depthM) > d0 + 0.01, depth0, { timeout: 15000 });
  await trainee.waitForFunction((t0) => Number(document.body.dataset.ultrasoundTick) > t0 + 500, tick0, { timeout: 15000 });
  await trainee.waitForTimeout(500);
  const depth1 = Number(await data(trainee, "depthM"));
  const sliceAfter = await slice.screenshot({ path: join(outDir, "slice-after.png") });
  if (sliceBefore.equals(sliceAfter)) fail("the ultrasound slice did not change as the needle advanced");

  // "Placed": the score changes (the accuracy part counts the placement).
  await trainee.click("#ex-place");
  await trainee.waitForFunction((s0) => Math.abs(Number(document.body.dataset.score) - s0) > 1e-6, score0, { timeout: 10000 });
  const score1 = Number(await data(trainee, "score"));
  await observer.waitForFunction((s) => Math.abs(Number(document.body.dataset.score) - s) < 5, score1, { timeout: 10000 });

  // The instructor takes control: every page shows it; then hands it back.
  const instructor = await context.newPage();
  watchErrors(instructor, "instructor");
  await instructor.goto(links.instructor, { waitUntil: "load" });
  await instructor.waitForFunction(() => document.body.dataset.exercise === "biopsy-2d", null, { timeout: 20000 });
  if (await instructor.evaluate(() => document.getElementById("ex-instructor").hidden)) fail("the instructor's page hides the instructor's buttons");
  await instructor.click("#ex-take");
  await observer.waitForFunction(() => document.body.dataset.controller === "instructor", null, { timeout: 10000 });
  await trainee.waitForFunction(() => document.body.dataset.controller === "instructor", null, { timeout: 10000 });
  await instructor.fill("#ex-marker-label", "look here");
  await instructor.click("#ex-add-marker");
  await observer.waitForFunction(() => /look here/.test(document.getElementById("ex-markers").textContent), null, { timeout: 10000 });
  await observer.bringToFront();
  await observer.waitForTimeout(300);
  await observer.screenshot({ path: join(outDir, "training-observer.png") });
  const controllerShown = await data(observer, "controller");
  await instructor.click("#ex-hand-back");
  await observer.waitForFunction(() => document.body.dataset.controller === "trainee", null, { timeout: 10000 });
  await trainee.bringToFront();
  await trainee.screenshot({ path: join(outDir, "training-trainee.png") });
  if (errors.length) fail(`errors in the pages: ${errors.join("; ")}`);

  const summary = {
    links,
    depth0,
    depth1,
    score0,
    score1,
    controllerShown,
    sliceChanged: true,
    ultrasoundFrames: Number(await data(trainee, "ultrasoundFrames")),
  };
  writeFileSync(join(outDir, "summary-training.json"), JSON.stringify(summary, null, 2));
  console.log(JSON.stringify(summary));
} catch (e) {
  console.error(`web training e2e failed: ${e.message}`);
  for (const [who, p] of [["trainee", trainee], ["observer", observer]]) {
    if (!p) continue;
    const st = await p
      .evaluate(() => ({ status: document.getElementById("status")?.textContent, data: { ...document.body.dataset } }))
      .catch(() => null);
    console.error(`${who} page state: ${JSON.stringify(st)}`);
  }
  await trainee.screenshot({ path: join(outDir, "failure-training.png") }).catch(() => {});
  if (errors.length) console.error(errors.join("\n"));
  process.exitCode = 1;
} finally {
  await context.close();
  rmSync(userDataDir, { recursive: true, force: true });
}
