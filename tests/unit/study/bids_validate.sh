#!/usr/bin/env bash
# Validates a BIDS dataset with the BIDS validator (the `bids-validator` package from the npm
# registry, pinned: 1.15.0 is the newest release and runs on Debian 12's Node 18), installed on
# first use into PREFIX (under the build folder). Prints the validator's version, every error and
# warning, and a summary line "bids-validator VERSION: N errors, M warnings". Exits 0 only when
# the validator ran and found no error; an install that fails (no npm registry) fails loudly.
#
#   bids_validate.sh DATASET PREFIX
set -uo pipefail
dataset=$1
prefix=$(realpath -m "$2")
version=1.15.0
fail() { echo "bids_validate: FAILED: $*" >&2; exit 1; }
command -v node >/dev/null && command -v npm >/dev/null ||
  fail "node and npm are needed (config/setup.sh installs nodejs and npm)"
echo "bids_validate: node $(node --version), npm $(npm --version)"
package="$prefix/node_modules/bids-validator/package.json"
installed=$(node -p "require('$package').version" 2>/dev/null)
if [ "$installed" != "$version" ]; then
  echo "bids_validate: installing bids-validator@$version from the npm registry into $prefix"
  mkdir -p "$prefix" || fail "cannot create $prefix"
  npm install --prefix "$prefix" --no-audit --no-fund --no-save --loglevel=error \
    "bids-validator@$version" ||
    fail "npm could not install bids-validator@$version (is the npm registry reachable?)"
  installed=$(node -p "require('$package').version" 2>/dev/null) ||
    fail "bids-validator is not in $prefix after npm install"
fi
report=$(mktemp)
trap 'rm -f "$report"' EXIT
# The validator's own exit status says only "errors or not"; its JSON report says which.
"$prefix/node_modules/.bin/bids-validator" --json "$dataset" >"$report"
status=$?
node - "$report" "$installed" "$status" <<'JS' || exit 1
const fs = require('fs');
const [report, version, status] = process.argv.slice(2);
let result;
try {
  result = JSON.parse(fs.readFileSync(report, 'utf8'));
} catch (e) {
  console.error(`bids_validate: FAILED: the validator (exit ${status}) wrote no JSON report: ${e}`);
  console.error(fs.readFileSync(report, 'utf8').slice(0, 4000));
  process.exit(1);
}
const show = (kind, issues) => {
  for (const issue of issues) {
    console.log(`${kind} [${issue.code}] ${issue.key}: ${issue.reason}`);
    for (const f of (issue.files || []).slice(0, 5))
      if (f && f.file) console.log(`    ${f.file.relativePath}${f.reason ? ': ' + f.reason : ''}` +
                                   `${f.evidence ? ' (' + String(f.evidence).slice(0, 160) + ')' : ''}`);
  }
};
const errors = result.issues.errors || [], warnings = result.issues.warnings || [];
show('ERROR', errors);
show('WARNING', warnings);
const s = result.summary || {};
console.log(`bids-validator ${version}: ${errors.length} errors, ${warnings.length} warnings ` +
            `(${s.totalFiles} files, subjects ${JSON.stringify(s.subjects)}, sessions ` +
            `${JSON.stringify(s.sessions)}, tasks ${JSON.stringify(s.tasks)}, modalities ` +
            `${JSON.stringify(s.modalities)})`);
process.exit(errors.length === 0 && status === '0' ? 0 : 1);
JS
