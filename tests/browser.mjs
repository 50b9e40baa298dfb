// The headless Chromium of the page tests (tests/web_e2e.mjs, web3d_e2e.mjs,
// web_training_e2e.mjs): Debian's /usr/bin/chromium (or $NEEDLESIM_CHROMIUM) driven over CDP by
// playwright-core from web/node_modules (never a downloaded browser), with the flags it needs as
// root in a container, and the command line every such script takes.
import { createRequire } from "node:module";
import { mkdirSync } from "node:fs";

const require = createRequire(new URL("../web/package.json", import.meta.url));
export const { chromium } = require("playwright-core");

export const executablePath = process.env.NEEDLESIM_CHROMIUM || "/usr/bin/chromium";

/** Headless Chromium as root, quiet (no background traffic, no first-run work). */
export const CHROMIUM_ARGS = [
  "--headless",
  "--no-sandbox",
  "--disable-gpu",
  "--disable-background-networking",
  "--disable-component-update",
  "--no-first-run",
  "--disable-quic",
  "--disable-sync",
];

/** WebGL through the SwiftShader software renderer (the 3D view). */
export const WEBGL_ARGS = ["--use-angle=swiftshader", "--enable-unsafe-swiftshader"];

/** `node tests/SCRIPT BASE_URL OUT_DIR`: the two arguments (OUT_DIR created), or exit 2 with the usage. */
export function scriptArgs(script) {
  const [base, outDir] = process.argv.slice(2);
  if (!base || !outDir) {
    console.error(`usage: node tests/${script} BASE_URL OUT_DIR`);
    process.exit(2);
  }
  mkdirSync(outDir, { recursive: true });
  return [base, outDir];
}

export function fail(msg) {
  throw new Error(msg);
}
