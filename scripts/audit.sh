#!/usr/bin/env bash
# npm audit of the production dependencies: fails on high-severity findings.
# Where the registry's advisory endpoint cannot be reached (some sandboxes
# answer 405), says so and does not fail: there is nothing to judge.
set -uo pipefail
cd "$(dirname "$0")/.."
out=$(npm audit --omit=dev --audit-level=high 2>&1)
code=$?
if grep -qE "audit endpoint returned an error|ENOTFOUND|ECONNREFUSED|EAI_AGAIN" <<<"$out"; then
  echo "npm audit: the advisory endpoint is unreachable here; not checked"
  exit 0
fi
echo "$out" | tail -n 5
exit $code
