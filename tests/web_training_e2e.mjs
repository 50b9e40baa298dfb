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
import { writeFileSync } from "node:fs";
import { join } from "node:path";
import { CHROMIUM_ARGS, chromium, executablePath, fail, scriptArgs } from "./browser.mjs";

const [base, outDir] = scriptArgs("web_training_e2e.mjs");
const t0 = Date.now();
const step = (what) => console.log(`[${((Date.now() - t0) / 1000).toFixed(1)} s] ${what}`);

// One browser, a context per person (trainee, observer, instructor): each its own cookies and
// connection pool, as three people's browsers would be.
const browser = await chromium.launch({
  executablePath,
  headless: true,
  args: CHROMIUM_ARGS,
});
// Generous waits: the machines these run on are shared and often loaded (a load of 20 on 2
// cores makes a page load take half a minute); the checks are on what happens, not how fast.
const WAIT_MS = 90000;
const newPage = async () => {
  const p = await (await browser.newContext({ viewport: { width: 1240, height: 900 } })).newPage();
  p.setDefaultTimeout(WAIT_MS);
  return p;
};
const errors = [];
const watchErrors = (p, who) => {
  p.on("pageerror", (e) => errors.push(`${who} pageerror: ${e.message}`));
  p.on("console", (m) => {
    if (m.type() === "error") errors.push(`${who} console: ${m.text()}`);
  });
};
const data = (p, key) => p.evaluate((k) => document.body.dataset[k], key);
const trainee = await newPage();
let observer = null;
try {
  watchErrors(trainee, "trainee");
  await trainee.goto(`${base}/`, { waitUntil: "load" });
  await trainee.waitForSelector("body[data-ready='1']", { timeout: WAIT_MS });
  await trainee.selectOption("#exercise-select", "biopsy-2d");
  step("the trainee starts the exercise");
  await trainee.click("#create-exercise");
  await trainee.waitForFunction(() => document.body.dataset.exercise === "biopsy-2d", null, { timeout: WAIT_MS });
  await trainee.waitForFunction(() => Number(document.body.dataset.frames) >= 10 && Number(document.body.dataset.ultrasoundFrames) >= 2, null, {
    timeout: WAIT_MS,
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
  step("the observer opens its link");
  observer = await newPage();
  watchErrors(observer, "observer");
  await observer.goto(links.observer, { waitUntil: "load" });
  await observer.waitForFunction(() => document.body.dataset.exercise === "biopsy-2d" && document.body.dataset.controller === "trainee", null, {
    timeout: WAIT_MS,
  });
  if (await observer.evaluate(() => document.getElementById("ex-instructor").offsetParent !== null)) fail("the observer's page shows the instructor's buttons");

  // The trainee drags the needle in along its axis.
  step("the trainee drags the needle in");
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
  await trainee.waitForFunction((d0) => Number(document.body.dataset.depthM) > d0 + 0.01, depth0, { timeout: WAIT_MS });
  await trainee.waitForFunction((t0) => Number(document.body.dataset.ultrasoundTick) > t0 + 500, tick0, { timeout: WAIT_MS });
  await trainee.waitForTimeout(500);
  const depth1 = Number(await data(trainee, "depthM"));
  const sliceAfter = await slice.screenshot({ path: join(outDir, "slice-after.png") });
  if (sliceBefore.equals(sliceAfter)) fail("the ultrasound slice did not change as the needle advanced");

  // "Placed": the score changes (the accuracy part counts the placement).
  step("the trainee declares placed");
  await trainee.click("#ex-place");
  await trainee.waitForFunction((s0) => Math.abs(Number(document.body.dataset.score) - s0) > 1e-6, score0, { timeout: WAIT_MS });
  await trainee.waitForFunction(() => /biopsy: [0-9.]+ mm/.test(document.getElementById("ex-targets").textContent), null, { timeout: WAIT_MS });
  const score1 = Number(await data(trainee, "score"));
  const placed = await trainee.evaluate(() => document.getElementById("ex-targets").textContent);
  await observer.waitForFunction((s) => Math.abs(Number(document.body.dataset.score) - s) < 5, score1, { timeout: WAIT_MS });

  // The instructor takes control: every page shows it; then hands it back.
  step("the instructor takes control");
  const instructor = await newPage();
  watchErrors(instructor, "instructor");
  await instructor.goto(links.instructor, { waitUntil: "load" });
  await instructor.waitForFunction(() => document.body.dataset.exercise === "biopsy-2d", null, { timeout: WAIT_MS });
  if (await instructor.evaluate(() => document.getElementById("ex-instructor").offsetParent === null)) fail("the instructor's page hides the instructor's buttons");
  await instructor.click("#ex-take");
  await observer.waitForFunction(() => document.body.dataset.controller === "instructor", null, { timeout: WAIT_MS });
  await trainee.waitForFunction(() => document.body.dataset.controller === "instructor", null, { timeout: WAIT_MS });
  await instructor.fill("#ex-marker-label", "look here");
  await instructor.click("#ex-add-marker");
  await observer.waitForFunction(() => /look here/.test(document.getElementById("ex-markers").textContent), null, { timeout: WAIT_MS });
  await observer.bringToFront();
  await observer.waitForTimeout(300);
  await observer.screenshot({ path: join(outDir, "training-observer.png") });
  const controllerShown = await data(observer, "controller");
  await instructor.click("#ex-hand-back");
  await observer.waitForFunction(() => document.body.dataset.controller === "trainee", null, { timeout: WAIT_MS });
  await trainee.bringToFront();
  await trainee.screenshot({ path: join(outDir, "training-trainee.png") });
  if (errors.length) fail(`errors in the pages: ${errors.join("; ")}`);

  const summary = {
    links,
    depth0,
    depth1,
    score0,
    score1,
    placed,
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
  await browser.close();
}
