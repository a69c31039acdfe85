#!/usr/bin/env bash
# Assembles the npm package m4d-player (web/package/package.json) in OUT/package: the
# WebAssembly decoder of build/web/module (scripts/build_web.sh builds it), the modules and
# TypeScript declarations of web/js and web/adapters, README.md and LICENSE; then packs it with
# `npm pack`, offline, into OUT/m4d-player-VERSION.tgz (written atomically). Export entries whose
# module is not in the tree are left out of the packed package.json (and said so).
#
#   scripts/pack_web.sh [--out DIR]      (default OUT: build/web)
set -euo pipefail
cd "$(dirname "$0")/.."
out=build/web
while [ $# -gt 0 ]; do
  case $1 in
    --out) out=${2:?--out needs a directory}; shift 2 ;;
    -h | --help) sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "pack_web: unknown argument $1" >&2; exit 2 ;;
  esac
done

module=build/web/module
for file in m4d.mjs m4d.d.mts m4d_wasm.mjs m4d_wasm.wasm; do
  if [ ! -f "$module/$file" ]; then
    echo "pack_web: no $module/$file: run scripts/build_web.sh" >&2
    exit 2
  fi
done

mkdir -p "$out"
stage=$(cd "$(mktemp -d "$out/.package.XXXXXX")" && pwd)
trap 'rm -rf "$stage"' EXIT
mkdir "$stage/package" "$stage/package/js" "$stage/package/adapters" "$stage/tgz"
package=$stage/package
cp "$module"/m4d.mjs "$module"/m4d.d.mts "$module"/m4d_wasm.mjs "$module"/m4d_wasm.wasm "$package/js/"
for file in web/js/*.mjs web/js/*.d.mts; do
  case $(basename "$file") in m4d.mjs | m4d.d.mts) ;; *) cp "$file" "$package/js/" ;; esac
done
for file in web/adapters/*.mjs web/adapters/*.d.mts; do
  if [ -f "$file" ]; then cp "$file" "$package/adapters/"; fi
done
cp web/package/README.md LICENSE "$package/"

# package.json: the SDK's version, and only the exports whose files are there.
node - "$package" sdk/include/m4d/m4d.h web/package/package.json <<'NODE'
const { existsSync, readFileSync, writeFileSync } = require('node:fs');
const { join } = require('node:path');
const [dir, header, source] = process.argv.slice(2);
const pkg = JSON.parse(readFileSync(source, 'utf8'));
const part = (name) => readFileSync(header, 'utf8').match(new RegExp(`#define M4D_VERSION_${name} (\\d+)`))[1];
const sdk = `${part('MAJOR')}.${part('MINOR')}.${part('PATCH')}`;
if (pkg.version !== sdk) {
  console.error(`pack_web: web/package/package.json says ${pkg.version}, the SDK is ${sdk}`);
  process.exit(1);
}
for (const [entry, target] of Object.entries(pkg.exports)) {
  const conditions = typeof target === 'string' ? { default: target } : { ...target };
  const main = conditions.default;
  for (const [condition, file] of Object.entries(conditions)) {
    if (file !== './package.json' && !existsSync(join(dir, file))) delete conditions[condition];
  }
  if (!conditions.default) {
    console.error(`pack_web: ${entry} left out (no ${main} yet)`);
    delete pkg.exports[entry];
  } else {
    pkg.exports[entry] = Object.keys(conditions).length === 1 ? conditions.default : conditions;
  }
}
writeFileSync(join(dir, 'package.json'), JSON.stringify(pkg, null, 2) + '\n');
NODE

name=$(cd "$package" && npm pack --offline --ignore-scripts --silent --pack-destination "$stage/tgz")
if [ -z "$name" ] || [ ! -f "$stage/tgz/$name" ]; then
  echo "pack_web: npm pack wrote no tarball" >&2
  exit 1
fi
mv "$stage/tgz/$name" "$out/$name"
rm -rf "$out/package"
mv "$package" "$out/package"
echo "$out/$name"
