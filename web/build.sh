#!/usr/bin/env bash
# Regenerates web/src/gen/ from proto/ (buf + protoc-gen-es, from npm) and rebuilds web/dist/
# (esbuild). Reproducible: pinned versions in package-lock.json, no timestamps or hashes in the
# output. Run `npm ci` in web/ first (this script does it when node_modules is missing).
set -euo pipefail
web="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$web"
if [ ! -x node_modules/.bin/esbuild ] || [ ! -x node_modules/.bin/buf ]; then
    npm ci --no-fund --no-audit
fi
node_modules/.bin/buf generate ../proto --template buf.gen.yaml
rm -rf dist
node_modules/.bin/esbuild src/app.ts --bundle --format=esm --target=es2022 --minify \
    --legal-comments=none --charset=utf8 --log-level=warning --outfile=dist/app.js
cp src/style.css dist/app.css
