#!/usr/bin/env bash
# Regenerates web/src/gen/ from proto/ (buf + protoc-gen-es, from npm), type-checks web/src/
# (tsc --noEmit, strict: esbuild only strips types) and rebuilds web/dist/ (esbuild: app.js, and
# app.css from the CSS the sources import: uPlot's and src/style.css). Reproducible: pinned
# versions in package-lock.json, no timestamps or hashes in the output. Run `npm ci` in web/ first
# (this script does it when node_modules is missing).
set -euo pipefail
web="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$web"
if [ ! -x node_modules/.bin/esbuild ] || [ ! -x node_modules/.bin/buf ] || [ ! -x node_modules/.bin/tsc ]; then
    npm ci --no-fund --no-audit
fi
node_modules/.bin/buf generate ../proto --template buf.gen.yaml
node_modules/.bin/tsc --noEmit -p tsconfig.json
rm -rf dist
node_modules/.bin/esbuild src/main.ts --bundle --format=esm --target=es2022 --minify \
    --legal-comments=none --charset=utf8 --log-level=warning --outfile=dist/app.js
