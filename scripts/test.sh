#!/usr/bin/env bash
# Installs what the tests need (Chromium, npm packages), builds, and runs every test tier.
set -euo pipefail
cd "$(dirname "$0")/.."

if [ -z "${PATHTRACE_CHROMIUM:-}" ] && [ ! -x /usr/bin/chromium ]; then
  echo "Installing Debian's chromium (needed by the browser tests and the CLI)..."
  if [ "$(id -u)" = 0 ]; then apt-get update && apt-get install -y chromium
  else sudo apt-get update && sudo apt-get install -y chromium; fi
fi

if [ ! -d node_modules ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  npm ci
fi

npm run typecheck
bash scripts/audit.sh
npm run build
npx vitest run --reporter=default --reporter=json --outputFile.json=test-output/vitest-report.json "$@"
